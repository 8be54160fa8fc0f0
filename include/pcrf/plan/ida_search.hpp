/// \file ida_search.hpp
/// \brief The hunt-and-fill search of one IDA curve (Vamvatsikos & Cornell 2002): which
/// intensity to run next, given the verdicts of the runs so far. Pure logic: no solver, no
/// MPI, no cube.
///
///  hunt   from `start`, steps that grow by `step` each time (start, start + step,
///         start + 3 step, start + 6 step, …), capped at `max_intensity`, until a run
///         collapses. A safe run at `max_intensity` ends the curve: its collapse intensity
///         is right-censored there.
///  bracket  bisect between the highest safe run below the lowest collapse and that
///         collapse until (collapse − safe)/safe ≤ `resolution` (when the very first run
///         collapses, halve down from it until a run is safe).
///  fill   the remaining runs, up to `max_runs`, halve the largest gap between the safe
///         runs, so the curve is traced where the frame survives. A fill run that collapses
///         lowers the collapse and the bracket is refined again; a gap is filled only while
///         the runs left could bisect such a new bracket down to `resolution`, so a curve that
///         was bracketed stays bracketed.
/// The next intensity depends only on this curve's own results, so a resumed or differently
/// scheduled search makes the same runs.
#pragma once

#include <optional>
#include <vector>

namespace pcrf::plan {

struct IdaSearchSettings {
  double start = 0.0;          ///< first intensity (> 0)
  double step = 0.0;           ///< hunt increment growth; 0: `start`
  double resolution = 0.02;    ///< relative width of the final bracket, in (0, 1)
  double max_intensity = 0.0;  ///< cap of the hunt (≥ start)
  int max_runs = 16;           ///< runs of the curve, ≥ 2
};

class IdaSearch {
 public:
  explicit IdaSearch(const IdaSearchSettings& settings);

  /// Intensity of the next run; nullopt when the curve is done.
  std::optional<double> next() const;
  /// Records the verdict of a run at `intensity` (normally next()).
  void add(double intensity, bool collapsed);

  bool done() const { return !next().has_value(); }
  int runs() const { return static_cast<int>(runs_.size()); }
  /// Lowest collapsing intensity (NaN: no collapse up to the largest intensity run).
  double collapse_intensity() const;
  /// Highest safe intensity below the lowest collapse (NaN: none).
  double last_safe_intensity() const;
  /// True when the bracket is within `resolution` (or the curve is censored at the cap).
  bool bracketed() const;

 private:
  struct Run {
    double intensity;
    bool collapsed;
  };
  std::optional<double> hunt() const;
  std::optional<double> fill() const;

  IdaSearchSettings settings_;
  std::vector<Run> runs_;
};

}  // namespace pcrf::plan
