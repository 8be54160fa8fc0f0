/// \file ida_work.hpp
/// \brief A study's adaptive IDA as work for the scheduler: one curve per record and frame,
/// what counts as a collapse, resuming from what a cube already holds, and the per-curve
/// summaries written back to the cube.
#pragma once

#include <memory>
#include <vector>

#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/ida/ida_curves.hpp"
#include "pcrf/parallel/scheduler.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

/// What a run's outcome tells its curve's search under the study's [ida] collapse rule (the
/// one rule of the run and of the cost estimate's IDA curves).
ida::IdaCurves::CollapseTest collapse_test(const Study& study);

/// The IDA curves of `study`, with every run `writer` already holds replayed (a resumed curve
/// continues where it stopped). `workers`: how many will ask (batch sizes).
std::unique_ptr<ida::IdaCurves> make_ida_curves(const Study& study, const CaseSpace& space, const cube::CubeWriter& writer,
                                                int workers);

/// Chunks of an IDA cube handed out whole (issue 38; docs/checkpoint.md), in order: each holds
/// whole curves (a chunk takes whole trailing axes, and `ida_point` is the last), all of them
/// of curves [first_curve, last_curve) (the shard's), none run yet, no case with a time history
/// (`histories`: those cases). The rule of every plan's whole chunks: none unless there are at
/// least `least` such chunks; the last `tail` of them go run by run, so that the run ends balanced.
std::vector<std::size_t> ida_unit_chunks(const cube::CubeWriter& writer, const std::vector<std::int64_t>& histories,
                                         const CaseSpace& space, std::int64_t first_curve, std::int64_t last_curve,
                                         std::size_t least, std::size_t tail);

/// A worker's search of the curves of a chunk handed out whole (parallel::ScheduleOptions::
/// evaluate_unit): each curve in turn, run by run, by ida::search_curve and the study's collapse
/// rule, as rank 0's IdaCurves would search it. The points a curve never runs stay not run.
parallel::UnitEvaluator ida_unit_evaluator(const Study& study);

/// An IDA's work on rank 0: the chunks handed out whole first (their curves searched by the
/// workers, rank 0 hears only each chunk's number and counts), then every other curve run by
/// run from the IDA's search (IdaCurves: the tail chunks, curves begun before a --resume, all
/// curves of a study with too few chunks).
class IdaWork final : public parallel::WorkSource {
 public:
  /// `curves`: every curve, stored runs replayed (make_ida_curves); those in `units` are
  /// left out of its hand-out here.
  IdaWork(std::unique_ptr<ida::IdaCurves> curves, std::vector<std::size_t> units, const cube::ChunkGrid& grid);
  parallel::WorkBatch take(bool in_process_worker) override;
  void completed(const parallel::CaseOutcome& outcome) override { curves_->completed(outcome); }
  bool exhausted() const override { return next_ == units_.size() && curves_->exhausted(); }

  const ida::IdaCurves& curves() const { return *curves_; }
  /// True when a worker searches `curve` in one of the chunks handed out whole.
  bool in_unit(std::size_t curve) const;
  bool has_units() const { return !units_.empty(); }

 private:
  std::unique_ptr<ida::IdaCurves> curves_;
  std::vector<std::size_t> units_;  ///< sorted
  std::size_t next_ = 0;
  const cube::ChunkGrid& grid_;
};

/// collapse_intensity, last_safe_intensity and ida_runs of every curve, into the cube; with
/// verdict checks also the band of intensities whose verdicts were unstable. A curve searched
/// in a chunk handed out whole is known to rank 0 only from what is stored: with `final`
/// (the run's end, every chunk back) the writer first takes the workers' parts
/// (CubeWriter::take_parts) and such curves are replayed from the stored runs; before, they
/// are NaN (not known yet), as a curve of another shard.
void store_ida_summaries(const Study& study, const IdaWork& work, cube::CubeWriter& writer, bool final);

}  // namespace pcrf::run
