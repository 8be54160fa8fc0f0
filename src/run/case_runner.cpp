// One case of a study, from index to result row (see case_runner.hpp).
#include "pcrf/run/case_runner.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "pcrf/solver/case_group.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;
namespace {

/// A failed case: its metrics NaN (an IDA's intensity and factor columns stay).
void mark_failed(parallel::CaseOutcome& outcome, const ResultColumns& columns, const std::string& message) {
  columns.clear_metrics(outcome.row);
  outcome.status = static_cast<std::int8_t>(CaseStatus::kSolverFailure);
  outcome.note = message;
}

/// Equal for every two scenes same_scene calls the same (0 and −0 alike, every NaN alike):
/// the cache of prepared frames compares keys before values, so that a study of distinct
/// frames does not compare every case's values with each frame kept.
std::uint64_t scene_key(const SceneSpec& scene) {
  std::uint64_t key = static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(scene.model));
  for (const double x : scene.values) {
    const double v = x == 0.0 ? 0.0 : (std::isnan(x) ? std::numeric_limits<double>::quiet_NaN() : x);
    key = (key ^ std::bit_cast<std::uint64_t>(v)) * 0x100000001b3ULL;  // FNV-1a's prime
  }
  return key;
}

/// Runs `f`; an exception marks `outcome` failed with its text.
template <class F>
void guarded(parallel::CaseOutcome& outcome, const ResultColumns& columns, F&& f) noexcept {
  try {
    f();
  } catch (const std::exception& e) {
    mark_failed(outcome, columns, e.what());
  } catch (...) {
    mark_failed(outcome, columns, "unknown exception");
  }
}

}  // namespace

CaseRunner::CaseRunner(const Study& study, const CaseSpace& space, RecordCache& records)
    : study_(study), space_(space), records_(records), columns_(study),
      group_(make_group_solver(study.solver, static_cast<int>(study.run.lanes))),
      one_case_(one_at_a_time_group()) {
  // Compute only what is asked: the exact angular-velocity peak costs an extra root.
  request_.omega_peak = false;
  for (const auto* m : columns_.metrics())
    if (m == &metric::omega_max() || m == &metric::t_omega_max()) request_.omega_peak = true;
}

std::shared_ptr<PreparedFrame> CaseRunner::prepared(const SceneSpec& scene) const {
  std::lock_guard lock(last_mutex_);
  const std::uint64_t key = scene_key(scene);
  auto same = [&](std::size_t i) { return prepared_keys_[i] == key && same_scene(prepared_[i].scene, scene); };
  if (last_prepared_ < prepared_.size() && same(last_prepared_)) return prepared_[last_prepared_].frame;
  for (auto k = prepared_keys_.begin(); (k = std::find(k, prepared_keys_.end(), key)) != prepared_keys_.end(); ++k) {
    const auto i = static_cast<std::size_t>(k - prepared_keys_.begin());
    if (same(i)) return prepared_[last_prepared_ = i].frame;
  }
  // A new frame: into a free slot, else over the oldest (slots are reused in turn, nothing
  // moves: a study of distinct frames misses every time).
  Prepared fresh{scene, prepare_scene(scene.make(), study_.physics)};
  std::size_t slot = prepared_.size();
  if (slot < kPreparedFrames) {
    prepared_.push_back(std::move(fresh));
    prepared_keys_.push_back(key);
  } else {
    slot = oldest_prepared_;
    oldest_prepared_ = (oldest_prepared_ + 1) % kPreparedFrames;
    prepared_[slot] = std::move(fresh);
    prepared_keys_[slot] = key;
  }
  return prepared_[last_prepared_ = slot].frame;
}

double CaseRunner::level_of(const CaseSpec& spec, const parallel::WorkItem& item) {
  return std::isnan(spec.level) ? item.argument : spec.level;
}

parallel::CaseOutcome CaseRunner::empty_outcome(std::int64_t index) const {
  return {index, static_cast<std::int8_t>(CaseStatus::kSolverFailure), columns_.empty_row(), {}};
}

std::optional<CaseRunner::Ready> CaseRunner::set_up(const parallel::WorkItem& item,
                                                    parallel::CaseOutcome& outcome) const {
  CaseSpec spec = space_.case_at(item.case_index);
  spec.level = level_of(spec, item);
  const double factor = spec.factor ? *spec.factor : records_.scale_factor(spec.record, spec.level, study_.intensity);
  if (study_.ida) {  // the run's intensity and factor travel with it, whatever happens next
    outcome.row[columns_.ida_intensity_column()] = spec.level;
    outcome.row[columns_.scale_factor_column()] = factor;
  }
  Ready ready;
  try {
    ready.frame = prepared(spec.frame);
  } catch (const std::invalid_argument& e) {  // make_frame's geometry, or outside the model's domain
    outcome.status = static_cast<std::int8_t>(CaseStatus::kInvalidFrame);
    outcome.note = std::string("invalid frame: ") + e.what();
    return std::nullopt;
  }
  ready.motion = excitation(spec.record, spec.incidence_deg, factor);
  return ready;
}

void CaseRunner::conclude(const GroupCase& answer, parallel::CaseOutcome& outcome) const {
  if (answer.outcome == GroupOutcome::kRefused) {
    mark_failed(outcome, columns_, answer.result.message);
    return;
  }
  const CaseResult& result = answer.result;
  outcome.status = static_cast<std::int8_t>(result.status);
  const auto& metrics = columns_.metrics();
  for (std::size_t m = 0; m < metrics.size(); ++m) {
    const double value = metrics[m]->get(result);
    if (std::isinf(value)) {
      mark_failed(outcome, columns_,
                  "case " + std::to_string(outcome.case_index) + ": non-finite " + std::string(metrics[m]->name));
      return;
    }
    outcome.row[m] = value;
  }
  outcome.note = result.message;
}

parallel::CaseOutcome CaseRunner::run(const parallel::WorkItem& item, const HistorySink& history,
                                      double history_dt_s) const noexcept {
  parallel::CaseOutcome outcome = empty_outcome(item.case_index);
  guarded(outcome, columns_, [&] {
    const auto ready = set_up(item, outcome);
    if (!ready) return;
    OutputRequest request = request_;
    request.history_dt_s = history_dt_s;
    PreparedFrame* const frame[] = {ready->frame.get()};
    conclude(one_case_->solve(frame, ready->motion->view(), study_.solver, request, history).front(), outcome);
  });
  return outcome;
}

parallel::ResultBatch CaseRunner::run(std::span<const parallel::WorkItem> items) const noexcept {
  parallel::ResultBatch outcomes;
  std::vector<std::size_t> waiting;  // set up, in order; solved below by excitation
  std::vector<Ready> ready;
  for (const parallel::WorkItem& item : items) {
    outcomes.push_back(empty_outcome(item.case_index));
    guarded(outcomes.back(), columns_, [&] {
      if (auto r = set_up(item, outcomes.back())) {
        waiting.push_back(outcomes.size() - 1);
        ready.push_back(std::move(*r));
      }
    });
  }
  std::vector<bool> done(waiting.size(), false);
  for (std::size_t first = 0; first < waiting.size(); ++first) {
    if (done[first]) continue;
    // The cases of first's excitation (the same object: the excitation cache hands it out).
    std::vector<std::size_t> group;
    std::vector<PreparedFrame*> frames;
    for (std::size_t k = first; k < waiting.size(); ++k) {
      if (done[k] || ready[k].motion != ready[first].motion) continue;
      done[k] = true;
      group.push_back(k);
      frames.push_back(ready[k].frame.get());
    }
    std::vector<GroupCase> answers;
    parallel::CaseOutcome* const first_outcome = &outcomes[waiting[group.front()]];
    guarded(*first_outcome, columns_, [&] {  // only what is no one case's: every case of the group fails
      answers = group_->solve(frames, ready[first].motion->view(), study_.solver, request_);
    });
    for (std::size_t j = 0; j < group.size(); ++j) {
      parallel::CaseOutcome& outcome = outcomes[waiting[group[j]]];
      if (answers.empty()) {
        mark_failed(outcome, columns_, first_outcome->note);
      } else {
        guarded(outcome, columns_, [&] { conclude(answers[j], outcome); });
      }
    }
  }
  return outcomes;
}

std::shared_ptr<const ScaledExcitation> CaseRunner::excitation(std::size_t record, std::optional<double> incidence_deg,
                                                              double scale) const {
  std::lock_guard lock(last_mutex_);
  auto it = std::find_if(scaled_.begin(), scaled_.end(), [&](const LastScaled& s) {
    return s.record == record && s.incidence_deg == incidence_deg && s.scale == scale;
  });
  if (it == scaled_.end()) {
    if (scaled_.size() >= kScaledRecords) scaled_.pop_back();
    scaled_.insert(scaled_.begin(),
                   {record, incidence_deg, scale, std::make_shared<const ScaledExcitation>(frame_excitation(records_.station(record), incidence_deg, scale))});
    it = scaled_.begin();
  }
  return it->motion;
}

CaseStatus outcome_status(const parallel::CaseOutcome& outcome) {
  if (outcome.status == parallel::kEvaluatorThrew) return CaseStatus::kSolverFailure;
  return static_cast<CaseStatus>(outcome.status);
}

bool is_failure(CaseStatus status) {
  return status == CaseStatus::kSolverFailure || status == CaseStatus::kTimeLimit;
}

}  // namespace pcrf::run
