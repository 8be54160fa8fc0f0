/// \file percentile.hpp
/// \brief The one percentile of the engine: the estimators' intervals and the cube's
/// statistics use it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pcrf::analysis {

/// Quantile q ∈ [0, 1] of values already sorted, linear between order statistics (numpy's
/// default). NaN for no value. Header-only, so that layers below the estimators (the cube's
/// statistics) use it without depending on them.
inline double percentile_sorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

/// The same of any values (NaNs left out).
inline double percentile(std::vector<double> values, double q) {
  std::erase_if(values, [](double v) { return std::isnan(v); });
  std::sort(values.begin(), values.end());
  return percentile_sorted(values, q);
}

}  // namespace pcrf::analysis
