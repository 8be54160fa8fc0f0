/// \file study_cube.hpp
/// \brief How a study maps onto a result cube: coordinate names and units, the metric
/// variables, the status flags, the global attributes, and history groups.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

/// The cube of a study. Dimensions as CaseSpace; `record` a text coordinate (with the
/// auxiliary `record_source` and `record_title`); the plan's coordinates along its frame
/// dimensions (Plan::coordinates); the metric variables in ResultColumns order.
/// With an intensity axis, `intensity` replaces `scale`, each record carries its unscaled
/// intensity (`record_<measure>`), and `scale_factor(record, intensity)` holds the factors.
cube::CubeLayout make_cube_layout(const Study& study, const CaseSpace& space, RecordCache& records,
                                  const std::string& fingerprint);

/// A case's time history as a cube history group: a `t_s` dimension and one variable per
/// HistorySample field; the case's coordinates as attributes.
cube::HistoryTable make_history_table(const std::string& label, std::int64_t case_index, const Study& study,
                                      const CaseSpace& space, const std::vector<HistorySample>& samples);

}  // namespace pcrf::run
