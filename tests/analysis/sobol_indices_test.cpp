// Sobol' indices on functions whose indices are known in closed form: Ishigami (a = 7,
// b = 0.1) and a linear model. At N = 4096 base samples each index's bootstrap interval
// covers the analytic value, and the intervals are narrow enough to mean something.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <limits>
#include <functional>
#include <numbers>

#include "pcrf/analysis/sobol_indices.hpp"
#include "pcrf/study/sampling.hpp"

namespace pcrf::analysis {
namespace {

/// Evaluates f on a Saltelli design over [lo, hi]^d.
SaltelliOutputs evaluate(std::size_t n, std::size_t d, double lo, double hi,
                         const std::function<double(const std::vector<double>&)>& f) {
  const auto design = study::saltelli_design(n, d, true, 17);
  SaltelliOutputs o{std::vector<double>(n), std::vector<double>(n), std::vector<std::vector<double>>(d, std::vector<double>(n))};
  std::vector<double> x(d);
  for (std::size_t row = 0; row < n * (d + 2); ++row) {
    for (std::size_t i = 0; i < d; ++i) x[i] = lo + (hi - lo) * design.points[row * d + i];
    const double y = f(x);
    const std::size_t j = study::SaltelliDesign::sample(row, d), block = study::SaltelliDesign::block(row, d);
    if (block == 0) o.f_a[j] = y;
    else if (block == 1) o.f_b[j] = y;
    else o.f_ab[block - 2][j] = y;
  }
  return o;
}

void expect_covered(const std::vector<SobolIndex>& got, const std::vector<double>& s1, const std::vector<double>& st) {
  for (std::size_t i = 0; i < s1.size(); ++i) {
    EXPECT_LE(got[i].s1_low, s1[i]) << "S1 of x" << i + 1 << " = " << got[i].s1;
    EXPECT_GE(got[i].s1_high, s1[i]) << "S1 of x" << i + 1 << " = " << got[i].s1;
    EXPECT_LE(got[i].st_low, st[i]) << "ST of x" << i + 1 << " = " << got[i].st;
    EXPECT_GE(got[i].st_high, st[i]) << "ST of x" << i + 1 << " = " << got[i].st;
    EXPECT_LT(got[i].s1_high - got[i].s1_low, 0.1) << "x" << i + 1;
    EXPECT_LT(got[i].st_high - got[i].st_low, 0.1) << "x" << i + 1;
  }
}

TEST(SobolIndices, IshigamiAnalyticIndicesAreWithinTheIntervals) {
  const double a = 7.0, b = 0.1, pi = std::numbers::pi;
  const auto o = evaluate(4096, 3, -pi, pi, [&](const std::vector<double>& x) {
    return std::sin(x[0]) + a * std::sin(x[1]) * std::sin(x[1]) + b * std::pow(x[2], 4) * std::sin(x[0]);
  });
  // Analytic: V = a²/8 + b π⁴/5 + b² π⁸/18 + 1/2, V1 = (1 + b π⁴/5)²/2, V2 = a²/8,
  // V13 = b² π⁸ (1/18 − 1/50), S3 = 0.
  const double v1 = 0.5 * std::pow(1.0 + b * std::pow(pi, 4) / 5.0, 2), v2 = a * a / 8.0;
  const double v13 = b * b * std::pow(pi, 8) * (1.0 / 18.0 - 1.0 / 50.0);
  const double v = v1 + v2 + v13;
  expect_covered(sobol_indices(o), {v1 / v, v2 / v, 0.0}, {(v1 + v13) / v, v2 / v, v13 / v});
}

TEST(SobolIndices, LinearModelIndicesAreTheSquaredWeights) {
  const std::vector<double> c{1.0, 2.0, 0.5, 0.0};
  const auto o = evaluate(4096, 4, 0.0, 1.0, [&](const std::vector<double>& x) {
    double y = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i) y += c[i] * x[i];
    return y;
  });
  double sum = 0.0;
  for (double w : c) sum += w * w;
  std::vector<double> s;
  for (double w : c) s.push_back(w * w / sum);
  expect_covered(sobol_indices(o), s, s);  // additive: S1 = ST
}

TEST(SobolIndices, AConstantOutputHasNoIndices) {
  const auto o = evaluate(64, 2, 0.0, 1.0, [](const std::vector<double>&) { return 3.0; });
  EXPECT_TRUE(std::isnan(sobol_indices(o, 10)[0].s1));
}

// Issue 29: S1 > ST at N = 64 passed without a word. An index that cannot be right (S1
// above ST, or negative, beyond the intervals) gets a caution with the N that would do.
TEST(SobolIndices, ImpossibleEstimatesGetACautionWithTheSamplesNeeded) {
  const SobolIndex above{0.4, 0.35, 0.45, 0.2, 0.15, 0.25};
  const std::string c = sobol_caution(above, 64);
  EXPECT_NE(c.find("S1 = 0.4 is above ST = 0.2"), std::string::npos) << c;
  EXPECT_NE(c.find("64 base samples"), std::string::npos) << c;
  EXPECT_NE(c.find("about 1024"), std::string::npos) << c;  // 64 (0.2 / 0.05)² = 1024
  const SobolIndex negative{0.1, 0.0, 0.2, -0.3, -0.5, -0.1};
  const std::string n = sobol_caution(negative, 64);
  EXPECT_NE(n.find("ST = -0.3 is negative"), std::string::npos) << n;
  EXPECT_NE(n.find("about 4096"), std::string::npos) << n;  // 64 (0.3 / 0.05)² = 2304, up to 2^12
  // Overlapping intervals, or a negative estimate whose interval reaches 0: no caution.
  EXPECT_EQ(sobol_caution({0.3, 0.1, 0.5, 0.25, 0.2, 0.35}, 64), "");
  EXPECT_EQ(sobol_caution({-0.02, -0.1, 0.05, 0.1, 0.05, 0.2}, 64), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(sobol_caution({nan, nan, nan, nan, nan, nan}, 64), "");
}

}  // namespace
}  // namespace pcrf::analysis
