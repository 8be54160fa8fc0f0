/// \file cube_model_scatter.hpp
/// \brief Modelling uncertainty measured from a cube whose frames are draws of the frame's
/// parameters (plan lhs, sobol or saltelli): every frame's fragility data pooled and fitted
/// as one, split by analysis/model_dispersion.hpp into the record-to-record and the
/// parameters' dispersion, beside FEMA P-695's rated modelling term. `pcrf cube risk` adds
/// the λ_c each total implies, `pcrf cube p695` the collapse probability at the MCE.
/// docs/risk.md defines every number.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/analysis/model_dispersion.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/post/table.hpp"

namespace pcrf::post {

/// Whether the cube's frames are draws of the frame's parameters (its plan is lhs, sobol or
/// saltelli): their scatter is then modelling uncertainty, not a design choice.
bool frames_are_sampled(const cube::CubeReader& cube);

/// Every frame's data pooled and fitted as cube_fragility fits one frame: an IDA's collapse
/// intensities and censored bounds together; stripes' trials and collapses summed per
/// intensity. nullopt when the pooled data cannot fix a lognormal.
std::optional<analysis::Lognormal> pooled_fit(const std::vector<FrameFragility>& frames);

struct ModelScatter {
  analysis::MeasuredDispersion dispersion;
  double beta_mdl_rated = 0.0;       ///< β_MDL of the modelling quality rating
  double beta_total_measured = 0.0;  ///< √(β_pooled² + β_DR² + β_TD²): the modelling term measured
  double beta_total_rated = 0.0;     ///< √(β_RTR² + β_DR² + β_TD² + β_MDL²): the modelling term rated
  std::size_t unfitted = 0;          ///< sampled frames without a fit of their own (left out of β_RTR, β_medians)
};

/// The measured scatter of `frames` (cube_fragility of `cube`) with P-695's ratings of the
/// design requirements, test data and model (A–D). nullopt when the frames are not sampled,
/// fewer than two have a fit, or the pooled data cannot be fitted.
std::optional<ModelScatter> model_scatter(const cube::CubeReader& cube, const std::vector<FrameFragility>& frames,
                                          char design_rating, char test_rating, char model_rating);

/// The report fields of the scatter (`model_*`), missing cells when there is none; `extra`
/// (the λ_c or the P(collapse | MCE) each total implies) follow them.
std::vector<std::pair<std::string, Cell>> model_fields(const std::optional<ModelScatter>& scatter,
                                                       std::vector<std::pair<std::string, Cell>> extra);
/// The fields' names, for a command's --json schema text.
std::string model_field_names();

/// A line for stderr when sampled frames had no fit of their own; empty otherwise.
std::string model_scatter_warning(const std::optional<ModelScatter>& scatter);

/// Text: what was measured, two lines (nothing when there is no scatter); `units` of the median.
void print_model_scatter(const Report& report, const std::string& units, std::ostream& out);

}  // namespace pcrf::post
