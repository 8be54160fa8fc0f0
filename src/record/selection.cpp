// Record selection to a target spectrum (see selection.hpp).
#include "pcrf/record/selection.hpp"
#include "pcrf/byte_order_mark.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <random>

#include "pcrf/number_text.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

using Matrix = std::vector<std::vector<double>>;  // [record][period]

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  for (char c : line) {
    if (c == ',') fields.push_back(std::move(field)), field.clear();
    else if (c != '\r' && c != ' ' && c != '\t') field += c;
  }
  fields.push_back(std::move(field));
  return fields;
}

std::optional<double> number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& key, const std::string& problem) {
  throw UserError(Where{{key}, file, line}, problem);
}

// ---- statistics of a set ----------------------------------------------------------------

struct SetStats {
  std::vector<double> mean, sigma, skew;
};

SetStats stats_of(const Matrix& set, bool skewness) {
  const std::size_t n = set.size(), p = set.front().size();
  SetStats s{std::vector<double>(p, 0.0), std::vector<double>(p, 0.0), std::vector<double>(p, 0.0)};
  for (std::size_t j = 0; j < p; ++j) {
    double sum = 0.0;
    for (const auto& r : set) sum += r[j];
    const double m = sum / static_cast<double>(n);
    double m2 = 0.0, m3 = 0.0;
    for (const auto& r : set) m2 += (r[j] - m) * (r[j] - m), m3 += std::pow(r[j] - m, 3);
    m2 /= static_cast<double>(n), m3 /= static_cast<double>(n);
    s.mean[j] = m;
    s.sigma[j] = std::sqrt(m2);
    if (skewness) s.skew[j] = m2 > 0.0 ? m3 / std::pow(m2, 1.5) : 0.0;
  }
  return s;
}

double deviation(const SetStats& s, const SelectionTarget& t, const SelectionSettings& w, bool skewness) {
  double total = 0.0;
  for (std::size_t j = 0; j < t.periods_s.size(); ++j) {
    const double sigma_error = s.sigma[j] - t.sigma_ln_sa[j];
    const double sigma_term = !w.relative_sigma ? sigma_error * sigma_error
                              : t.sigma_ln_sa[j] > 0.0 ? std::pow(sigma_error / t.sigma_ln_sa[j], 2)
                                                       : 0.0;  // σ = 0: the conditioning period, fixed by the scales
    total += w.w_mean * std::pow(s.mean[j] - t.mean_ln_sa[j], 2) + w.w_sigma * sigma_term;
    if (skewness) total += w.w_skew * s.skew[j] * s.skew[j];
  }
  return total;
}

/// Lower factor A of the covariance (Σ = A Aᵀ), from ρ's eigen-decomposition with negative
/// eigenvalues set to 0 (a model correlation matrix can be slightly indefinite).
Eigen::MatrixXd covariance_factor(const SelectionTarget& t) {
  const auto p = static_cast<Eigen::Index>(t.periods_s.size());
  Eigen::MatrixXd rho(p, p);
  for (Eigen::Index i = 0; i < p; ++i)
    for (Eigen::Index j = 0; j < p; ++j)
      rho(i, j) = t.correlation.empty() ? baker_jayaram_correlation(t.periods_s[static_cast<std::size_t>(i)], t.periods_s[static_cast<std::size_t>(j)])
                                        : t.correlation[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(rho);
  const Eigen::VectorXd root = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  Eigen::MatrixXd a = eig.eigenvectors() * root.asDiagonal();
  for (Eigen::Index i = 0; i < p; ++i) a.row(i) *= t.sigma_ln_sa[static_cast<std::size_t>(i)];
  return a;
}

/// Step 1: `trials` simulated sets of N spectra (ln Sa), best first by the deviation of their
/// mean, σ and skewness from the target's (a stable sort: ties keep the order drawn).
std::vector<Matrix> simulated_sets(const SelectionTarget& t, const SelectionSettings& w) {
  const Eigen::MatrixXd a = covariance_factor(t);
  const auto p = static_cast<Eigen::Index>(t.periods_s.size());
  std::mt19937_64 rng(w.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<std::pair<double, Matrix>> sets;
  for (int trial = 0; trial < w.trials; ++trial) {
    Matrix set(w.count, std::vector<double>(t.periods_s.size()));
    for (auto& row : set) {
      Eigen::VectorXd z(p);
      for (Eigen::Index i = 0; i < p; ++i) z(i) = normal(rng);
      const Eigen::VectorXd x = a * z;
      for (Eigen::Index i = 0; i < p; ++i) row[static_cast<std::size_t>(i)] = t.mean_ln_sa[static_cast<std::size_t>(i)] + x(i);
    }
    const double d = deviation(stats_of(set, true), t, w, true);
    sets.emplace_back(d, std::move(set));
  }
  std::stable_sort(sets.begin(), sets.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Matrix> out;
  for (auto& entry : sets) out.push_back(std::move(entry.second));
  return out;
}

/// The library's ln Sa at the target's periods, linear in (ln T, ln Sa) between grid points.
std::vector<double> ln_sa_at(const LibraryEntry& e, const std::vector<double>& grid, const std::vector<double>& periods) {
  std::vector<double> out;
  for (double t : periods) {
    const auto hi = static_cast<std::size_t>(std::lower_bound(grid.begin(), grid.end(), t) - grid.begin());
    if (grid[hi] == t) {
      out.push_back(std::log(e.sa_g[hi]));
      continue;
    }
    const std::size_t lo = hi - 1;
    const double f = (std::log(t) - std::log(grid[lo])) / (std::log(grid[hi]) - std::log(grid[lo]));
    out.push_back((1.0 - f) * std::log(e.sa_g[lo]) + f * std::log(e.sa_g[hi]));
  }
  return out;
}

/// The conditioning period's index: the first with σ = 0 (none: the size).
std::size_t conditioning_index(const SelectionTarget& t) {
  for (std::size_t j = 0; j < t.sigma_ln_sa.size(); ++j)
    if (t.sigma_ln_sa[j] == 0.0) return j;
  return t.sigma_ln_sa.size();
}

bool allowed(double s, const SelectionSettings& w) { return s >= w.scale_min && s <= w.scale_max; }

std::vector<double> shifted(const std::vector<double>& ln_sa, double ln_s) {
  std::vector<double> out(ln_sa);
  for (double& x : out) x += ln_s;
  return out;
}

}  // namespace

double baker_jayaram_correlation(double t1_s, double t2_s) {
  const double t_min = std::min(t1_s, t2_s), t_max = std::max(t1_s, t2_s);
  const double c1 = 1.0 - std::cos(std::numbers::pi / 2.0 - 0.366 * std::log(t_max / std::max(t_min, 0.109)));
  const double c2 = t_max < 0.2 ? 1.0 - 0.105 * (1.0 - 1.0 / (1.0 + std::exp(100.0 * t_max - 5.0))) * (t_max - t_min) / (t_max - 0.0099) : 0.0;
  const double c3 = t_max < 0.109 ? c2 : c1;
  const double c4 = c1 + 0.5 * (std::sqrt(c3) - c3) * (1.0 + std::cos(std::numbers::pi * t_min / 0.109));
  if (t_max < 0.109) return c2;
  if (t_min > 0.109) return c1;
  if (t_max < 0.2) return std::min(c2, c4);
  return c4;
}

SelectionTarget read_selection_target(std::istream& in, const std::string& file) {
  SelectionTarget t;
  t.file = file;
  std::vector<std::string> header;
  std::map<std::string, std::size_t> column;
  std::vector<std::size_t> rho_columns;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (n == 1) line = std::string(without_byte_order_mark(line));  // a spreadsheet's "CSV UTF-8"
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    const std::vector<std::string> fields = split_fields(line);
    if (header.empty()) {
      header = fields;
      for (std::size_t c = 0; c < header.size(); ++c) {
        column[header[c]] = c;
        if (header[c].rfind("rho_", 0) == 0) rho_columns.push_back(c);
      }
      for (const char* key : {"period_s", "mean_ln_sa", "sigma_ln_sa"})
        if (!column.count(key)) fail(file, n, key, "the target has no column '" + std::string(key) + "' (header: period_s,mean_ln_sa,sigma_ln_sa[,rho_<T>s…])");
      continue;
    }
    if (fields.size() != header.size())
      fail(file, n, "row", "has " + std::to_string(fields.size()) + " fields, the header " + std::to_string(header.size()));
    auto value = [&](std::size_t c) {
      const auto v = number(fields[c]);
      if (!v) fail(file, n, header[c], "'" + fields[c] + "' is not a finite number");
      return *v;
    };
    const double period = value(column["period_s"]), mean = value(column["mean_ln_sa"]), sigma = value(column["sigma_ln_sa"]);
    if (!(period > 0.0)) fail(file, n, "period_s", "must be positive, not " + number_text(period));
    if (!t.periods_s.empty() && period <= t.periods_s.back())
      fail(file, n, "period_s", "periods must increase (" + number_text(period) + " s after " + number_text(t.periods_s.back()) + " s)");
    if (sigma < 0.0) fail(file, n, "sigma_ln_sa", "must not be negative, not " + number_text(sigma));
    t.periods_s.push_back(period);
    t.mean_ln_sa.push_back(mean);
    t.sigma_ln_sa.push_back(sigma);
    t.row_lines.push_back(n);
    if (!rho_columns.empty()) {
      std::vector<double> row;
      for (std::size_t c : rho_columns) {
        const double r = value(c);
        if (r < -1.0 || r > 1.0) fail(file, n, header[c], "a correlation must lie in [-1, 1], not " + number_text(r));
        row.push_back(r);
      }
      t.correlation.push_back(std::move(row));
    }
  }
  if (t.periods_s.empty()) fail(file, n, "period_s", "the target has no periods");
  if (!t.correlation.empty()) {
    if (rho_columns.size() != t.periods_s.size())
      fail(file, t.row_lines.front(), header[rho_columns.front()],
           "the correlation needs one rho_ column per period: " + std::to_string(rho_columns.size()) + " for " +
               std::to_string(t.periods_s.size()) + " periods");
    for (std::size_t i = 0; i < t.periods_s.size(); ++i)
      for (std::size_t j = 0; j < t.periods_s.size(); ++j) {
        const std::string& key = header[rho_columns[j]];
        if (i == j && std::fabs(t.correlation[i][j] - 1.0) > 1e-9) fail(file, t.row_lines[i], key, "the correlation of a period with itself must be 1");
        if (std::fabs(t.correlation[i][j] - t.correlation[j][i]) > 1e-9) fail(file, t.row_lines[i], key, "the correlation must be symmetric");
      }
  }
  return t;
}

SelectionResult select_records(const SelectionTarget& target, const SpectraTable& table, const SelectionSettings& w) {
  if (w.count < 2) throw UserError("count", "select at least 2 records", {"count"});
  if (!(w.scale_min > 0.0 && w.scale_min <= w.scale_max && std::isfinite(w.scale_max)))
    throw UserError("scale_min", "scale limits must satisfy 0 < min ≤ max", {"scale_min"});
  if (w.trials < 1 || w.trials > 100000) throw UserError("trials", "must be 1 to 100000", {"trials"});
  if (!(w.w_mean >= 0.0 && w.w_sigma >= 0.0 && w.w_mean + w.w_sigma > 0.0 && std::isfinite(w.w_mean + w.w_sigma)))
    throw UserError("w_mean", "the weights must be finite, not negative, and not both 0", {"w_mean"});
  if (w.loops < 0 || w.loops > 1000) throw UserError("loops", "must be 0 to 1000", {"loops"});
  if (w.starts < 1 || w.starts > 100000) throw UserError("starts", "must be 1 to 100000", {"starts"});
  if (w.kind != "rotd50" && w.kind != "component") throw UserError("kind", "'" + w.kind + "' is not rotd50 or component", {"kind"});
  const auto& grid = table.periods_s;
  for (std::size_t j = 0; j < target.periods_s.size(); ++j) {
    const double t = target.periods_s[j];
    if (t < grid.front() * (1 - 1e-12) || t > grid.back() * (1 + 1e-12))
      fail(target.file, j < target.row_lines.size() ? target.row_lines[j] : 0, "period_s",
           number_text(t) + " s is outside the library's periods (" + number_text(grid.front()) + " s to " +
               number_text(grid.back()) + " s): compute the library on a grid that covers it");
  }
  std::vector<double> periods = target.periods_s;
  for (double& t : periods) t = std::clamp(t, grid.front(), grid.back());
  // The library entries of the kind asked for, at the target's periods.
  std::vector<std::size_t> ids;
  Matrix lib;
  for (std::size_t e = 0; e < table.entries.size(); ++e)
    if (table.entries[e].kind == w.kind) ids.push_back(e), lib.push_back(ln_sa_at(table.entries[e], grid, periods));
  const std::size_t cond = conditioning_index(target);
  // Conditional scaling: every entry's factor is fixed.
  std::vector<double> fixed_ln_s(lib.size(), 0.0);
  if (cond < periods.size())
    for (std::size_t k = 0; k < lib.size(); ++k) fixed_ln_s[k] = target.mean_ln_sa[cond] - lib[k][cond];
  std::size_t usable = 0;
  for (std::size_t k = 0; k < lib.size(); ++k) usable += cond == periods.size() || allowed(std::exp(fixed_ln_s[k]), w);
  if (usable < w.count)
    throw UserError("count", std::to_string(usable) + " entries of kind " + w.kind + " can be scaled within [" + number_text(w.scale_min) +
                             ", " + number_text(w.scale_max) + "]; " + std::to_string(w.count) + " asked",
                    {"count"});

  const double ln_min = std::log(w.scale_min), ln_max = std::log(w.scale_max);
  const std::size_t p = periods.size();
  const bool free_scale = cond == periods.size();

  // Step 2: the nearest entry to each simulated spectrum; a free scale is Jayaram et al.'s
  // least squares on Sa, kept within the limits.
  auto nearest = [&](const Matrix& sim, std::vector<std::size_t>& chosen, std::vector<double>& chosen_ln_s) {
    for (const auto& s : sim) {
      double best = std::numeric_limits<double>::infinity();
      std::size_t best_k = lib.size();
      double best_ln_s = 0.0;
      for (std::size_t k = 0; k < lib.size(); ++k) {
        if (std::find(chosen.begin(), chosen.end(), k) != chosen.end()) continue;
        double ln_s = fixed_ln_s[k];
        if (free_scale) {
          double num = 0.0, den = 0.0;
          for (std::size_t j = 0; j < p; ++j) num += std::exp(lib[k][j] + s[j]), den += std::exp(2 * lib[k][j]);
          ln_s = std::clamp(std::log(num / den), ln_min, ln_max);
        } else if (!allowed(std::exp(ln_s), w)) {
          continue;
        }
        double err = 0.0;
        for (std::size_t j = 0; j < p; ++j) err += std::pow(lib[k][j] + ln_s - s[j], 2);
        if (err < best) best = err, best_k = k, best_ln_s = ln_s;
      }
      if (best_k == lib.size()) throw UserError("count", "no library entry left within the scale limits", {"count"});
      chosen.push_back(best_k);
      chosen_ln_s.push_back(best_ln_s);
    }
  };

  // The fit of a set: w_mean Σ (m̂ − μ)² + w_sigma Σ (ŝ − σ)² (or its relative form).
  auto fit_of = [&](const std::vector<std::size_t>& chosen, const std::vector<double>& chosen_ln_s) {
    Matrix set;
    for (std::size_t i = 0; i < chosen.size(); ++i) set.push_back(shifted(lib[chosen[i]], chosen_ln_s[i]));
    return deviation(stats_of(set, false), target, w, false);
  };

  // Step 3: greedy replacement. In a pass, entry i is replaced by the entry and scale that give
  // the best fit with the others; a free scale is searched on 64 steps of ln s between the
  // limits, then refined by golden-section search between the neighbours of the best step
  // (the fit is smooth in ln s). The entry in place, at its scale, is the first candidate, so
  // that no replacement makes the fit worse. Passes follow one another until one replaces no
  // entry; then the scales alone are optimised (passes over the entries in place, coordinate
  // descent) until a pass improves the fit by less than a relative 1e-12, and one more pass
  // over every entry ends the optimisation unless it replaces one (at most `loops` passes that
  // may replace entries).
  auto greedy = [&](std::vector<std::size_t>& chosen, std::vector<double>& chosen_ln_s) {
    const double n = static_cast<double>(chosen.size());
    std::vector<double> s1(p), s2(p);
    SetStats stats{std::vector<double>(p), std::vector<double>(p), {}};
    auto pass = [&](bool scales_only) {
      bool swapped = false;
      for (std::size_t i = 0; i < chosen.size(); ++i) {
        // Sums of ln Sa and its square over the set without entry i: each candidate is then
        // judged in O(periods).
        std::fill(s1.begin(), s1.end(), 0.0), std::fill(s2.begin(), s2.end(), 0.0);
        for (std::size_t m = 0; m < chosen.size(); ++m)
          if (m != i)
            for (std::size_t j = 0; j < p; ++j) {
              const double x = lib[chosen[m]][j] + chosen_ln_s[m];
              s1[j] += x, s2[j] += x * x;
            }
        auto fit_with = [&](std::size_t k, double ln_s) {
          for (std::size_t j = 0; j < p; ++j) {
            const double y = lib[k][j] + ln_s, mean = (s1[j] + y) / n;
            stats.mean[j] = mean;
            stats.sigma[j] = std::sqrt(std::max(0.0, (s2[j] + y * y) / n - mean * mean));
          }
          return deviation(stats, target, w, false);
        };
        double best = fit_with(chosen[i], chosen_ln_s[i]);
        std::size_t best_k = chosen[i];
        double best_ln_s = chosen_ln_s[i];
        for (std::size_t k = 0; k < lib.size(); ++k) {
          if (k != chosen[i] && (scales_only || std::find(chosen.begin(), chosen.end(), k) != chosen.end())) continue;
          if (!free_scale) {
            if (!allowed(std::exp(fixed_ln_s[k]), w)) continue;
            if (const double d = fit_with(k, fixed_ln_s[k]); d < best) best = d, best_k = k, best_ln_s = fixed_ln_s[k];
            continue;
          }
          constexpr int kSteps = 64;
          auto step_ln_s = [&](int step) { return ln_min + (ln_max - ln_min) * step / kSteps; };
          int best_step = 0;
          double best_step_fit = std::numeric_limits<double>::infinity();
          for (int step = 0; step <= kSteps; ++step)
            if (const double d = fit_with(k, step_ln_s(step)); d < best_step_fit) best_step_fit = d, best_step = step;
          double lo = step_ln_s(std::max(0, best_step - 1)), hi = step_ln_s(std::min(kSteps, best_step + 1));
          const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
          double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
          double f1 = fit_with(k, x1), f2 = fit_with(k, x2);
          while (hi - lo > 1e-9) {
            if (f1 < f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - golden * (hi - lo), f1 = fit_with(k, x1);
            else lo = x1, x1 = x2, f1 = f2, x2 = lo + golden * (hi - lo), f2 = fit_with(k, x2);
          }
          double ln_s = step_ln_s(best_step), d = best_step_fit;
          if (f1 < d) ln_s = x1, d = f1;
          if (f2 < d) ln_s = x2, d = f2;
          if (d < best) best = d, best_k = k, best_ln_s = ln_s;
        }
        swapped = swapped || best_k != chosen[i];
        chosen[i] = best_k;
        chosen_ln_s[i] = best_ln_s;
      }
      return swapped;
    };
    for (int loop = 0; loop < w.loops; ++loop) {
      if (pass(false)) continue;
      if (!free_scale) break;  // fixed scales: nothing more to optimise
      for (int sweep = 0; sweep < 1000; ++sweep) {
        const double before = fit_of(chosen, chosen_ln_s);
        pass(true);
        if (!(before - fit_of(chosen, chosen_ln_s) > 1e-12 * before)) break;
      }
      if (++loop < w.loops && pass(false)) continue;
      break;
    }
  };

  // Steps 2 and 3 from each of the best `starts` simulated sets; the best fit is kept.
  const std::vector<Matrix> sims = simulated_sets(target, w);
  std::vector<std::size_t> chosen;
  std::vector<double> chosen_ln_s;
  double best_fit = std::numeric_limits<double>::infinity();
  for (int start = 0; start < std::min(w.starts, w.trials); ++start) {
    std::vector<std::size_t> ks;
    std::vector<double> ln_s;
    nearest(sims[static_cast<std::size_t>(start)], ks, ln_s);
    greedy(ks, ln_s);
    if (const double d = fit_of(ks, ln_s); d < best_fit) best_fit = d, chosen = std::move(ks), chosen_ln_s = std::move(ln_s);
  }
  auto set_of = [&](const std::vector<std::size_t>& ks, const std::vector<double>& ln_s) {
    Matrix set;
    for (std::size_t i = 0; i < ks.size(); ++i) set.push_back(shifted(lib[ks[i]], ln_s[i]));
    return set;
  };

  SelectionResult r;
  r.ln_sa = set_of(chosen, chosen_ln_s);
  const SetStats s = stats_of(r.ln_sa, false);
  r.mean_ln_sa = s.mean;
  r.sigma_ln_sa = s.sigma;
  // The figure of merit is always Baker & Lee's: absolute σ errors, their weights 1 and 2.
  SelectionSettings baker_lee;
  r.sum_of_squares = deviation(s, target, baker_lee, false);
  for (std::size_t j = 0; j < periods.size(); ++j) {
    r.median_error_percent = std::max(r.median_error_percent, 100.0 * std::fabs(std::exp(s.mean[j] - target.mean_ln_sa[j]) - 1.0));
    if (target.sigma_ln_sa[j] > 0.0)
      r.sigma_error_percent = std::max(r.sigma_error_percent, 100.0 * std::fabs(s.sigma[j] - target.sigma_ln_sa[j]) / target.sigma_ln_sa[j]);
  }
  for (std::size_t i = 0; i < chosen.size(); ++i) r.records.push_back({ids[chosen[i]], std::exp(chosen_ln_s[i])});
  return r;
}

}  // namespace pcrf
