/// \file level_axis.hpp
/// \brief How hard each record shakes: the study's second axis. Scale factors (`scale`),
/// intensity stripes (`intensity`: every record scaled to every intensity), or an IDA (each
/// curve's runs choose their intensities as they go: no level dimension before the frame
/// dimensions, `ida_point`, the runs of a curve, after them).
///
/// One object answers what CaseSpace, the cube layout, the result row and the fingerprint
/// need of the axis; make_level_axis is the one place that tells the three apart.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {

class LevelAxis {
 public:
  virtual ~LevelAxis() = default;

  /// Dimensions between `record` and the frame dimensions (`scale` or `intensity`).
  virtual std::vector<cube::Dimension> leading_dimensions() const = 0;
  /// Dimensions after the frame dimensions (an IDA's `ida_point`).
  virtual std::vector<cube::Dimension> trailing_dimensions() const { return {}; }
  /// The values along the leading dimension; empty when there is none (a case's level then
  /// comes with its work item).
  virtual const std::vector<double>& levels() const = 0;

  /// The axis' coordinates along `record` (a record's unscaled intensity) and along the
  /// leading dimensions, and their side variables; `records` gives the records' intensities.
  virtual void add_leading(cube::CubeLayout& layout, RecordCache& records) const = 0;
  /// Coordinates along the trailing dimensions and side variables per curve, over
  /// `curve_dimensions` (every dimension but the trailing ones).
  virtual void add_trailing(cube::CubeLayout& /*layout*/, const std::vector<std::string>& /*curve_dimensions*/) const {}
  /// Result-row columns after the metrics (ResultColumns): an IDA run's intensity and factor.
  virtual std::vector<cube::MetricVariable> row_variables() const { return {}; }

  /// The axis' line of the study's canonical text, without its newline: "scale 1 2" or
  /// "intensity 0.5 1", numbers at the stream's precision.
  virtual void describe(std::ostream& out) const = 0;
};

/// The name of the text coordinate along `record` that names the records of stripe `stripe`
/// (from 0) of a [selection] study: "selected_record_0", …
std::string selected_record_name(std::size_t stripe);

/// The axis a study gives: [ida], else [axes] intensity with [intensity], else [axes] scale.
std::shared_ptr<const LevelAxis> make_level_axis(const Study& study);

}  // namespace pcrf::study
