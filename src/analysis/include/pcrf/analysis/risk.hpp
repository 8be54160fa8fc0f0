/// \file risk.hpp
/// \brief From a site's hazard curve and a collapse fragility to the mean annual rate of
/// collapse, λ_c = ∫ P(C | im) |dλ(im)|, its probability in t years, its deaggregation over
/// intensity, and the risk-targeted intensity of the USGS procedure (Luco et al. 2007;
/// ASCE 7-16 Chapter 21). Numbers only: no cube, no file, no study (the hazard file is read
/// by post/hazard_file.hpp).
///
/// Conventions (docs/risk.md):
///  - the hazard curve λ(x) [1/yr] is interpolated log-log between its points; below its
///    lowest intensity it is taken flat (nothing below the first point is counted: a fragility
///    not negligible there makes λ_c a lower bound, which RateResult::fragility_at_lowest shows);
///  - beyond its last point it is either cut off (the rate λ_n of exceeding the last intensity
///    counted at that intensity: a lower bound, since P(C | im) grows with im) or extended
///    with the power law of its last two points.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "pcrf/analysis/fragility.hpp"

namespace pcrf::risk {

/// What the hazard curve does beyond its last point.
enum class Tail { kCutOff, kPowerLaw };
/// "cut-off", "power-law". parse_tail also takes "cutoff". \throws UserError.
std::string to_string(Tail tail);
Tail parse_tail(const std::string& text);

/// Mean annual rate of exceedance λ(x) [1/yr] of an intensity x (in the measure's units).
class HazardCurve {
 public:
  /// \throws UserError naming the point (0-based) for fewer than two points,
  /// an intensity ≤ 0 or not increasing, a rate ≤ 0 or not decreasing, or sizes that differ.
  HazardCurve(std::vector<double> intensity, std::vector<double> rate_per_yr, Tail tail);
  /// λ(x) [1/yr]: log-log between points; λ(x₀) below the first; beyond the last, 0
  /// (cut off) or the last two points' power law.
  double rate_per_yr(double x) const;
  /// The local exponent k = −d ln λ / d ln x at x (0 below the first point and beyond a cut-off).
  double slope(double x) const;
  /// The intensity whose rate of exceedance is `rate_per_yr` (log-log inverse); NaN when
  /// the rate is above the first point's or (cut off) below the last's.
  double intensity_at_rate(double rate_per_yr) const;
  const std::vector<double>& intensities() const { return x_; }
  const std::vector<double>& rates_per_yr() const { return rate_; }
  Tail tail() const { return tail_; }

 private:
  std::vector<double> x_, rate_;
  Tail tail_;
};

/// λ(x) = k₀ x^−k sampled at `points` log-spaced intensities from `low` to `high`.
HazardCurve power_law_curve(double k0_per_yr, double k, double low, double high, std::size_t points, Tail tail);

/// The part of λ_c between two intensities (low == high: a jump of a step fragility, or the
/// cut-off point mass at the last intensity).
struct RatePiece {
  double low = 0.0;
  double high = 0.0;
  double rate_per_yr = 0.0;
};

struct RateResult {
  double lambda_per_yr = 0.0;        ///< λ_c [1/yr]
  std::vector<RatePiece> pieces;     ///< in increasing intensity; they sum to λ_c
  double fragility_at_lowest = 0.0;  ///< P(C | x₀) at the hazard curve's lowest intensity
  double beyond_last_per_yr = 0.0;   ///< the part of λ_c above the hazard curve's last intensity
  /// What a grid refinement of λ_c would change: 0, since every piece is integrated in closed
  /// form (collapse_rate) or is an exact sum (collapse_rate_steps). Kept for callers that check it.
  double relative_change = 0.0;
  std::size_t evaluations = 0;       ///< pieces integrated in closed form (lognormal)
  /// The part of λ_c from intensities below x (x at or outside a piece's end: exact).
  double rate_below(double x) const;
};

/// λ_c of a lognormal fragility, exact: on each piece between the hazard points and
/// `breakpoints` (deaggregation bin edges, the lowest collapse seen …) the hazard is one power
/// law λ_a (x/a)^−k and ∫ Φ(ln(x/θ)/β) |dλ| has a closed form (integration by parts, docs/risk.md),
/// evaluated without overflow for any k: two points 10⁻⁶ apart with a decade of rate between
/// them are a segment like any other. Linear in the number of pieces; no iteration, no failure.
/// \throws UserError for θ ≤ 0 or β ≤ 0 (or not finite).
RateResult collapse_rate(const HazardCurve& hazard, const analysis::Lognormal& fragility,
                         const std::vector<double>& breakpoints = {});

/// A step fragility: P(C | x) = probability[j] for intensity[j] ≤ x < intensity[j+1], 0
/// below intensity[0] (the fraction collapsed at each stripe; an IDA's empirical CDF). λ_c is
/// exact: between consecutive edges (the steps, the hazard points, `breakpoints`) P is
/// constant and the piece is P(a) (λ(a) − λ(b)); beyond the last edge, P λ(last edge). The
/// pieces are the deaggregation by ground-motion intensity, as for the lognormal; their sum
/// equals Σ_j λ(x_j) (P_j − P_{j−1}). \throws UserError for sizes that differ,
/// intensities not increasing or ≤ 0, probabilities outside [0, 1].
RateResult collapse_rate_steps(const HazardCurve& hazard, const std::vector<double>& intensity,
                               const std::vector<double>& probability, const std::vector<double>& breakpoints = {});

/// The empirical fragility of IDA collapse intensities: after each distinct collapse
/// intensity, the fraction of all `curves` (collapsed or censored) that collapsed at or below it.
void empirical_ida_steps(std::vector<double> collapse_intensities, std::size_t curves, std::vector<double>& intensity,
                         std::vector<double>& probability);

/// Sums `pieces` over the bins [edges[b], edges[b+1]) (a jump at an edge goes to the bin it
/// starts); pieces outside all bins go to the first or last. `edges` increasing, at least two.
std::vector<double> deaggregate(const std::vector<RatePiece>& pieces, const std::vector<double>& edges);

/// The spread of λ_c over refits of resampled data: the `confidence` percentile interval of
/// the λ_c of each refit (`refit` draws a resample with the generator it is given and fits it;
/// nullopt when the resample cannot be fitted: left out). Fixed `seed`: reproducible.
struct RateInterval {
  double low = 0.0;
  double high = 0.0;
  std::size_t fits = 0;  ///< resamples that gave a fit
  /// The sample size at which the interval's half-width would be `fraction` of `lambda_per_yr`,
  /// from `size` now, the width taken to shrink as 1/√n. NaN without an interval.
  double size_for(double lambda_per_yr, std::size_t size, double fraction) const;
};
RateInterval rate_interval(const HazardCurve& hazard, const std::function<std::optional<analysis::Lognormal>(std::mt19937_64&)>& refit,
                           std::size_t resamples = 1000, double confidence = 0.9, std::uint64_t seed = 20211);

/// 1 − exp(−λ t): the probability of at least one collapse in `years` (Poisson).
double probability_in_years(double lambda_per_yr, double years);
/// −ln(1 − p) / t: the rate whose probability in `years` is p.
double rate_for_probability(double probability, double years);

/// The USGS risk target (Luco et al. 2007; ASCE 7-16 Section 21.2.1.2): a generic lognormal
/// fragility of dispersion `beta` with `collapse_probability` at the intensity sought, whose
/// λ_c gives `target_probability` in `years`.
struct RiskTarget {
  double target_probability = 0.01;
  double years = 50.0;
  double beta = 0.6;
  double collapse_probability = 0.1;
  double rate_per_yr() const { return rate_for_probability(target_probability, years); }
  /// The generic fragility anchored at `intensity`: θ = intensity · exp(−Φ⁻¹(p) β).
  analysis::Lognormal fragility_at(double intensity) const;
};
/// \throws UserError for a probability outside (0, 1), years or β ≤ 0.
void check(const RiskTarget& target);

/// The risk-targeted intensity: the x whose generic fragility (RiskTarget::fragility_at) has
/// λ_c = target rate, by bisection in ln x to 1e-10 in λ_c's logarithm. NaN when no intensity
/// between 1e-6 and 1e6 times the curve's range reaches the target (a cut-off curve whose
/// largest rate is below it).
double risk_targeted_intensity(const HazardCurve& hazard, const RiskTarget& target);

/// The factor s on the hazard's intensities (λ_s(x) = λ(x / s)) at which the fragility's
/// λ_c equals the target rate: s > 1, the frame could bear a hazard s times as strong. Same
/// as dividing θ by s. NaN when no s between 1e-6 and 1e6 reaches it.
double hazard_factor_at_target(const HazardCurve& hazard, const analysis::Lognormal& fragility, const RiskTarget& target);

/// Cornell et al. (2002), Eq. 11 with a power-law hazard λ(x) = k₀ x^−k and a lognormal
/// fragility (θ, β): λ_c = k₀ θ^−k exp(k² β² / 2).
double cornell_collapse_rate(double k0_per_yr, double k, const analysis::Lognormal& fragility);
/// The risk-targeted intensity in closed form under that hazard: θ from the formula above
/// set to the target rate, times exp(Φ⁻¹(p) β).
double cornell_risk_targeted_intensity(double k0_per_yr, double k, const RiskTarget& target);

}  // namespace pcrf::risk
