/// \file cube_p695.hpp
/// \brief FEMA P-695 from a cube: each frame's median collapse intensity run through the
/// methodology (analysis/p695.hpp) to the verdict. Ŝ_CT is the methodology's own, counted
/// from the records (p695::counted_median; a stripe cube: the lowest stripe where half the
/// records with a verdict collapse); the fragility's lognormal median is shown beside it and
/// used instead on request (P695Inputs::s_ct).
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "pcrf/analysis/p695.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/post/cube_model_scatter.hpp"

namespace pcrf::post {

/// Which median collapse intensity feeds CMR and ACMR.
enum class SctFrom {
  kCounted,    ///< the intensity at which half the records collapse (P-695 Sections 6.3, 6.4)
  kLognormal,  ///< the median of the fitted lognormal fragility
};
/// "counted", "lognormal". \throws UserError for another word.
SctFrom parse_s_ct(const std::string& text);
std::string to_string(SctFrom from);

/// What the methodology needs besides the cube.
struct P695Inputs {
  SctFrom s_ct = SctFrom::kCounted;
  bool default_ratings = false;  ///< the ratings were not given (B,B,B by default): the report says so
  p695::Sdc sdc = p695::Sdc::kDmax;
  double period_s = 0.0;      ///< T [s]: max(C_u T_a, 0.25 s) or the frame's own convention
  /// Period-based ductility μ_T of every frame; 0: each frame's own, by the engine's
  /// convention (p695_ductility: δ_u over δ_y,eff from the pushover peak) at `period_s`.
  double mu_t = 0.0;
  char design_rating = 'B';   ///< quality ratings A–D of design requirements,
  char test_rating = 'B';     ///< test data
  char model_rating = 'B';    ///< and modelling
};

struct FrameP695 {
  std::string frame;
  double mu_t = 0.0;  ///< the μ_T used (given, or the frame's own)
  /// Ŝ_CT counted from the records [g] (NaN: fewer than half collapse), and the curves whose
  /// bound below it made it a conservative value (p695::CountedMedian::bounded).
  double s_ct_counted_g = 0.0;
  double s_ct_counted_high_g = 0.0;  ///< the counted Ŝ_CT were those curves never to collapse [g]
  std::size_t bounded = 0;
  double s_ct_lognormal_g = 0.0;  ///< the fitted lognormal's median [g] (NaN: no fit)
  p695::Assessment assessment;    ///< with the Ŝ_CT P695Inputs::s_ct chose
};

struct P695Report {
  std::vector<FrameP695> frames;
  p695::GroupVerdict group;
  /// Empty when the cube's measure is Sa(T) at `period_s`; otherwise why the numbers are not
  /// P-695's (another measure, another period).
  std::string measure_problem;
  /// What the verdict stands on that the table cannot show, one line each: counted medians
  /// moved by bounded curves, a group of one archetype, default quality ratings.
  std::vector<std::string> notes;
  /// Modelling uncertainty measured (a cube of sampled frames, cube_model_scatter.hpp), and
  /// the collapse probability at the MCE, Φ(ln(S_MT / θ) / β), of the pooled median θ with
  /// the total of the measured modelling term and with that of the rated one.
  std::optional<ModelScatter> model;
  double model_p_collapse_mce_measured = 0.0;
  double model_p_collapse_mce_rated = 0.0;
};

/// \throws cube::CubeError as cube_fragility; UserError for a frame without a
/// fitted median (no collapse at all) or bad inputs.
P695Report cube_p695(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors, const P695Inputs& inputs);

/// One row per frame and the group's verdict, aligned text (JSON: p695_report() and write_json()).
void print_p695(const P695Report& report, const P695Inputs& inputs, std::ostream& out);

}  // namespace pcrf::post
