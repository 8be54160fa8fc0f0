/// \file percentile.hpp
/// \brief The percentile the estimators' intervals use.
#pragma once

#include <vector>

namespace pcrf::analysis {

/// Quantile q ∈ [0, 1] of `values` (NaNs left out), linear between order statistics
/// (numpy's default). NaN when no value is left.
double percentile(std::vector<double> values, double q);

}  // namespace pcrf::analysis
