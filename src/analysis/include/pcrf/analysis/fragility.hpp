/// \file fragility.hpp
/// \brief Lognormal collapse fragility, P(collapse | IM = x) = Φ(ln(x/θ)/β), fitted by
/// maximum likelihood. Knows numbers only: no cube, no file, no study.
///
/// Two kinds of data:
///  - collapse intensities (IDA): each record's first collapse intensity, or a right-censored
///    value for a record that did not collapse up to the largest intensity run
///    (likelihood Π f(x_i) · Π [1 − F(c_j)]);
///  - stripes (Baker 2015): at intensity x_k, n_k records of which z_k collapsed
///    (likelihood Π p_k^{z_k} (1 − p_k)^{n_k − z_k}); z_k may be fractional (a case's
///    share of collapsing perturbed runs).
/// Uncertainty: a nonparametric bootstrap over records (resample records with replacement,
/// refit), percentile intervals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace pcrf::analysis {

struct Lognormal {
  double median = 0.0;  ///< θ, in the intensity's units
  double beta = 0.0;    ///< β, standard deviation of ln IM at collapse [-]
};

/// Standard normal CDF Φ.
double normal_cdf(double z);

/// MLE from collapse intensities `observed` (> 0) and right-censored values `censored`
/// (> 0: the collapse intensity exceeds them). nullopt when there are fewer than two
/// observed collapses, or all observations are equal (β undefined).
std::optional<Lognormal> fit_censored(const std::vector<double>& observed, const std::vector<double>& censored);

/// One stripe: `trials` records run at `intensity`, `collapses` of them collapsed.
struct Stripe {
  double intensity = 0.0;
  double trials = 0.0;
  double collapses = 0.0;
};
/// Binomial MLE over stripes. nullopt when the data cannot fix both parameters (no stripe
/// with collapses, or none without; fewer than two intensities).
std::optional<Lognormal> fit_stripes(const std::vector<Stripe>& stripes);

/// A percentile interval.
struct Interval {
  double low = 0.0;
  double high = 0.0;
};
struct BootstrapResult {
  Interval median;
  Interval beta;
  std::size_t fits = 0;  ///< resamples that gave a fit (the rest are left out)
};

/// Resamples `units` indices with replacement `resamples` times (fixed `seed`: reproducible),
/// calls `fit` on each, and returns the `confidence` percentile intervals (0.9: 5 % – 95 %).
BootstrapResult bootstrap(std::size_t units, const std::function<std::optional<Lognormal>(const std::vector<std::size_t>&)>& fit,
                          std::size_t resamples = 1000, double confidence = 0.9, std::uint64_t seed = 20211);

}  // namespace pcrf::analysis
