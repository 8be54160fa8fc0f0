/// \file cube_fragility.hpp
/// \brief Collapse fragility of every frame of a result cube: the cube's cases turned into
/// the numbers the estimators of analysis/fragility.hpp take, and their fits.
///
/// A grid cube with an `intensity` axis gives stripes: at each intensity, the records whose
/// case ended (at rest, rocking, fracture, overturned) and how many of them collapsed
/// (tendon fracture or overturned) — or, when the cube holds verdict checks, the sum of the
/// cases' `collapse_fraction` (the share of their perturbed runs that collapsed). Cases that failed (solver_failure, time_limit) or were
/// not run count in neither and are reported. An IDA cube gives each record's collapse
/// intensity, right-censored at its last safe intensity where none was found (fitted by
/// censored maximum likelihood). The bootstrap resamples records.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "pcrf/analysis/fragility.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"

namespace pcrf::post {

struct FrameFragility {
  std::string frame;              ///< "kappa=1.8,lambda=2" (the frame axes with several values), or "all"
  /// The frame as -w selectors, comma-separated ("kappa=1.8,lambda=2"; "case=3" where the
  /// frame label is a list plan's case label); empty for "all".
  std::string selection;
  std::size_t records = 0;        ///< records on the cube's record axis
  std::size_t cases = 0;          ///< cases that ended with a verdict (IDA: curves)
  double collapses = 0.0;         ///< of which collapsed
  std::size_t failed = 0;         ///< cases with no verdict (solver failure, time limit; IDA: curves with no value)
  std::size_t not_run = 0;        ///< cases (IDA: curves) never run: neither fitted nor counted as failed
  std::optional<analysis::Lognormal> fit;
  analysis::BootstrapResult interval;
  /// What was fitted: the stripes (grid cube), or each curve's collapse intensity and the
  /// last safe intensity of curves that never collapsed (IDA cube; right-censored).
  std::vector<analysis::Stripe> stripes;
  std::vector<double> collapse_intensities, censored_intensities;
};

/// One entry per frame of the selected cases. \throws cube::CubeError when the cube has no
/// intensity axis (scale-only cubes have no common intensity to fit against).
std::vector<FrameFragility> cube_fragility(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors);

/// Units and name of the cube's intensity ("g", "peak ground acceleration").
std::string intensity_units(const cube::CubeReader& cube);

}  // namespace pcrf::post
