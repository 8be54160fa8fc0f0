// A study's adaptive IDA as scheduler work (see ida_work.hpp).
#include "pcrf/run/ida_work.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/run/case_runner.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/run/result_row.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;
namespace {

/// What a run tells a curve's search: a collapse for the [ida] collapse statuses, a failed
/// run (its response is unknown: conservatively a collapse, as IDA practice counts
/// non-convergence) and, with theta_limit_rad, a peak rotation at or above it; no verdict for
/// a run the model cannot vouch for (gives_no_verdict: still rocking when its tail ended, a
/// ground in free fall, an invalid frame), which stops the hunt but is never a collapse nor
/// safe; else safe.
class CollapseRule {
 public:
  explicit CollapseRule(const Study& study) : limit_rad_(study.ida->theta_limit_rad) {
    std::stringstream words(study.ida->collapse);
    // The parser checked every word ([ida] collapse): each is a status's name.
    for (std::string word; std::getline(words, word, ',');) statuses_.push_back(static_cast<std::int8_t>(parse_status(word)));
    const std::size_t column = ResultColumns(study).metric_column(metric::theta_max().name);
    theta_column_ = column == ResultColumns::npos ? -1 : static_cast<int>(column);
  }

  ida::RunVerdict operator()(std::int8_t status, double theta_max_rad) const {
    const auto s = static_cast<CaseStatus>(status);
    if (is_failure(s) || status == parallel::kEvaluatorThrew) return ida::RunVerdict::kCollapse;
    if (std::find(statuses_.begin(), statuses_.end(), status) != statuses_.end()) return ida::RunVerdict::kCollapse;
    if (limit_rad_ > 0.0 && theta_max_rad >= limit_rad_) return ida::RunVerdict::kCollapse;
    return gives_no_verdict(s) ? ida::RunVerdict::kNoVerdict : ida::RunVerdict::kSafe;
  }
  /// θ_max of a row (NaN when not stored).
  double theta(const std::vector<double>& row) const { return theta_column_ < 0 ? std::nan("") : row[static_cast<std::size_t>(theta_column_)]; }
  int theta_column() const { return theta_column_; }

 private:
  double limit_rad_;
  std::vector<std::int8_t> statuses_;
  int theta_column_;
};

}  // namespace

ida::IdaCurves::CollapseTest collapse_test(const Study& study) {
  return [rule = CollapseRule(study)](const parallel::CaseOutcome& o) { return rule(o.status, rule.theta(o.row)); };
}

std::unique_ptr<ida::IdaCurves> make_ida_curves(const Study& study, const CaseSpace& space, const cube::CubeWriter& writer,
                                                int workers) {
  const CollapseRule rule(study);
  auto curves = std::make_unique<ida::IdaCurves>(static_cast<std::size_t>(space.curves()), study.ida->search(),
                                                 collapse_test(study), workers);
  // Resume: each curve's stored runs, in order, up to the first one not stored (a curve has
  // at most one run in flight, so a killed run leaves no gap before its last stored point).
  const auto& status = writer.status();
  const auto intensity = writer.read_values(schema::kIdaIntensity);
  const auto theta_values = rule.theta_column() < 0 ? std::vector<double>{} : writer.read_values(std::string(metric::theta_max().name));
  const std::vector<double>* theta = rule.theta_column() < 0 ? nullptr : &theta_values;
  const auto runs = static_cast<std::int64_t>(space.ida_runs());
  for (std::int64_t c = 0; c < space.curves(); ++c) {
    for (std::int64_t k = 0; k < runs; ++k) {
      const auto i = static_cast<std::size_t>(c * runs + k);
      if (status[i] == cube::kStatusNotRun) break;
      curves->replay(static_cast<std::size_t>(c), static_cast<int>(k), intensity[i],
                   rule(status[i], theta ? (*theta)[i] : std::nan("")));
    }
  }
  return curves;
}

void store_ida_summaries(const Study& study, const ida::IdaCurves& curves, cube::CubeWriter& writer) {
  std::vector<double> collapse, safe, runs, state, unresolved;
  const double none = std::nan("");  // a curve another shard computes: nothing known here
  const auto& status = writer.status();
  const auto points = static_cast<std::size_t>(curves.max_runs());
  for (std::size_t c = 0; c < curves.curves(); ++c) {
    const bool here = !curves.skipped(c);
    const auto& curve = curves.curve(c);
    collapse.push_back(here ? curve.collapse_intensity() : none);
    safe.push_back(here ? curve.last_safe_intensity() : none);
    runs.push_back(here ? static_cast<double>(curve.runs()) : none);
    // A state only once the curve is done: a curve still running is neither.
    state.push_back(here && curve.done() ? static_cast<double>(curve.state()) : none);
    const std::span<const std::int8_t> runs_of_curve(status.data() + c * points, points);
    unresolved.push_back(here ? static_cast<double>(schema::unresolved_count(runs_of_curve)) : none);
  }
  writer.store_side(schema::kCollapseIntensity, std::move(collapse));
  writer.store_side(schema::kLastSafeIntensity, std::move(safe));
  writer.store_side(schema::kIdaRuns, std::move(runs));
  writer.store_side(schema::kCurveState, std::move(state));
  writer.store_side(schema::kUnresolvedRuns, std::move(unresolved));
  if (!study.solver.verdict_check) return;
  // The band of intensities whose verdicts failed the perturbation test, per curve.
  const auto stable = writer.read_values(std::string(metric::status_stable().name));
  const auto intensity = writer.read_values(schema::kIdaIntensity);
  std::vector<double> from(curves.curves(), std::nan("")), to(curves.curves(), std::nan(""));
  for (std::size_t c = 0; c < curves.curves(); ++c)
    for (std::size_t k = 0; k < points; ++k) {
      const std::size_t i = c * points + k;
      if (stable[i] != 0.0) continue;
      if (!(intensity[i] >= from[c])) from[c] = intensity[i];
      if (!(intensity[i] <= to[c])) to[c] = intensity[i];
    }
  writer.store_side(schema::kUnstableFrom, std::move(from));
  writer.store_side(schema::kUnstableTo, std::move(to));
}

}  // namespace pcrf::run
