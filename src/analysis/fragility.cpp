// Lognormal fragility fits (see fragility.hpp). Both likelihoods are maximized over
// (μ = ln θ, s = ln β) by Nelder–Mead from the moment estimate: two parameters, smooth
// log-likelihoods, no derivatives to get wrong.
#include "pcrf/analysis/fragility.hpp"

#include "pcrf/user_error.hpp"

#include "pcrf/analysis/percentile.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace pcrf::analysis {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// log Φ(z), accurate in the lower tail.
double log_cdf(double z) {
  if (z > -5.0) return std::log(normal_cdf(z));
  // erfc keeps relative accuracy where Φ underflows towards 0.
  return std::log(0.5 * std::erfc(-z / std::numbers::sqrt2));
}

/// Minimizes f over R² from x0 (Nelder–Mead, standard coefficients).
std::array<double, 2> minimize(const std::function<double(const std::array<double, 2>&)>& f, std::array<double, 2> x0,
                               double step) {
  std::array<std::array<double, 2>, 3> p{x0, {x0[0] + step, x0[1]}, {x0[0], x0[1] + step}};
  std::array<double, 3> v{f(p[0]), f(p[1]), f(p[2])};
  for (int iteration = 0; iteration < 2000; ++iteration) {
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return v[a] < v[b]; });
    const auto best = order[0], mid = order[1], worst = order[2];
    if (std::fabs(v[worst] - v[best]) < 1e-13 * (1.0 + std::fabs(v[best])) &&
        std::fabs(p[worst][0] - p[best][0]) + std::fabs(p[worst][1] - p[best][1]) < 1e-10)
      break;
    const std::array<double, 2> c{(p[best][0] + p[mid][0]) / 2, (p[best][1] + p[mid][1]) / 2};
    auto along = [&](double t) { return std::array<double, 2>{c[0] + t * (p[worst][0] - c[0]), c[1] + t * (p[worst][1] - c[1])}; };
    const auto reflected = along(-1.0);
    const double fr = f(reflected);
    if (fr < v[best]) {
      const auto expanded = along(-2.0);
      const double fe = f(expanded);
      if (fe < fr) p[worst] = expanded, v[worst] = fe;
      else p[worst] = reflected, v[worst] = fr;
    } else if (fr < v[mid]) {
      p[worst] = reflected, v[worst] = fr;
    } else {
      const auto contracted = fr < v[worst] ? along(-0.5) : along(0.5);
      const double fc = f(contracted);
      if (fc < std::min(fr, v[worst])) {
        p[worst] = contracted, v[worst] = fc;
      } else {  // shrink towards the best point
        for (int k : {mid, worst}) {
          p[k] = {(p[k][0] + p[best][0]) / 2, (p[k][1] + p[best][1]) / 2};
          v[k] = f(p[k]);
        }
      }
    }
  }
  const auto best = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
  return p[best];
}

Lognormal from_parameters(const std::array<double, 2>& x) { return {std::exp(x[0]), std::exp(x[1])}; }

}  // namespace

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

std::optional<Lognormal> fit_censored(const std::vector<double>& observed, const std::vector<double>& censored) {
  if (observed.size() < 2) return std::nullopt;
  std::vector<double> ln_x, ln_c;
  for (double x : observed) ln_x.push_back(std::log(x));
  for (double c : censored) ln_c.push_back(std::log(c));
  double mean = 0.0, var = 0.0;
  for (double l : ln_x) mean += l;
  mean /= static_cast<double>(ln_x.size());
  for (double l : ln_x) var += (l - mean) * (l - mean);
  var /= static_cast<double>(ln_x.size());
  if (!(var > 0.0)) return std::nullopt;
  if (ln_c.empty()) return Lognormal{std::exp(mean), std::sqrt(var)};  // the closed-form MLE
  auto negative_log_likelihood = [&](const std::array<double, 2>& x) {
    const double mu = x[0], beta = std::exp(x[1]);
    double nll = static_cast<double>(ln_x.size()) * std::log(beta);
    for (double l : ln_x) nll += 0.5 * ((l - mu) / beta) * ((l - mu) / beta);
    for (double l : ln_c) nll -= log_cdf(-(l - mu) / beta);  // log(1 − Φ(z)) = log Φ(−z)
    return std::isfinite(nll) ? nll : kInf;
  };
  return from_parameters(minimize(negative_log_likelihood, {mean, 0.5 * std::log(var)}, 0.2));
}

std::optional<Lognormal> fit_stripes(const std::vector<Stripe>& stripes) {
  bool some_collapse = false, some_survival = false;
  std::vector<double> levels;
  double weighted = 0.0, weight = 0.0;
  for (const auto& s : stripes) {
    if (!(s.trials > 0.0)) continue;
    some_collapse = some_collapse || s.collapses > 0.0;
    some_survival = some_survival || s.collapses < s.trials;
    levels.push_back(s.intensity);
    const double p = s.collapses / s.trials;
    weighted += std::log(s.intensity) * p * (1.0 - p) + std::log(s.intensity) * 1e-9;
    weight += p * (1.0 - p) + 1e-9;
  }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  if (!some_collapse || !some_survival || levels.size() < 2) return std::nullopt;
  auto negative_log_likelihood = [&](const std::array<double, 2>& x) {
    const double mu = x[0], beta = std::exp(x[1]);
    double nll = 0.0;
    for (const auto& s : stripes) {
      if (!(s.trials > 0.0)) continue;
      const double z = (std::log(s.intensity) - mu) / beta;
      if (s.collapses > 0.0) nll -= s.collapses * log_cdf(z);
      if (s.trials - s.collapses > 0.0) nll -= (s.trials - s.collapses) * log_cdf(-z);
    }
    return std::isfinite(nll) ? nll : kInf;
  };
  const double spread = std::log(levels.back() / levels.front());
  return from_parameters(minimize(negative_log_likelihood, {weighted / weight, std::log(std::max(0.25 * spread, 0.05))}, 0.3));
}

BootstrapResult bootstrap(std::size_t units,
                          const std::function<std::optional<Lognormal>(const std::vector<std::size_t>&)>& fit,
                          std::size_t resamples, double confidence, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<std::size_t> pick(0, units - 1);
  std::vector<double> medians, betas;
  std::vector<std::size_t> sample(units);
  for (std::size_t b = 0; b < resamples; ++b) {
    for (auto& s : sample) s = pick(random);
    if (const auto f = fit(sample)) {
      medians.push_back(f->median);
      betas.push_back(f->beta);
    }
  }
  BootstrapResult result;
  result.fits = medians.size();
  if (medians.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    result.median = result.beta = {nan, nan};
    return result;
  }
  const double tail = (1.0 - confidence) / 2.0;
  result.median = {percentile(medians, tail), percentile(medians, 1.0 - tail)};
  result.beta = {percentile(betas, tail), percentile(betas, 1.0 - tail)};
  return result;
}

}  // namespace pcrf::analysis
