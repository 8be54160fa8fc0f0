// How big a study is (see study_size.hpp).
#include "pcrf/study/study_size.hpp"

#include <unistd.h>

#include <cstdio>

#include "pcrf/study/study_error.hpp"

namespace pcrf::study {
namespace {

/// A frame on rank 0: its parameters, labels and the plan's unit point, and its coordinates
/// in the cube's case axis [bytes] (an upper estimate).
constexpr double kFrameBytes = 512.0;
/// More runs per curve than any IDA needs; the search counts them in an int.
constexpr long kMaxIdaRuns = 1000000;

double frames_of(const Study& study) {
  switch (study.plan) {
    case PlanKind::kList: return static_cast<double>(study.cases.size());
    case PlanKind::kLhs:
    case PlanKind::kSobol: return static_cast<double>(study.samples);
    case PlanKind::kSaltelli: {
      double varied = 0.0;
      for (const auto& r : study.ranges) varied += r ? 1.0 : 0.0;
      return static_cast<double>(study.samples) * (varied + 2.0);
    }
    case PlanKind::kOneAtATime: {
      double frames = study.include_base ? 1.0 : 0.0;
      for (const auto& axis : study.axes) frames += static_cast<double>(axis.size());
      return frames;
    }
    case PlanKind::kGrid: break;
  }
  double frames = 1.0;
  for (const auto& axis : study.axes) frames *= axis.empty() ? 1.0 : static_cast<double>(axis.size());
  return frames;
}

std::string line_of(const Study& study, const std::string& key) {
  const auto line = study.setting_lines.find(key);
  return line != study.setting_lines.end() ? line->second : study.file;
}

}  // namespace

StudySize study_size(const Study& study) {
  StudySize size;
  size.frames = frames_of(study);
  const double levels = study.ida ? static_cast<double>(study.ida->max_runs) : static_cast<double>(study.levels.size());
  size.cases = size.frames * static_cast<double>(study.records.size()) * levels;
  return size;
}

void check_study_size(const Study& study) {
  if (study.ida && study.ida->max_runs > kMaxIdaRuns)
    throw StudyError(line_of(study, "ida.max_runs") + ": ida.max_runs: at most " + std::to_string(kMaxIdaRuns) +
                     " runs per curve, got " + std::to_string(study.ida->max_runs));
  const StudySize size = study_size(study);
  const double needed = kFrameBytes * size.frames + 1.0 * size.cases + static_cast<double>(kPendingResultsBytes);
  const double memory = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (needed <= 0.8 * memory) return;
  // The key to change: the sample count of a sampled plan, else an IDA's runs, else the axes.
  const std::string key = is_sampled(study.plan) ? "plan.samples" : study.ida ? "ida.max_runs" : "axes";
  char text[400];
  std::snprintf(text, sizeof text,
                ": %s: %.4g frames and %.4g cases need about %.3g GB on rank 0 (%.0f bytes a frame, one byte a case, "
                "and 0.27 GB of results between checkpoints), more than 80 %% of this machine's %.3g GB (every shard "
                "holds them all); make the study smaller",
                key.c_str(), size.frames, size.cases, needed / 1e9, kFrameBytes, memory / 1e9);
  throw StudyError(line_of(study, key) + text);
}

}  // namespace pcrf::study
