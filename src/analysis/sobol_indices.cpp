// Sobol' indices from a Saltelli design (see sobol_indices.hpp).
#include "pcrf/analysis/sobol_indices.hpp"

#include "pcrf/user_error.hpp"

#include "pcrf/analysis/percentile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace pcrf::analysis {
namespace {

struct Estimate {
  std::vector<double> s1, st;
};

/// The estimators over the rows `rows` (a resample, or every row once).
Estimate estimate(const SaltelliOutputs& o, const std::vector<std::size_t>& rows) {
  const std::size_t n = rows.size(), d = o.f_ab.size();
  double mean = 0.0;
  for (std::size_t r : rows) mean += o.f_a[r] + o.f_b[r];
  mean /= 2.0 * static_cast<double>(n);
  double variance = 0.0;
  for (std::size_t r : rows)
    variance += (o.f_a[r] - mean) * (o.f_a[r] - mean) + (o.f_b[r] - mean) * (o.f_b[r] - mean);
  variance /= 2.0 * static_cast<double>(n) - 1.0;
  Estimate e{std::vector<double>(d), std::vector<double>(d)};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < d; ++i) {
    double first = 0.0, total = 0.0;
    for (std::size_t r : rows) {
      const double ab = o.f_ab[i][r];
      first += (o.f_b[r] - mean) * (ab - o.f_a[r]);
      total += (o.f_a[r] - ab) * (o.f_a[r] - ab);
    }
    e.s1[i] = variance > 0.0 ? first / static_cast<double>(n) / variance : nan;
    e.st[i] = variance > 0.0 ? total / (2.0 * static_cast<double>(n)) / variance : nan;
  }
  return e;
}

}  // namespace

std::vector<SobolIndex> sobol_indices(const SaltelliOutputs& outputs, std::size_t resamples, double confidence,
                                      std::uint64_t seed) {
  const std::size_t n = outputs.f_a.size(), d = outputs.f_ab.size();
  std::vector<std::size_t> all(n);
  for (std::size_t r = 0; r < n; ++r) all[r] = r;
  const Estimate point = estimate(outputs, all);
  std::vector<std::vector<double>> s1(d), st(d);
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::vector<std::size_t> rows(n);
  for (std::size_t b = 0; b < resamples; ++b) {
    for (auto& r : rows) r = pick(random);
    const Estimate e = estimate(outputs, rows);
    for (std::size_t i = 0; i < d; ++i) {
      s1[i].push_back(e.s1[i]);
      st[i].push_back(e.st[i]);
    }
  }
  const double tail = (1.0 - confidence) / 2.0;
  std::vector<SobolIndex> indices(d);
  for (std::size_t i = 0; i < d; ++i)
    indices[i] = {point.s1[i], percentile(s1[i], tail), percentile(s1[i], 1.0 - tail),
                  point.st[i], percentile(st[i], tail), percentile(st[i], 1.0 - tail)};
  return indices;
}

std::string sobol_caution(const SobolIndex& index, std::size_t samples) {
  char text[200];
  double inconsistency = 0.0;
  if (index.s1_high < 0.0 || index.st_high < 0.0) {
    const bool first = index.s1_high < 0.0;
    inconsistency = -(first ? index.s1 : index.st);
    std::snprintf(text, sizeof text, "%s = %.3g is negative beyond its interval", first ? "S1" : "ST",
                  first ? index.s1 : index.st);
  } else if (index.s1_low > index.st_high) {
    inconsistency = index.s1 - index.st;
    std::snprintf(text, sizeof text, "S1 = %.3g is above ST = %.3g beyond their intervals", index.s1, index.st);
  } else {
    return {};
  }
  const double ratio = inconsistency / kSobolReadableError;
  double needed = static_cast<double>(samples) * ratio * ratio;
  needed = std::exp2(std::ceil(std::log2(std::max(needed, 2.0 * static_cast<double>(samples)))));
  char advice[160];
  std::snprintf(advice, sizeof advice, ": %zu base samples are too few; about %.0f would bring the error under %g",
                samples, needed, kSobolReadableError);
  return std::string(text) + advice;
}

}  // namespace pcrf::analysis
