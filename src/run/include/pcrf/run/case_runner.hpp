/// \file case_runner.hpp
/// \brief Runs the cases of a study: builds the frame, scales the record, solves the cases of
/// one excitation as a group (pcrf/solver/case_group.hpp) and packs the stored metrics into a
/// result row. Knows nothing of MPI or HDF5.
///
/// An outcome's status is the CaseStatus; its row's columns are the study's ResultColumns.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/parallel/result_batch.hpp"
#include "pcrf/parallel/work_source.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/run/result_row.hpp"
#include "pcrf/excitation/station_record.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

class CaseRunner {
 public:
  /// Keeps references: the study, the space and the cache must outlive the runner. `group`
  /// solves the cases of one excitation (run_device.hpp: the study's [run] device); null:
  /// the CPU engine's, make_group_solver.
  CaseRunner(const Study& study, const CaseSpace& space, RecordCache& records,
             std::shared_ptr<const CaseGroupSolver> group = nullptr);

  std::size_t row_width() const { return columns_.width(); }

  /// Runs case `item.case_index` (in an IDA, at the intensity `item.argument`). Never throws:
  /// a failure becomes status solver_failure with NaN metrics and the message as the
  /// outcome's note. Infinite metric values also count as a solver failure. With a history
  /// sink, rows come every `history_dt_s` seconds (0: the record's dt) plus every event.
  parallel::CaseOutcome run(const parallel::WorkItem& item, const HistorySink& history = {},
                            double history_dt_s = 0.0) const noexcept;
  /// Runs `items` as run() does, one outcome each in their order; the cases that share an
  /// excitation are solved as one group (the constructor's `group`; by default
  /// make_group_solver: in lockstep lanes, Study::run.lanes wide, where the solver settings
  /// allow it). A case the group refuses fails alone, with
  /// the reason as its note. The answers are run()'s, bit for bit.
  parallel::ResultBatch run(std::span<const parallel::WorkItem> items) const noexcept;

 private:
  /// What a case's frame feels: the record's components at the case's incidence, scaled
  /// (frame_excitation, as `pcrf run` makes it). The cases of a frame come together
  /// (CaseSpace::frame_major), one per record, incidence and level, so the excitations of
  /// the last few dozen are kept: cheap cases (a frame that never lifts off) would
  /// otherwise spend their time copying records.
  std::shared_ptr<const ScaledExcitation> excitation(std::size_t record, std::optional<double> incidence_deg,
                                                    double scale) const;
  /// The level of a case: its axis value, or in an IDA the intensity its work item carries.
  static double level_of(const CaseSpec& spec, const parallel::WorkItem& item);
  /// What a case needs before it is solved.
  struct Ready {
    std::shared_ptr<PreparedFrame> frame;
    std::shared_ptr<const ScaledExcitation> motion;
  };
  /// Sets up `item`'s case (the IDA columns of `outcome` included); nullopt when the case
  /// ends here (an invalid frame: `outcome` says so). \throws as run() catches.
  std::optional<Ready> set_up(const parallel::WorkItem& item, parallel::CaseOutcome& outcome) const;
  /// `outcome` from the case's answer: status, metrics, note (a refused case: failed).
  void conclude(const GroupCase& answer, parallel::CaseOutcome& outcome) const;
  /// A fresh outcome of case `index` (solver failure until concluded).
  parallel::CaseOutcome empty_outcome(std::int64_t index) const;

  const Study& study_;
  const CaseSpace& space_;
  RecordCache& records_;
  ResultColumns columns_;
  OutputRequest request_;
  std::shared_ptr<const CaseGroupSolver> group_;  ///< the cases of one excitation
  std::unique_ptr<CaseGroupSolver> one_case_;  ///< a case with a history
  struct LastScaled {
    std::size_t record = static_cast<std::size_t>(-1);
    std::optional<double> incidence_deg;
    double scale = 0.0;
    std::shared_ptr<const ScaledExcitation> motion;
  };
  mutable std::mutex last_mutex_;
  mutable std::vector<LastScaled> scaled_;  ///< most recent first
  static constexpr std::size_t kScaledRecords = 64;

  /// The frame of a case, prepared once and kept for the next cases of the same frame (a
  /// grid hands out every record and level of a frame together). \throws UserError.
  std::shared_ptr<PreparedFrame> prepared(const SceneSpec& scene) const;
  struct Prepared {
    SceneSpec scene;
    std::shared_ptr<PreparedFrame> frame;
  };
  mutable std::vector<Prepared> prepared_;  ///< up to kPreparedFrames, replaced oldest first
  mutable std::vector<std::uint64_t> prepared_keys_;  ///< scene_key of each, compared first
  mutable std::size_t last_prepared_ = 0;    ///< the slot found last (checked first)
  mutable std::size_t oldest_prepared_ = 0;  ///< the slot a new frame replaces once all are used
  /// At least the frames a worker is handed together in lockstep (study_run.cpp's tiles).
  static constexpr std::size_t kPreparedFrames = 128;
};

/// The status an outcome carries (an evaluator that threw: a solver failure).
CaseStatus outcome_status(const parallel::CaseOutcome& outcome);

/// Statuses that count as failures in progress lines and summaries.
bool is_failure(CaseStatus status);

}  // namespace pcrf::run
