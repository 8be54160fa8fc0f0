/// \file ida_work.hpp
/// \brief A study's adaptive IDA as work for the scheduler: one curve per record and frame,
/// what counts as a collapse, resuming from what a cube already holds, and the per-curve
/// summaries written back to the cube.
#pragma once

#include <memory>

#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/ida/ida_curves.hpp"
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

/// collapse_intensity, last_safe_intensity and ida_runs of every curve, into the cube; with
/// verdict checks also the band of intensities whose verdicts were unstable.
void store_ida_summaries(const Study& study, const ida::IdaCurves& curves, cube::CubeWriter& writer);

}  // namespace pcrf::run
