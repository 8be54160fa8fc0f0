/// \file cube_fragility.hpp
/// \brief Collapse fragility of every frame of a result cube: the cube's cases turned into
/// the numbers the estimators of analysis/fragility.hpp take, and their fits.
///
/// A grid cube with an `intensity` axis gives stripes: at each intensity, the records whose
/// case ended (at rest, rocking, fracture, overturned) and how many of them collapsed
/// (tendon fracture or overturned) — or, when the cube holds verdict checks, the sum of the
/// cases' `collapse_fraction` (the share of their perturbed runs that collapsed). Cases that failed (solver_failure, time_limit),
/// were not run, or ended with the frame still rocking (unresolved) count in neither and are reported. An IDA cube gives each record's collapse
/// intensity, right-censored at its last safe intensity where none was found (fitted by
/// censored maximum likelihood); a curve whose runs ran out before it was bracketed
/// (`curve_state` unbracketed) is censored at its last safe intensity and counted apart. The
/// bootstrap resamples records.
#pragma once

#include <cstdint>
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
  /// IDA cubes only: curves whose max_runs ran out before they were bracketed or censored at
  /// max_intensity; each is right-censored at its last safe intensity (left out when it has
  /// none), never fitted as a collapse or as censored at the cap.
  std::optional<std::size_t> unbracketed;
  /// Grid cubes: cases whose frame was still rocking at the end (rocking_at_end), in no
  /// stripe: neither safe nor collapsed. IDA cubes: unresolved curves (curve_state
  /// unresolved: a run without a verdict ended the hunt), each censored at its last safe
  /// intensity (a lower bound; left out when it has none), never at max_intensity.
  std::size_t unresolved = 0;
  std::int64_t first_case = -1;   ///< one case of the frame (its parameters), -1 when none was selected
  std::optional<analysis::Lognormal> fit;
  analysis::BootstrapResult interval;
  /// What was fitted: the stripes (grid cube), or each curve's collapse intensity and the
  /// last safe intensity of curves that never collapsed (IDA cube; right-censored).
  std::vector<analysis::Stripe> stripes;
  /// IDA: the last safe intensities at which unresolved curves are censored (fitted as censored).
  std::vector<double> collapse_intensities, censored_intensities, unresolved_intensities;
};

/// The one rule for intervals from few records, followed by `cube fragility` (the median's
/// and β's intervals) and `cube risk` (λ_c's) alike: a bootstrap over fewer than this many
/// records (IDA: curves with a value) cannot tell its own spread, so a fit from fewer gets
/// a caution (few_records_warning) and no interval at all.
inline constexpr std::size_t kFewestForInterval = 10;

/// The records (IDA: curves with a value) a frame's fit stands on, as the rule counts them.
std::size_t interval_units(const FrameFragility& frame);
/// Whether the rule gives `frame` an interval: a fit from at least kFewestForInterval units.
bool gives_interval(const FrameFragility& frame);
/// The caution of a fit without an interval by the rule ("frame F: a fit from 4 records, fewer
/// than 10: …"); empty for a frame that gets one, or has no fit.
std::string few_records_warning(const FrameFragility& frame);

/// One line per frame with unbracketed or unresolved curves, saying how they were fitted, and
/// per frame fitted from fewer than kFewestForInterval records or curves (for stderr).
std::vector<std::string> unbracketed_warnings(const std::vector<FrameFragility>& frames);

/// One entry per frame of the selected cases. With `reduction.dimension` set (an IDA cube only),
/// each record's collapse intensities along that dimension are first reduced to one
/// (cube::reduce_censored): over incidence_deg, `min` is the worst orientation of each record,
/// `median` its RotD50-like value, `max` the best; a reduced value is censored when a censored
/// curve could still change it, and missing when one of its curves has no value. The
/// dimension is then no frame axis; `collapses` and `cases` count reduced values.
/// \throws cube::CubeError when the cube has no intensity axis (scale-only cubes have no
/// common intensity to fit against), or for a reduction of a stripe cube, of an unknown
/// dimension or by another `how` than max, min, median.
std::vector<FrameFragility> cube_fragility(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors,
                                           const cube::Reduction& reduction = {});

/// Units and name of the cube's intensity ("g", "peak ground acceleration").
std::string intensity_units(const cube::CubeReader& cube);

}  // namespace pcrf::post
