/// \file cube_risk.hpp
/// \brief `pcrf cube risk`: each frame's fragility (cube_fragility.hpp) integrated against a
/// site's hazard curve (hazard_file.hpp) by analysis/risk.hpp: the annual collapse rate λ_c,
/// its probability in t years and its deaggregation, from the fitted lognormal and from the
/// empirical fragility side by side; the risk-targeted intensity (Luco et al. 2007) and each
/// frame's factor on the hazard at that target. docs/risk.md explains every number.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pcrf/analysis/risk.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/post/cube_model_scatter.hpp"
#include "pcrf/hazard/hazard_file.hpp"
#include "pcrf/post/table.hpp"

namespace pcrf::post {

struct RiskInputs {
  std::filesystem::path hazard;
  risk::Tail tail = risk::Tail::kPowerLaw;
  double years = 50.0;       ///< t of p_collapse_in_years [yr]
  risk::RiskTarget target;   ///< 1 % in 50 years, generic β 0.6, 10 % at the intensity
  /// FEMA P-695 quality ratings A–D of design requirements, test data and modelling: their
  /// dispersions (Section 7.3.4) are added to the fitted β in quadrature for a second λ_c.
  char design_rating = 'B', test_rating = 'B', model_rating = 'B';
  /// √(β_DR² + β_TD² + β_MDL²) of the ratings.
  double ratings_beta() const;
};

/// Fewer collapses than this bracket too few to trust λ_c (a warning).
inline constexpr std::size_t kFewBracketing = 10;

struct FrameRisk {
  std::string frame, selection;
  std::size_t cases = 0;     ///< curves (IDA) or cases with a verdict (stripes)
  double collapses = 0.0;
  std::optional<analysis::Lognormal> fit;
  std::optional<risk::RateResult> lognormal;  ///< λ_c of the fit (none without one)
  risk::RateResult empirical;                 ///< λ_c of the fraction collapsed
  std::vector<double> empirical_intensity, empirical_probability;  ///< the step fragility
  double lowest_collapse = 0.0;     ///< the lowest intensity at which a collapse was seen (NaN: none)
  double lower_tail_share = 0.0;    ///< share of the lognormal λ_c from below it (NaN: no fit or none)
  /// Curves that bracket a collapse (IDA: curves that collapsed; stripes: the most records
  /// seen collapsing at one intensity).
  std::size_t bracketing = 0;
  double hazard_factor = 0.0;       ///< risk::hazard_factor_at_target of the fit (NaN: none)
  /// 90 % interval of the lognormal λ_c over 1000 refits: an IDA's curves resampled with
  /// replacement; a stripe cube's collapses redrawn per stripe as binomial (n, z/n).
  /// None (NaN ends) for a fit from fewer than kFewestForInterval records or curves: the
  /// rule of cube fragility (cube_fragility.hpp, gives_interval).
  risk::RateInterval interval;
  std::size_t sample_size = 0;      ///< curves (IDA) or records (stripes) the interval is of
  /// λ_c of the fit with the ratings' dispersion added: β' = √(β² + RiskInputs::ratings_beta()²).
  std::optional<risk::RateResult> with_ratings;
};

struct RiskReport {
  pcrf::hazard::HazardFile hazard;
  std::string cube_measure;
  std::vector<FrameRisk> frames;
  std::vector<double> bin_edges;    ///< deaggregation bins (10 per decade)
  double risk_targeted_intensity = 0.0;
  double uniform_hazard_intensity = 0.0;  ///< at 2 % in 50 years (ASCE 7's MCE_G return period)
  std::vector<std::string> warnings;
  /// Modelling uncertainty measured (a cube of sampled frames, cube_model_scatter.hpp) and the
  /// λ_c of the pooled median with β_pooled, with the total of the measured modelling term and
  /// with that of the rated one.
  std::optional<ModelScatter> model;
  std::optional<risk::RateResult> model_pooled, model_measured, model_rated;
};

/// \throws UserError (file and line) for a bad file or a measure (or Sa period) other
/// than the cube's; cube::CubeError as cube_fragility; UserError for bad inputs.
RiskReport cube_risk(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors, const RiskInputs& inputs);

/// The report as tables: `frames`, `deaggregation`, `hazard` (the curve as read) and
/// `empirical` (each frame's step fragility), and the fields (the inputs, the
/// risk-targeted intensity, the group of frames).
Report risk_report(const RiskReport& result, const RiskInputs& inputs, const std::string& file);

/// The text: what was integrated how, then the frames table.
void print_risk(const Report& report, std::ostream& out);

std::vector<Column> risk_columns();
std::vector<Column> risk_deaggregation_columns();

}  // namespace pcrf::post
