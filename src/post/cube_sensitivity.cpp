// Sobol' indices of a saltelli cube (see cube_sensitivity.hpp).
#include "pcrf/user_error.hpp"
#include "pcrf/post/cube_sensitivity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {

namespace vocabulary = schema;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A frame's output per case: the metric, or the collapse indicator.
std::vector<double> outputs(const cube::CubeReader& cube, const std::string& metric) {
  const auto status = cube.read_status();
  if (metric != "collapse") {
    auto values = cube.read_metric(metric);
    for (std::size_t i = 0; i < values.size(); ++i)  // a case without a verdict (or unresolved) has no output
      if (status[i] == cube::kStatusNotRun || status[i] >= static_cast<std::int8_t>(CaseStatus::kSolverFailure) ||
          is_unresolved(static_cast<CaseStatus>(status[i])))
        values[i] = kNaN;
    return values;
  }
  std::vector<double> values(status.size(), kNaN);
  for (std::size_t i = 0; i < status.size(); ++i) {
    const auto s = static_cast<CaseStatus>(status[i]);
    if (has_verdict(s)) values[i] = is_collapse(s) ? 1.0 : 0.0;
  }
  return values;
}

}  // namespace

std::vector<SensitivityGroup> cube_sensitivity(const cube::CubeReader& cube, const std::string& metric,
                                               const std::vector<cube::Selector>& selectors, bool by_record) {
  const auto& layout = cube.layout();
  const cube::Coordinate* blocks = layout.find_coordinate(vocabulary::kSaltelliBlock);
  const cube::Coordinate* samples = layout.find_coordinate(vocabulary::kSaltelliSample);
  if (blocks == nullptr || samples == nullptr)
    throw cube::CubeError("is not a saltelli design (its cases carry no saltelli_block): run a study with "
                          "[plan] kind = \"saltelli\"");
  // The varied parameters, in design order: the AB_<parameter> blocks of sample 0.
  std::vector<std::string> parameters;
  for (std::size_t c = 0; c < blocks->size(); ++c)
    if (samples->numbers[c] == 0.0 && blocks->strings[c].rfind("AB_", 0) == 0) parameters.push_back(blocks->strings[c].substr(3));
  const std::size_t d = parameters.size();
  const auto n = static_cast<std::size_t>(blocks->size() / (d + 2));

  const auto values = outputs(cube, metric);
  const auto selected = cube::select_cases(layout, selectors);
  const auto shape = layout.shape();
  const std::size_t record_dim = 0, level_dim = 1, case_dim = shape.size() - 1;
  const std::size_t records = shape[record_dim];
  // output[record][case], from the one selected level
  std::vector<std::vector<double>> y(records, std::vector<double>(blocks->size(), kNaN));
  std::vector<bool> level_used(shape[level_dim], false);
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    if (!selected[static_cast<std::size_t>(i)]) continue;
    const auto c = unravel(i, shape);
    level_used[c[level_dim]] = true;
    y[c[record_dim]][c[case_dim]] = values[static_cast<std::size_t>(i)];
  }
  if (std::count(level_used.begin(), level_used.end(), true) > 1)
    throw UserError(Where{}, cube.file().string() + ": has several values of '" + layout.dimensions[level_dim].name +
                                 "': pick one with {} " + layout.dimensions[level_dim].name + "=VALUE", {"where"});

  auto group_of = [&](const std::string& name, const std::vector<std::size_t>& which) {
    SensitivityGroup g{name, parameters, {}, 0, 0};
    analysis::SaltelliOutputs o{{}, {}, std::vector<std::vector<double>>(d)};
    std::vector<double> row(d + 2);
    for (std::size_t j = 0; j < n; ++j) {
      bool complete = true;
      for (std::size_t b = 0; b < d + 2; ++b) {
        double sum = 0.0;
        for (std::size_t r : which) sum += y[r][j * (d + 2) + b];
        row[b] = sum / static_cast<double>(which.size());  // NaN when any record has none
        complete = complete && std::isfinite(row[b]);
      }
      if (!complete) {
        ++g.dropped;
        continue;
      }
      o.f_a.push_back(row[0]);
      o.f_b.push_back(row[1]);
      for (std::size_t i = 0; i < d; ++i) o.f_ab[i].push_back(row[2 + i]);
    }
    g.samples = o.f_a.size();
    if (g.samples >= 2) g.indices = analysis::sobol_indices(o);
    return g;
  };
  std::vector<SensitivityGroup> groups;
  if (by_record) {
    const auto* names = layout.find_coordinate(vocabulary::kRecord);
    for (std::size_t r = 0; r < records; ++r) groups.push_back(group_of(names->label(r), {r}));
  } else {
    std::vector<std::size_t> all(records);
    for (std::size_t r = 0; r < records; ++r) all[r] = r;
    groups.push_back(group_of("all", all));
  }
  return groups;
}

}  // namespace pcrf::post
