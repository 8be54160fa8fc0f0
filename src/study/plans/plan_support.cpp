// What the plans share (see plan_support.hpp and plan.hpp).
#include "study/plans/plan_support.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>

#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/user_error.hpp"
#include "study/axis_fields.hpp"

namespace pcrf::study {

std::string Plan::canonical_heading() const {
  return "include_base=1";  // one-at-a-time's option, written by every plan since the first fingerprints
}

void fail_history(const HistoryRequest& request, const std::string& problem) {
  throw UserError(request.declared_at, "history \"" + request.label + "\": " + problem);
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

std::vector<std::vector<double>> read_parameter_axes(const PlanInput& input) {
  std::vector<std::vector<double>> axes(input.model.parameters.size());
  if (input.axes == nullptr) return axes;
  refuse_other_scenes(*input.axes, input.model);
  for (std::size_t p : axis_parameters(input.model)) {
    const auto& parameter = input.model.parameters[p];
    if (!input.axes->has(parameter.name)) continue;
    axes[p] = read_values(*input.axes, parameter.name);
    check_axis(*input.axes, parameter.name, axes[p], &parameter);
  }
  std::vector<std::string_view> swept;
  for (auto key : input.model.exclusive)
    if (input.axes->has(key)) swept.push_back(key);
  if (swept.size() > 1)
    input.axes->fail(swept.back(), "give either " + std::string(swept.front()) + " or " + std::string(swept.back()) + ", not both");
  return axes;
}

std::vector<std::size_t> axis_parameters(const SceneModel& model) {
  std::vector<std::size_t> indices;
  for (std::size_t k = 0; k < model.parameters.size(); ++k)
    if (model.parameters[k].axis) indices.push_back(k);
  return indices;
}

void describe_axes(std::ostream& out, const SceneModel& model, const std::vector<std::vector<double>>& axes) {
  for (std::size_t p : axis_parameters(model)) {
    out << "axis " << model.parameters[p].name;
    if (!axes.empty())
      for (double v : axes[p]) out << ' ' << v;
    out << '\n';
  }
}

void describe_parameters(std::ostream& out, const SceneModel& model, const ScenePoint& frame) {
  for (std::size_t k = 0; k < model.parameters.size(); ++k) out << ' ' << model.parameters[k].name << '=' << frame[k];
}

PointPlan::PointPlan(const SceneModel& model, std::vector<Point> points)
    : model_(&model), points_(std::move(points)), dimensions_{{schema::kCase, points_.size()}} {
  for (auto& p : points_)
    if (p.model == nullptr) p.model = model_;
}

PointPlan::PointPlan(const SceneModel& model, std::size_t count)
    : model_(&model), dimensions_{{schema::kCase, count}} {}

SceneSpec PointPlan::frame_at(std::span<const std::size_t> coordinates) const {
  const std::size_t i = coordinates[0];
  const SceneModel& m = point_model(i);
  ScenePoint values(m.parameters.size());
  frame_values(i, values);
  return {&m, std::move(values)};
}

void PointPlan::frame_values(std::size_t i, std::span<double> values) const {
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = point_value(i, k);
}

std::vector<SceneSpec> PointPlan::frames() const {
  std::vector<SceneSpec> frames;
  frames.reserve(point_count());
  for (std::size_t i = 0; i < point_count(); ++i) frames.push_back(frame_at(std::span<const std::size_t>(&i, 1)));
  return frames;
}

std::vector<cube::Coordinate> PointPlan::coordinates() const {
  // Every coordinate along `case` is computed from the case number when the writer asks
  // (cube::Coordinate::number_at, text_at), piece by piece: nothing per case is held, however
  // many cases (issue 38). The writer asks only while it creates the cube, when this plan is alive.
  const std::size_t n = point_count();
  const auto computed_number = [n](cube::Coordinate c, std::function<double(std::size_t)> at) {
    c.number_at = std::move(at);
    c.computed_size = n;
    return c;
  };
  const auto computed_text = [n](cube::Coordinate c, std::function<std::string(std::size_t)> at) {
    c.text_at = std::move(at);
    c.computed_size = n;
    return c;
  };
  std::vector<cube::Coordinate> coords{computed_number(
      number_coordinate(schema::kCase, schema::kCase, "", "frame number", {}),
      [](std::size_t i) { return static_cast<double>(i); })};
  coords.back().is_index = true;
  if (stores_labels())
    coords.push_back(computed_text(text_coordinate(schema::kCaseLabel, schema::kCase, "frame label", {}),
                                   [this](std::size_t i) { return point_label(i); }));
  // The models present: the plan's first, then the others in catalogue order.
  std::vector<const SceneModel*> present{model_};
  std::vector<char> used(scene_models().size(), 0);
  // Held frames say their model; computed ones are all of the plan's (no pass over every case:
  // 42 instructions a case on each rank that makes the cube's layout, issue 38).
  for (const Point& p : points_) used[static_cast<std::size_t>(p.model - scene_models().data())] = 1;
  for (const auto& m : scene_models())
    if (&m != model_ && used[static_cast<std::size_t>(&m - scene_models().data())]) present.push_back(&m);
  if (present.size() > 1)
    coords.push_back(computed_text(text_coordinate(schema::kSceneModel, schema::kCase, "scene model of the frame", {}),
                                   [this](std::size_t i) { return std::string(point_model(i).name); }));
  for (auto& c : extra_coordinates()) coords.push_back(std::move(c));
  // The plan's model's other parameters are the cube's attributes (frame_h_m, …); another
  // model has no base point, so all of its parameters are coordinates.
  std::vector<std::string_view> written;
  for (const SceneModel* m : present)
    for (std::size_t k = 0; k < m->parameters.size(); ++k) {
      const auto& parameter = m->parameters[k];
      if (m == model_ && !parameter.axis) continue;
      if (std::find(written.begin(), written.end(), parameter.name) != written.end()) continue;
      written.push_back(parameter.name);
      // SceneSpec::value without a frame made and a search by name per case: the position
      // of the parameter in each model present, found once.
      std::vector<std::size_t> position(present.size());
      for (std::size_t j = 0; j < present.size(); ++j) position[j] = present[j]->index(parameter.name);
      auto value = [this, present, position](std::size_t i) {
        const SceneModel* own = &point_model(i);
        const std::size_t j = static_cast<std::size_t>(std::find(present.begin(), present.end(), own) - present.begin());
        return position[j] == std::string::npos ? std::numeric_limits<double>::quiet_NaN()  // as SceneSpec::value
                                                : point_value(i, position[j]);
      };
      coords.push_back(computed_number(number_coordinate(std::string(parameter.name), schema::kCase,
                                                         std::string(parameter.units), std::string(parameter.long_name), {}),
                                       std::move(value)));
      // Frames all of the plan's model (every plan that computes them): a piece at once.
      if (present.size() == 1)
        coords.back().numbers_from = [this, k](std::size_t first, std::span<double> out) { point_values(first, k, out); };
    }
  return coords;
}

void PointPlan::point_values(std::size_t first, std::size_t k, std::span<double> out) const {
  for (std::size_t m = 0; m < out.size(); ++m) out[m] = point_value(first + m, k);
}

std::vector<std::size_t> PointPlan::locate(const HistoryRequest& request) const {
  if (!request.case_label) return {pick_single(request, point_count(), schema::kCase)};
  for (std::size_t i = 0; i < point_count(); ++i)
    if (point_label(i) == *request.case_label) return {i};
  fail_history(request, "no case is labelled \"" + *request.case_label + "\"");
  return {};  // not reached: fail_history throws
}

std::string PointPlan::history_key_problem(std::string_view key) const {
  if (key == schema::kCase) return "";
  return "plan \"" + std::string(name()) + "\" selects cases by `case` label";
}

}  // namespace detail
}  // namespace pcrf::study
