// One case of a study, from index to result row (see case_runner.hpp).
#include "pcrf/study/case_runner.hpp"

#include <cmath>
#include <limits>

namespace pcrf::study {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

void mark_failed(parallel::CaseOutcome& outcome, const std::string& message) {
  std::fill(outcome.row.begin(), outcome.row.end(), kNaN);
  outcome.status = static_cast<std::int8_t>(CaseStatus::kSolverFailure);
  outcome.note = message;
}

}  // namespace

CaseRunner::CaseRunner(const Study& study, const CaseSpace& space, RecordCache& records)
    : study_(study), space_(space), records_(records) {
  for (const auto& name : study.metrics) metrics_.push_back(find_metric(name));
  // Compute only what is asked: the exact angular-velocity peak costs an extra root.
  request_.omega_peak = false;
  for (const auto* m : metrics_)
    if (m->name == "omega_max_rad_s" || m->name == "t_omega_max_s") request_.omega_peak = true;
}

parallel::CaseOutcome CaseRunner::run(std::int64_t index, const HistorySink& history) const noexcept {
  parallel::CaseOutcome outcome{index, static_cast<std::int8_t>(CaseStatus::kSolverFailure),
                                std::vector<double>(row_width(), kNaN), {}};
  try {
    const CaseSpec spec = space_.case_at(index);
    const Frame frame = make_frame(spec.parameters);
    const auto motion = scaled_record(spec.record, scale_factor(spec));
    const CaseResult result = solve_case(frame, *motion, study_.physics, study_.solver, request_, history);
    outcome.status = static_cast<std::int8_t>(result.status);
    for (std::size_t m = 0; m < metrics_.size(); ++m) {
      const double value = metrics_[m]->get(result);
      if (std::isinf(value)) {
        mark_failed(outcome, "case " + std::to_string(index) + ": non-finite " + std::string(metrics_[m]->name));
        return outcome;
      }
      outcome.row[m] = value;
    }
    outcome.note = result.message;
  } catch (const std::exception& e) {
    mark_failed(outcome, e.what());
  } catch (...) {
    mark_failed(outcome, "unknown exception");
  }
  return outcome;
}

double CaseRunner::scale_factor(const CaseSpec& spec) const {
  if (!study_.intensity) return spec.level;
  return spec.level / records_.intensity(spec.record, *study_.intensity);
}

std::shared_ptr<const GroundMotion> CaseRunner::scaled_record(std::size_t record, double scale) const {
  std::lock_guard lock(last_mutex_);
  if (!last_.motion || last_.record != record || last_.scale != scale)
    last_ = {record, scale, std::make_shared<const GroundMotion>(records_.get(record).scaled(scale))};
  return last_.motion;
}

CaseStatus outcome_status(const parallel::CaseOutcome& outcome) {
  if (outcome.status == parallel::kEvaluatorThrew) return CaseStatus::kSolverFailure;
  return static_cast<CaseStatus>(outcome.status);
}

bool is_failure(CaseStatus status) {
  return status == CaseStatus::kSolverFailure || status == CaseStatus::kTimeLimit;
}

}  // namespace pcrf::study
