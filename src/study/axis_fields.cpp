// Axis values and frame parameters from study-file tables (see axis_fields.hpp).
#include "study/axis_fields.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pcrf::study::detail {
namespace {

std::vector<double> read_range(const toml::table& table, const std::vector<std::string>& path, const std::string& file) {
  Fields range(table, path, file, {"from", "to", "count", "spacing"});
  for (auto key : {"from", "to", "count"})
    if (!range.has(key)) range.fail(key, "a range needs from, to and count");
  const double from = *range.number("from");
  const double to = *range.number("to");
  const auto count = *range.integer("count");
  const std::string spacing = range.text("spacing").value_or("linear");
  if (count < 1) range.fail("count", "must be at least 1 (got " + std::to_string(count) + ")");
  // The values are made here: a count no axis needs is refused before it is allocated.
  constexpr std::int64_t kMaxAxisValues = 10000000;
  if (count > kMaxAxisValues)
    range.fail("count", "at most " + std::to_string(kMaxAxisValues) + " values on one axis (got " + std::to_string(count) + ")");
  if (to < from) range.fail("to", "the range runs backwards (to " + number_text(to) + " < from " + number_text(from) + ")");
  if (count == 1 && to != from) range.fail("count", "a range from " + number_text(from) + " to " + number_text(to) + " needs at least 2 values");
  if (count > 1 && to == from) range.fail("count", "an empty range (from = to) has one value: use count = 1");
  if (spacing != "linear" && spacing != "log") range.fail("spacing", "expected \"linear\" or \"log\", got \"" + spacing + "\"");
  if (spacing == "log" && from <= 0.0) range.fail("from", "a log range must start above 0");
  std::vector<double> values(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double t = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    values[i] = shortest_decimal_near(spacing == "log" ? from * std::pow(to / from, t) : from + t * (to - from));
  }
  values.front() = from;  // exact ends, whatever the rounding in between
  values.back() = to;
  return values;
}

}  // namespace

namespace {
std::vector<std::string_view> scene_keys(bool axis_only) {
  std::vector<std::string_view> keys;
  for (const auto& model : scene_models())
    for (const auto& p : model.parameters)
      if ((p.axis || !axis_only) && std::find(keys.begin(), keys.end(), p.name) == keys.end()) keys.push_back(p.name);
  return keys;
}
}  // namespace

std::vector<std::string_view> parameter_keys() { return scene_keys(true); }
std::vector<std::string_view> all_scene_keys() { return scene_keys(false); }

void refuse_other_scenes(const Fields& fields, const SceneModel& model) {
  for (auto key : all_scene_keys())
    if (fields.has(key) && model.index(key) == std::string::npos)
      fields.fail(key, "does not apply to model \"" + std::string(model.name) + "\" (it is a parameter of " +
                           models_taking(key) + "; this scene's: " + model.keys_text() + ")");
}

const SceneModel* read_model(const Fields& fields) {
  const auto name = fields.text("model");
  if (!name) return nullptr;
  try {
    return &scene_model(*name);
  } catch (const UserError& e) {  // the file and line of the key
    fields.fail("model", e.problem(Dialect::kStudy));
  }
}

void read_parameters(const Fields& fields, const SceneModel& model, ScenePoint& point, bool axis_only) {
  refuse_other_scenes(fields, model);
  for (std::size_t k = 0; k < model.parameters.size(); ++k) {
    const auto& p = model.parameters[k];
    if (!fields.has(p.name)) continue;
    if (axis_only && !p.axis) fields.fail(p.name, "is set once for every case, in [frame] or [base]");
    const double value = *fields.number(p.name);
    if (const auto problem = p.problem(value); !problem.empty()) fields.fail(p.name, "value " + number_text(value) + " " + problem);
    point[k] = value;
  }
  std::vector<std::string_view> given;
  for (auto key : model.exclusive)
    if (fields.has(key)) given.push_back(key);
  if (given.size() > 1)
    fields.fail(given.back(), "give either " + std::string(given.front()) + " or " + std::string(given.back()) + ", not both");
}

std::vector<std::string_view> with_parameter_keys(std::vector<std::string_view> keys) {
  for (auto key : parameter_keys()) keys.push_back(key);
  return keys;
}

std::vector<std::string_view> with_scene_keys(std::vector<std::string_view> keys) {
  for (auto key : all_scene_keys()) keys.push_back(key);
  return keys;
}

std::vector<double> read_values(const Fields& fields, std::string_view key) {
  const toml::node& node = *fields.node(key);
  const auto path = fields.path(key);
  if (node.is_number()) return {Fields::number_at(fields.file(), node, path)};
  if (const auto* table = node.as_table()) return read_range(*table, path, fields.file());
  const auto* array = node.as_array();
  if (array == nullptr)
    fields.fail(key, "expected a number, a list of numbers or a range {from, to, count}, got " +
                         Fields::type_name(node));
  if (array->empty()) fields.fail(key, "empty list");
  std::vector<double> values;
  for (std::size_t i = 0; i < array->size(); ++i)
    values.push_back(Fields::number_at(fields.file(), (*array)[i], fields.entry_path(key, i)));
  return values;
}

void check_axis(const Fields& fields, std::string_view key, const std::vector<double>& values,
                const SceneParameter* parameter) {
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  if (auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end())
    fields.fail(key, "value " + number_text(*dup) + " appears twice");
  for (double v : values) {
    const std::string problem = parameter != nullptr ? parameter->problem(v) : (v > 0.0 ? "" : "must be positive");
    if (!problem.empty()) fields.fail(key, "value " + number_text(v) + " " + problem);
  }
}

}  // namespace pcrf::study::detail
