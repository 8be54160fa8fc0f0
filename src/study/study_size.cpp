// How big a study is (see study_size.hpp).
#include "pcrf/study/study_size.hpp"

#include <cstdio>

#include "pcrf/machine_memory.hpp"
#include "pcrf/study/plan.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {
namespace {

/// A frame on rank 0: its parameters, labels and the plan's unit point, and its coordinates
/// in the cube's case axis [bytes] (an upper estimate).
constexpr double kFrameBytes = 512.0;
/// More runs per curve than any IDA needs; the search counts them in an int.
constexpr long kMaxIdaRuns = 1000000;

double frames_of(const Study& study) {
  double frames = 1.0;
  for (const auto& d : study.plan->dimensions()) frames *= static_cast<double>(d.size);
  return frames;
}

}  // namespace

StudySize study_size(const Study& study) {
  StudySize size;
  size.frames = frames_of(study);
  const double levels = study.ida ? static_cast<double>(study.ida->max_runs) : static_cast<double>(study.levels.size());
  const std::size_t records = study.selection ? study.selection->settings.count : study.records.size();  // slots per stripe
  size.cases = size.frames * static_cast<double>(records) * levels;
  return size;
}

void check_study_size(const Study& study) {
  if (study.ida && study.ida->max_runs > kMaxIdaRuns)
    throw UserError(study.where("ida.max_runs"), "at most " + std::to_string(kMaxIdaRuns) + " runs per curve, got " +
                                                     std::to_string(study.ida->max_runs));
  const StudySize size = study_size(study);
  const double needed = kFrameBytes * size.frames + 1.0 * size.cases + static_cast<double>(kPendingResultsBytes);
  const double memory = machine_memory_bytes();
  if (needed <= kUsableMemoryShare * memory) return;
  // The key to change: an IDA's runs, else the plan's size (the axes, or the samples).
  const bool sampled = study.given_at.count("plan.samples") > 0;
  const std::string key = study.ida ? "ida.max_runs" : sampled ? "plan.samples" : "axes";
  char text[400];
  std::snprintf(text, sizeof text,
                "%.4g frames and %.4g cases need about %.3g GB on rank 0 (%.0f bytes a frame, one byte a case, "
                "and 0.27 GB of results between checkpoints), more than 80 %% of this machine's %.3g GB (every shard "
                "holds them all); make the study smaller",
                size.frames, size.cases, needed / 1e9, kFrameBytes, memory / 1e9);
  throw UserError(study.where(key), text);
}

void check_frame_count(double frames, const Where& where) {
  const double needed = kFrameBytes * frames + static_cast<double>(kPendingResultsBytes);
  const double memory = machine_memory_bytes();
  if (needed <= kUsableMemoryShare * memory) return;
  char text[300];
  std::snprintf(text, sizeof text,
                "%.4g frames need about %.3g GB on rank 0 (%.0f bytes a frame), more than 80 %% of this machine's "
                "%.3g GB; make the study smaller",
                frames, needed / 1e9, kFrameBytes, memory / 1e9);
  throw UserError(where, text);
}

}  // namespace pcrf::study
