// Sobol' indices from a Saltelli design (see sobol_indices.hpp).
#include "pcrf/analysis/sobol_indices.hpp"

#include "pcrf/analysis/percentile.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace pcrf::analysis
