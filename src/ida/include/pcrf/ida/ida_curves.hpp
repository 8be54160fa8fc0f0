/// \file ida_curves.hpp
/// \brief The adaptive IDA as a source of work for the scheduler: one IdaSearch per curve
/// (a record and a frame), each curve's next run made when its previous one comes back, many
/// curves advancing at once. Knows nothing of physics: the caller says which outcomes are
/// collapses, and which give no verdict.
///
/// Case indices: curve c, point k (the k-th run of the curve) is case c · max_runs + k, so
/// the runs of a curve are the last axis (`ida_point`) of a cube over the curves' axes.
/// A work item's argument is the run's intensity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "pcrf/parallel/work_source.hpp"
#include "pcrf/ida/ida_search.hpp"

namespace pcrf::ida {

/// The case of point `point` (the point-th run) of curve `curve`: curve · max_runs + point.
inline std::int64_t ida_case(std::int64_t curve, std::int64_t point, int max_runs) {
  return curve * max_runs + point;
}

/// Runs the search of curve `curve` on from where `search` stands to its end, each run by
/// `run` (its case and intensity -> its verdict, nullopt: stop here), in order: what a worker
/// handed the curves of a chunk whole does (the runs of a curve are sequential: each depends
/// on the last), the same search as IdaCurves makes curve by curve; and, with the stored
/// verdicts as `run`, the replay of a curve from what a cube holds (the intensities are the
/// search's own). Returns false when `run` stopped it.
template <class Run>
bool search_curve(IdaSearch& search, std::int64_t curve, int max_runs, Run run) {
  for (std::optional<double> x = search.next(); x; x = search.next()) {
    const std::optional<RunVerdict> verdict = run(ida_case(curve, search.runs(), max_runs), *x);
    if (!verdict) return false;
    search.add(*x, *verdict);
  }
  return true;
}

class IdaCurves final : public parallel::WorkSource {
 public:
  using CollapseTest = std::function<RunVerdict(const parallel::CaseOutcome&)>;

  /// \param curves    number of curves
  /// \param workers   workers that will ask (for batch sizes)
  IdaCurves(std::size_t curves, const IdaSearchSettings& settings, CollapseTest collapsed, int workers);

  /// Resume: the verdict of point `point` of `curve`, stored by an earlier run. Points must
  /// come in order; a curve's later runs are then those the search makes next.
  void replay(std::size_t curve, int point, double intensity, RunVerdict verdict);

  /// Leaves a curve out of this run (another shard computes it).
  void skip(std::size_t curve);
  bool skipped(std::size_t curve) const { return skipped_[curve]; }

  parallel::WorkBatch take(bool in_process_worker) override;
  void completed(const parallel::CaseOutcome& outcome) override;
  bool exhausted() const override;

  int max_runs() const { return settings_.max_runs; }
  std::size_t curves() const { return searches_.size(); }
  const IdaSearch& curve(std::size_t c) const { return searches_[c]; }
  std::size_t finished_curves() const;

 private:
  void refresh(std::size_t curve);

  IdaSearchSettings settings_;
  CollapseTest collapsed_;
  int workers_;
  std::vector<IdaSearch> searches_;
  std::vector<double> in_flight_;      ///< intensity handed out per curve; NaN: none
  std::deque<std::size_t> ready_;      ///< curves whose next run can be handed out (and stale entries)
  std::vector<bool> queued_;           ///< which curves are in ready_ for real
  std::size_t ready_count_ = 0;        ///< how many
  std::size_t running_ = 0;            ///< curves with a run in flight
  std::vector<bool> skipped_;          ///< curves another shard computes
};

}  // namespace pcrf::ida
