// A study's adaptive IDA as scheduler work (see ida_work.hpp).
#include "pcrf/run/ida_work.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
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
  /// True when a verdict depends on θ_max (theta_limit_rad set and stored).
  bool uses_theta() const { return limit_rad_ > 0.0 && theta_column_ >= 0; }

 private:
  double limit_rad_;
  std::vector<std::int8_t> statuses_;
  int theta_column_;
};

/// Some metrics of the cases of whole curves [first_curve, end_curve), read from the writer as
/// one block of the chunks that hold them (CubeWriter::read_values of a chunk range): what
/// rank 0 holds of a variable at once, never the whole of it.
class CurveBlock {
 public:
  CurveBlock(const cube::CubeWriter& writer, std::int64_t runs_per_curve, std::int64_t first_curve, std::int64_t end_curve,
             const std::vector<std::string>& metrics) {
    const auto& grid = writer.grid();
    const std::size_t first_chunk = grid.chunk_of(first_curve * runs_per_curve);
    const std::size_t end_chunk = grid.chunk_of(end_curve * runs_per_curve - 1) + 1;
    first_case_ = grid.range(first_chunk).first;
    for (const auto& name : metrics) values_.push_back(writer.read_values(name, first_chunk, end_chunk));
  }
  /// Metric `metric` (its place in the constructor's list) of case `case_index` (of the block's curves).
  double value(std::size_t metric, std::int64_t case_index) const {
    return values_[metric][static_cast<std::size_t>(case_index - first_case_)];
  }

 private:
  std::int64_t first_case_ = 0;
  std::vector<std::vector<double>> values_;
};

/// Cases a block of curves reads at most, per metric, unless one curve has more (128 MiB of
/// doubles; two metrics at most at once: 256 MiB, the bound of the results rank 0 holds between
/// checkpoints): bounds rank 0's memory whatever the number of curves. Each block reads the
/// journal's index again (CubeWriter::read_values), so blocks are large: 6 at 10^8 runs.
constexpr std::int64_t kBlockCases = std::int64_t{1} << 24;

/// visit(block, first_curve, end_curve) for each block of whole curves, in order, holding the
/// metrics `metrics` of that block only.
template <class Visit>
void for_each_curve_block(const cube::CubeWriter& writer, std::int64_t curves, std::int64_t runs_per_curve,
                          const std::vector<std::string>& metrics, Visit visit) {
  const std::int64_t per_block = std::max<std::int64_t>(1, kBlockCases / std::max<std::int64_t>(runs_per_curve, 1));
  for (std::int64_t first = 0; first < curves; first += per_block) {
    const std::int64_t end = std::min(curves, first + per_block);
    visit(CurveBlock(writer, runs_per_curve, first, end, metrics), first, end);
  }
}

/// Each stored run of curve `c`, in order, up to the first one not stored (a curve's runs are
/// stored as a prefix: it has at most one run in flight, and a worker searching a whole chunk
/// reports its curves' runs in order), as add(point, intensity, verdict). The block's metric
/// 0 is the intensity, 1 θ_max when `with_theta`.
template <class Add>
void stored_runs(std::int64_t c, std::int64_t runs, const cube::StatusBook& status, const CurveBlock& block,
                 bool with_theta, const CollapseRule& rule, Add add) {
  for (std::int64_t k = 0; k < runs; ++k) {
    const std::int64_t i = c * runs + k;
    if (status[static_cast<std::size_t>(i)] == cube::kStatusNotRun) break;
    add(static_cast<int>(k), block.value(0, i), rule(status[static_cast<std::size_t>(i)], with_theta ? block.value(1, i) : std::nan("")));
  }
}

/// 1 for each status code schema::unresolved_count counts (the one rule), by code's byte: a
/// curve's few runs are counted by table, not by that function's pass over every code.
std::array<std::int64_t, 256> unresolved_codes() {
  std::array<std::int64_t, 256> table{};
  for (int code = -128; code < 128; ++code) {
    const auto s = static_cast<std::int8_t>(code);
    table[static_cast<std::uint8_t>(s)] = schema::unresolved_count(std::span<const std::int8_t>(&s, 1));
  }
  return table;
}

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
  const auto& status = writer.statuses();
  if (writer.done_count() == 0) return curves;  // a new cube: nothing stored to replay
  const bool with_theta = rule.uses_theta();
  std::vector<std::string> metrics{schema::kIdaIntensity};
  if (with_theta) metrics.emplace_back(metric::theta_max().name);
  const auto runs = static_cast<std::int64_t>(space.ida_runs());
  for_each_curve_block(writer, space.curves(), runs, metrics, [&](const CurveBlock& block, std::int64_t first, std::int64_t end) {
    for (std::int64_t c = first; c < end; ++c)
      stored_runs(c, runs, status, block, with_theta, rule, [&](int k, double x, ida::RunVerdict verdict) {
        curves->replay(static_cast<std::size_t>(c), k, x, verdict);
      });
  });
  return curves;
}

std::vector<std::size_t> ida_unit_chunks(const cube::CubeWriter& writer, const std::vector<std::int64_t>& histories,
                                         const CaseSpace& space, std::int64_t first_curve, std::int64_t last_curve,
                                         std::size_t least, std::size_t tail) {
  const auto runs = static_cast<std::int64_t>(space.ida_runs());
  const auto& grid = writer.grid();
  std::vector<std::size_t> units;
  for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
    const auto r = grid.range(c);
    if (runs <= 0 || r.first % runs != 0 || r.count % runs != 0) continue;  // not whole curves
    if (r.first < first_curve * runs || r.first + r.count > last_curve * runs) continue;
    if (writer.chunk_done(c) != 0) continue;  // counted per chunk by the writer, as whole_chunks asks
    if (std::any_of(histories.begin(), histories.end(), [&](std::int64_t i) { return i >= r.first && i < r.first + r.count; }))
      continue;
    units.push_back(c);
  }
  if (units.size() < least || units.size() < tail) return {};
  units.resize(units.size() - tail);
  return units;
}

parallel::UnitEvaluator ida_unit_evaluator(const Study& study) {
  return [settings = study.ida->search(), collapsed = collapse_test(study)](
             std::int64_t, std::span<const parallel::WorkItem> cases, const parallel::UnitCases& run) {
    if (cases.empty()) return;
    // A unit is whole curves (ida_unit_chunks), its cases consecutive: curve c's points are
    // c · max_runs + k.
    const std::int64_t first = cases.front().case_index;
    const std::int64_t end = first + static_cast<std::int64_t>(cases.size());
    for (std::int64_t c = first / settings.max_runs; c < end / settings.max_runs; ++c) {
      ida::IdaSearch search(settings);
      const bool whole = ida::search_curve(search, c, settings.max_runs, [&](std::int64_t index, double intensity) -> std::optional<ida::RunVerdict> {
        const parallel::WorkItem item{index, intensity};
        const auto outcome = run(std::span<const parallel::WorkItem>(&item, 1));
        if (!outcome) return std::nullopt;  // the run is being stopped
        return collapsed(outcome->front());
      });
      if (!whole) return;
    }
  };
}

IdaWork::IdaWork(std::unique_ptr<ida::IdaCurves> curves, std::vector<std::size_t> units, const cube::ChunkGrid& grid)
    : curves_(std::move(curves)), units_(std::move(units)), grid_(grid) {
  std::sort(units_.begin(), units_.end());
  const auto runs = static_cast<std::int64_t>(curves_->max_runs());
  for (const std::size_t chunk : units_) {
    const auto r = grid_.range(chunk);
    for (std::int64_t c = r.first / runs; c < (r.first + r.count) / runs; ++c) curves_->skip(static_cast<std::size_t>(c));
  }
}

parallel::WorkBatch IdaWork::take(bool in_process_worker) {
  if (next_ == units_.size()) return curves_->take(in_process_worker);
  const std::size_t chunk = units_[next_++];
  const auto r = grid_.range(chunk);
  return parallel::unit_range_batch(static_cast<std::int64_t>(chunk), r.first, r.count);
}

bool IdaWork::in_unit(std::size_t curve) const {
  if (units_.empty()) return false;
  const std::size_t chunk = grid_.chunk_of(ida::ida_case(static_cast<std::int64_t>(curve), 0, curves_->max_runs()));
  return std::binary_search(units_.begin(), units_.end(), chunk);
}

namespace {

/// The summaries of each curve (collapse and last safe intensities, runs, state, unresolved
/// runs) as side variables. `replay`: the curves searched by workers are replayed from what
/// is stored (their runs' statuses, in the cube, its journal or the workers' parts; θ_max
/// only where the collapse rule reads it, a block of curves at a time): the search the worker
/// made, each run's verdict read back, one curve at a time. The intensities are the search's
/// own, as the worker's were: no value of the cube is read for them.
void store_curve_summaries(const Study& study, const IdaWork& work, cube::CubeWriter& writer, bool replay) {
  const ida::IdaCurves& curves = work.curves();
  std::vector<double> collapse, safe, runs, state, unresolved;
  const double none = std::nan("");  // a curve another shard computes: nothing known here
  const auto& status = writer.statuses();
  const auto points = static_cast<std::size_t>(curves.max_runs());
  const CollapseRule rule(study);
  const bool with_theta = replay && rule.uses_theta();
  const std::vector<std::string> metrics = with_theta ? std::vector<std::string>{std::string(metric::theta_max().name)}
                                                      : std::vector<std::string>{};
  const auto settings = study.ida->search();
  ida::IdaSearch replayed(settings);
  const auto unresolved_of = unresolved_codes();
  const auto curve_count = static_cast<std::int64_t>(curves.curves());
  for_each_curve_block(writer, curve_count, settings.max_runs, metrics, [&](const CurveBlock& block, std::int64_t first, std::int64_t end) {
    for (auto c = static_cast<std::size_t>(first); c < static_cast<std::size_t>(end); ++c) {
      const bool unit = work.in_unit(c);
      const bool here = unit ? replay : !curves.skipped(c);
      const ida::IdaSearch* curve = &curves.curve(c);
      if (unit && replay) {
        replayed.restart();
        ida::search_curve(replayed, static_cast<std::int64_t>(c), settings.max_runs,
                          [&](std::int64_t i, double) -> std::optional<ida::RunVerdict> {
                            const auto k = static_cast<std::size_t>(i);
                            if (status[k] == cube::kStatusNotRun) return std::nullopt;  // the curve's last stored run
                            return rule(status[k], with_theta ? block.value(0, i) : std::nan(""));
                          });
        curve = &replayed;
      }
      collapse.push_back(here ? curve->collapse_intensity() : none);
      safe.push_back(here ? curve->last_safe_intensity() : none);
      runs.push_back(here ? static_cast<double>(curve->runs()) : none);
      // A state only once the curve is done: a curve still running is neither.
      state.push_back(here && curve->done() ? static_cast<double>(curve->state()) : none);
      std::int64_t unresolved_runs = 0;
      for (std::size_t k = 0; here && k < points; ++k) unresolved_runs += unresolved_of[static_cast<std::uint8_t>(status[c * points + k])];
      unresolved.push_back(here ? static_cast<double>(unresolved_runs) : none);
    }
  });
  writer.store_side(schema::kCollapseIntensity, std::move(collapse));
  writer.store_side(schema::kLastSafeIntensity, std::move(safe));
  writer.store_side(schema::kIdaRuns, std::move(runs));
  writer.store_side(schema::kCurveState, std::move(state));
  writer.store_side(schema::kUnresolvedRuns, std::move(unresolved));
}

/// The band of intensities whose verdicts failed the perturbation test, per curve, read a
/// block of curves at a time.
void store_unstable_band(const ida::IdaCurves& curves, cube::CubeWriter& writer) {
  const auto points = static_cast<std::int64_t>(curves.max_runs());
  std::vector<double> from(curves.curves(), std::nan("")), to(curves.curves(), std::nan(""));
  const std::vector<std::string> metrics{std::string(metric::status_stable().name), schema::kIdaIntensity};
  constexpr std::size_t kStable = 0, kIntensity = 1;  // their places in `metrics`
  for_each_curve_block(writer, static_cast<std::int64_t>(curves.curves()), points, metrics,
                       [&](const CurveBlock& block, std::int64_t first, std::int64_t end) {
                         for (std::int64_t c = first; c < end; ++c)
                           for (std::int64_t i = c * points; i < (c + 1) * points; ++i) {
                             if (block.value(kStable, i) != 0.0) continue;
                             const double x = block.value(kIntensity, i);
                             auto& low = from[static_cast<std::size_t>(c)];
                             auto& high = to[static_cast<std::size_t>(c)];
                             if (!(x >= low)) low = x;
                             if (!(x <= high)) high = x;
                           }
                       });
  writer.store_side(schema::kUnstableFrom, std::move(from));
  writer.store_side(schema::kUnstableTo, std::move(to));
}

}  // namespace

void store_ida_summaries(const Study& study, const IdaWork& work, cube::CubeWriter& writer, bool final) {
  const bool replay = final && work.has_units();
  if (replay) writer.take_parts();  // the workers' chunks: their statuses join the writer's
  store_curve_summaries(study, work, writer, replay);
  if (study.solver.verdict_check) store_unstable_band(work.curves(), writer);
}

}  // namespace pcrf::run
