/// \file ida_search.hpp
/// \brief The hunt-and-fill search of one IDA curve (Vamvatsikos & Cornell 2002): which
/// intensity to run next, given the verdicts of the runs so far. Pure logic: no solver, no
/// MPI, no cube.
///
///  hunt   from `start`, steps that grow geometrically: the k-th step is step · step_factor^(k−1)
///         (start, start + step, start + step (1 + f), …; with f = 2 and step = start the
///         intensity doubles), capped at `max_intensity`, until a run collapses. A safe run
///         at `max_intensity` ends the curve: its collapse intensity is right-censored there.
///  bracket  bisect between the highest safe run below the lowest collapse and that
///         collapse until (collapse − safe)/safe ≤ `resolution` (when the very first run
///         collapses, halve down from it until a run is safe).
///  fill   the remaining runs, up to `max_runs`, halve the largest gap between the safe
///         runs, so the curve is traced where the frame survives. A fill run that collapses
///         lowers the collapse and the bracket is refined again; a gap is filled only while
///         the runs left could bisect such a new bracket down to `resolution`, so a curve that
///         was bracketed stays bracketed.
/// A run that gives no verdict (RunVerdict::kNoVerdict: the model no longer applies, or the
/// frame was still moving when the run ended) stops the hunt and is bisected down to like a
/// collapse, but it is no collapse: a curve whose lowest stopping run gives no verdict is
/// unresolved, with no collapse intensity, and it is never censored at `max_intensity`.
/// A finished curve is in one of four states (CurveState): bracketed to `resolution`,
/// right-censored at `max_intensity`, unbracketed because `max_runs` ran out first, or
/// unresolved.
/// The next intensity depends only on this curve's own results, so a resumed or differently
/// scheduled search makes the same runs.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pcrf/metrics/curve_state.hpp"
#include "pcrf/setting.hpp"

namespace pcrf::ida {

// How a curve ended: pcrf/metrics/curve_state.hpp (below the scheduler, so that reports name
// curve states without MPI); here under the IDA's own names too.
using pcrf::CurveState;
using pcrf::curve_state_name;
using pcrf::kCurveStateNames;

/// What one run of a curve says: safe, collapsed, or nothing the search may call either
/// (the caller decides which statuses those are: study/cube_vocabulary.hpp).
enum class RunVerdict { kSafe, kCollapse, kNoVerdict };

/// The hunt's default growth of its steps, measured (studies/README.md, [ida] step_factor).
inline constexpr double kDefaultStepFactor = 2.0;

/// The fewest runs an IDA curve may have: its first run and one more, the fewest that can
/// bracket a collapse. The one statement of the rule: the [ida] max_runs setting's bound (its
/// check and its row in studies/README.md) and IdaSearch's own check derive from it.
inline constexpr int kMinIdaRuns = 2;

struct IdaSearchSettings {
  double start = 0.0;          ///< first intensity (> 0)
  double step = 0.0;           ///< hunt: the first step; 0: `start`
  double step_factor = kDefaultStepFactor;  ///< hunt: each step is this times the one before (≥ 1)
  double resolution = 0.02;    ///< relative width of the final bracket, in (0, 1)
  double max_intensity = 0.0;  ///< cap of the hunt (≥ start)
  int max_runs = 16;           ///< runs of the curve, ≥ kMinIdaRuns
};

class IdaSearch {
 public:
  explicit IdaSearch(const IdaSearchSettings& settings);

  /// Forgets every run (the search starts anew, its memory kept: a replay of many curves).
  void restart() { runs_.clear(); }

  /// Intensity of the next run; nullopt when the curve is done.
  std::optional<double> next() const;
  /// Records the verdict of a run at `intensity` (normally next()).
  void add(double intensity, RunVerdict verdict);
  void add(double intensity, bool collapsed) { add(intensity, collapsed ? RunVerdict::kCollapse : RunVerdict::kSafe); }

  bool done() const { return !next().has_value(); }
  int runs() const { return static_cast<int>(runs_.size()); }
  /// Lowest collapsing intensity (NaN: no collapse up to the largest intensity run, or a run
  /// without a verdict below it: an unresolved curve has no collapse intensity).
  double collapse_intensity() const;
  /// Highest safe intensity below the lowest run that stopped the hunt (NaN: none).
  double last_safe_intensity() const;
  /// True when the bracket below the lowest stopping run is within `resolution` (or the
  /// curve is censored at the cap).
  bool bracketed() const;
  /// How the curve stands: bracketed, censored at the cap, or (done or not) neither yet.
  CurveState state() const;

 private:
  struct Run {
    double intensity;
    bool collapsed;   ///< stops the hunt: a collapse or no verdict
    bool no_verdict;
  };
  /// Lowest intensity of a run that stopped the hunt (NaN: none), and whether it gave no verdict.
  double ceiling() const;
  bool ceiling_has_no_verdict() const;
  std::optional<double> hunt() const;
  std::optional<double> fill() const;

  IdaSearchSettings settings_;
  std::vector<Run> runs_;
};

}  // namespace pcrf::ida
