// The columns of a case's result row (see result_row.hpp).
#include "pcrf/run/result_row.hpp"

#include <algorithm>
#include <limits>

#include "pcrf/parallel/result_batch.hpp"
#include "pcrf/study/level_axis.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

ResultColumns::ResultColumns(const Study& study) {
  for (const auto& name : study.metrics) {
    const MetricInfo* m = find_metric(name);
    metrics_.push_back(m);
    variables_.push_back({name, std::string(m->units), std::string(m->description)});
  }
  for (auto& v : make_level_axis(study)->row_variables()) variables_.push_back(std::move(v));
}

std::size_t ResultColumns::metric_column(std::string_view name) const {
  const auto it = std::find_if(metrics_.begin(), metrics_.end(), [&](const MetricInfo* m) { return m->name == name; });
  return it == metrics_.end() ? npos : static_cast<std::size_t>(it - metrics_.begin());
}

std::size_t ResultColumns::column_of(std::string_view name, std::size_t from) const {
  for (std::size_t c = from; c < variables_.size(); ++c)
    if (variables_[c].name == name) return c;
  return npos;
}

std::vector<double> ResultColumns::empty_row() const {
  return parallel::pooled_row(width(), std::numeric_limits<double>::quiet_NaN());  // a worker's, reused
}

void ResultColumns::clear_metrics(std::vector<double>& row) const {
  std::fill(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(metrics_.size()), std::numeric_limits<double>::quiet_NaN());
}

}  // namespace pcrf::run
