// What the plans share (see plan_support.hpp and plan.hpp).
#include "study/plans/plan_support.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "pcrf/study/cube_vocabulary.hpp"
#include "pcrf/study/study_error.hpp"
#include "study/axis_fields.hpp"

namespace pcrf::study {

std::string Plan::canonical_heading() const {
  return "include_base=1";  // one-at-a-time's option, written by every plan since the first fingerprints
}

void fail_history(const HistoryRequest& request, const std::string& problem) {
  throw StudyError(request.declared_at + ": outputs.histories \"" + request.label + "\": " + problem);
}

std::size_t pick_single(const HistoryRequest& request, std::size_t size, const std::string& key) {
  if (size != 1) fail_history(request, "the " + key + " axis has " + std::to_string(size) + " values: give `" + key + "`");
  return 0;
}

std::size_t find_value(const std::vector<double>& axis, double value) {
  for (std::size_t i = 0; i < axis.size(); ++i)
    if (std::fabs(axis[i] - value) <= 1e-12 * std::max(std::fabs(axis[i]), std::fabs(value))) return i;
  return std::string::npos;
}

cube::Coordinate number_coordinate(std::string name, std::string dimension, std::string units, std::string long_name,
                                   std::vector<double> values) {
  cube::Coordinate c;
  c.name = std::move(name);
  c.dimension = std::move(dimension);
  c.units = std::move(units);
  c.long_name = std::move(long_name);
  c.numbers = std::move(values);
  return c;
}

cube::Coordinate text_coordinate(std::string name, std::string dimension, std::string long_name,
                                 std::vector<std::string> values) {
  cube::Coordinate c;
  c.name = std::move(name);
  c.dimension = std::move(dimension);
  c.long_name = std::move(long_name);
  c.strings = std::move(values);
  c.is_text = true;
  return c;
}

namespace detail {

std::array<std::vector<double>, kParameterCount> read_parameter_axes(const PlanInput& input) {
  std::array<std::vector<double>, kParameterCount> axes;
  for (std::size_t p = 0; p < kParameterCount && input.axes != nullptr; ++p) {
    const auto key = all_parameters()[p].name;
    if (!input.axes->has(key)) continue;
    axes[p] = read_values(*input.axes, key);
    check_axis(*input.axes, key, axes[p], p);
  }
  return axes;
}

void describe_axes(std::ostream& out, const std::array<std::vector<double>, kParameterCount>& axes) {
  for (std::size_t p = 0; p < kParameterCount; ++p) {
    out << "axis " << all_parameters()[p].name;
    for (double v : axes[p]) out << ' ' << v;
    out << '\n';
  }
}

void describe_parameters(std::ostream& out, const FrameParameters& frame) {
  for (const auto& info : all_parameters()) out << ' ' << info.name << '=' << frame.*info.member;
  out << " h_m=" << frame.h_m << " m_c_kg=" << frame.m_c_kg;
}

PointPlan::PointPlan(std::vector<Point> points)
    : points_(std::move(points)), dimensions_{{vocabulary::kCase, points_.size()}} {}

FrameParameters PointPlan::frame_at(std::span<const std::size_t> coordinates) const {
  return points_[coordinates[0]].parameters;
}

std::vector<FrameParameters> PointPlan::frames() const {
  std::vector<FrameParameters> frames;
  for (const auto& p : points_) frames.push_back(p.parameters);
  return frames;
}

std::vector<cube::Coordinate> PointPlan::coordinates() const {
  std::vector<double> index(points_.size());
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    index[i] = static_cast<double>(i);
    labels.push_back(points_[i].label);
  }
  std::vector<cube::Coordinate> coords{number_coordinate(vocabulary::kCase, vocabulary::kCase, "", "frame number", index)};
  coords.back().is_index = true;
  coords.push_back(text_coordinate(vocabulary::kCaseLabel, vocabulary::kCase, "frame label", labels));
  for (auto& c : extra_coordinates()) coords.push_back(std::move(c));
  for (const auto& info : all_parameters()) {
    std::vector<double> values;
    for (const auto& p : points_) values.push_back(p.parameters.*info.member);
    coords.push_back(number_coordinate(std::string(info.name), vocabulary::kCase, "1", std::string(info.long_name), values));
  }
  return coords;
}

std::vector<std::size_t> PointPlan::locate(const HistoryRequest& request) const {
  if (!request.case_label) return {pick_single(request, points_.size(), vocabulary::kCase)};
  const auto it = std::find_if(points_.begin(), points_.end(), [&](const Point& p) { return p.label == *request.case_label; });
  if (it == points_.end()) fail_history(request, "no case is labelled \"" + *request.case_label + "\"");
  return {static_cast<std::size_t>(it - points_.begin())};
}

std::string PointPlan::history_key_problem(std::string_view key) const {
  if (key == vocabulary::kCase) return "";
  return "plan \"" + std::string(name()) + "\" selects cases by `case` label";
}

}  // namespace detail
}  // namespace pcrf::study
