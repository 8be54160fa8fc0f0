// The columns of a case's result row (see result_row.hpp).
#include "pcrf/study/result_row.hpp"

#include <algorithm>
#include <limits>

#include "pcrf/study/cube_vocabulary.hpp"

namespace pcrf::study {

ResultColumns::ResultColumns(const Study& study) : ida_(study.ida.has_value()) {
  for (const auto& name : study.metrics) {
    const MetricInfo* m = find_metric(name);
    metrics_.push_back(m);
    variables_.push_back({name, std::string(m->units), std::string(m->description)});
  }
  if (!ida_) return;
  const IntensitySpec& im = *study.intensity;  // the parser requires it with [ida]
  const std::string measure = intensity_long_name(im.measure, im.period_s, im.damping);
  variables_.push_back({vocabulary::kIdaIntensity, std::string(intensity_units(im.measure)), "intensity of the run: " + measure});
  variables_.push_back({vocabulary::kScaleFactor, "1", "factor applied to the record's accelerations for the run"});
}

std::size_t ResultColumns::metric_column(std::string_view name) const {
  const auto it = std::find_if(metrics_.begin(), metrics_.end(), [&](const MetricInfo* m) { return m->name == name; });
  return it == metrics_.end() ? npos : static_cast<std::size_t>(it - metrics_.begin());
}

std::vector<double> ResultColumns::empty_row() const {
  return std::vector<double>(width(), std::numeric_limits<double>::quiet_NaN());
}

void ResultColumns::clear_metrics(std::vector<double>& row) const {
  std::fill(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(metrics_.size()), std::numeric_limits<double>::quiet_NaN());
}

}  // namespace pcrf::study
