/// \file cube_p695.hpp
/// \brief FEMA P-695 from a cube: each frame's median collapse intensity (its fragility) run
/// through the methodology (analysis/p695.hpp) to the verdict.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "pcrf/analysis/p695.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/post/cube_fragility.hpp"

namespace pcrf::post {

/// What the methodology needs besides the cube.
struct P695Inputs {
  p695::Sdc sdc = p695::Sdc::kDmax;
  double period_s = 0.0;      ///< T [s]: max(C_u T_a, 0.25 s) or the frame's own convention
  double mu_t = 3.0;          ///< period-based ductility μ_T
  char design_rating = 'B';   ///< quality ratings A–D of design requirements,
  char test_rating = 'B';     ///< test data
  char model_rating = 'B';    ///< and modelling
};

struct FrameP695 {
  std::string frame;
  p695::Assessment assessment;
};

struct P695Report {
  std::vector<FrameP695> frames;
  p695::GroupVerdict group;
  /// Empty when the cube's measure is Sa(T) at `period_s`; otherwise why the numbers are not
  /// P-695's (another measure, another period).
  std::string measure_problem;
};

/// \throws cube::CubeError as cube_fragility; std::invalid_argument for a frame without a
/// fitted median (no collapse at all) or bad inputs.
P695Report cube_p695(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors, const P695Inputs& inputs);

/// One row per frame and the group's verdict, aligned text (JSON: p695_report() and write_json()).
void print_p695(const P695Report& report, const P695Inputs& inputs, std::ostream& out);

}  // namespace pcrf::post
