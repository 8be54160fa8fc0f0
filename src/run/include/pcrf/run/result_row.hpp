/// \file result_row.hpp
/// \brief The columns of a case's result row: which value sits where in the row a worker
/// sends and the cube stores. One type owns the order, so the case runner that fills a row,
/// the cube layout that declares its variables and the IDA that reads verdicts agree on it.
///
/// Columns: the stored metrics (Study::metrics, in that order), then in an IDA the run's
/// intensity (`ida_intensity`) and the factor its record was scaled by (`scale_factor`).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

class ResultColumns {
 public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  explicit ResultColumns(const Study& study);

  /// Number of columns.
  std::size_t width() const { return variables_.size(); }
  /// The stored metrics: columns 0 … metrics().size() − 1.
  const std::vector<const MetricInfo*>& metrics() const { return metrics_; }
  /// Column of stored metric `name`; npos when the study does not store it.
  std::size_t metric_column(std::string_view name) const;
  /// Columns of an IDA run's intensity and scale factor (the level axis' row variables);
  /// npos outside an IDA.
  std::size_t ida_intensity_column() const { return column_of(schema::kIdaIntensity, metrics_.size()); }
  std::size_t scale_factor_column() const { return column_of(schema::kScaleFactor, metrics_.size()); }
  /// The cube's variable of each column, in column order.
  const std::vector<cube::MetricVariable>& variables() const { return variables_; }

  /// A row of NaN, `width()` wide.
  std::vector<double> empty_row() const;
  /// Sets the metric columns of `row` to NaN (a failed case); an IDA run's intensity and
  /// factor stay: they are known before the run.
  void clear_metrics(std::vector<double>& row) const;

 private:
  /// Column of variable `name` at or after column `from`, or npos.
  std::size_t column_of(std::string_view name, std::size_t from) const;

  std::vector<const MetricInfo*> metrics_;
  std::vector<cube::MetricVariable> variables_;
};

}  // namespace pcrf::run
