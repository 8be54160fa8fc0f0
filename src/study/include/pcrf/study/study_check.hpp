/// \file study_check.hpp
/// \brief The checks that need more than the study file: every record loads, every frame
/// of the study can be built, every history request names exactly one case.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {

struct CheckedStudy {
  std::string fingerprint;                  ///< see fingerprint.hpp
  std::vector<std::int64_t> history_cases;  ///< case index of each Study::histories entry
  bool frames_checked = false;              ///< every frame was built: the next three are counted
  std::int64_t invalid_frames = 0;          ///< frames the model cannot represent
  std::int64_t invalid_cases = 0;           ///< their cases (they end as invalid_frame)
  std::string first_invalid;                ///< "kappa=…, …: why", for the --check report
  std::vector<std::string> notes;           ///< "record \"R\": …" for each record's alignment and sign notes
  /// Record files whose measures no earthquake record has (record_plausibility), one line
  /// each naming the study line, the record and the likely `units`. With [run]
  /// warnings_as_errors they are a UserError instead.
  std::vector<std::string> warnings;
};

/// Which frames check_study builds.
enum class FrameCheck {
  /// Only where the study's input depends on them: a displaced start (physics.theta0_rad)
  /// must lie below each frame's overturning angle. Otherwise no frame is built up front: the
  /// worker that runs a case builds its frame, once, and an invalid one ends the case as
  /// invalid_frame. What a run does: a study of 10⁶ distinct frames would otherwise build
  /// each twice, once serially on rank 0 before the workers start.
  kWhereNeeded,
  /// Every distinct frame, counting the invalid ones (`pcrf study --check` reports them).
  kEveryFrame,
};

/// Loads every record into `records` (so they are read once), builds the frames `frames`
/// asks for (an invalid one is counted, not an error: its cases end as invalid_frame) and
/// resolves the history requests. Runs before any work starts and before the output file is
/// created. \throws UserError naming the file, the key and the problem.
CheckedStudy check_study(const Study& study, const CaseSpace& space, RecordCache& records,
                         FrameCheck frames = FrameCheck::kEveryFrame);

/// The warning about record `r` of `study` (record_plausibility), or "" when it looks like a
/// record; a synthetic record never warns. It is a problem at the record's declared_at.
std::string record_warning(const Study& study, std::size_t r, const GroundMotion& motion);

}  // namespace pcrf::study
