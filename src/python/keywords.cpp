// A Python call's keyword arguments (see keywords.hpp).
#include "keywords.hpp"

#include "pcrf/api/frame_input.hpp"

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "pcrf/user_error.hpp"
#include "pcrf/model/scene_catalog.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/study/study.hpp"
#include "pcrf/units.hpp"
#include "pcrf/closest_word.hpp"

namespace pcrf::python {

template <class Target>
SettingValue setting_value(const Setting<Target>& s, const py::handle& value) {
  SettingValue v;
  if (py::isinstance<py::bool_>(value)) {
    v = value.cast<bool>();
  } else if (py::isinstance<py::str>(value)) {
    return api::checked_setting_text(s, value.cast<std::string>());
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string words;
    for (const auto& word : value) words += (words.empty() ? "" : ",") + py::str(word).cast<std::string>();
    return api::checked_setting_text(s, words);
  } else if (PyIndex_Check(value.ptr())) {
    v = static_cast<std::int64_t>(py::int_(py::reinterpret_borrow<py::object>(value)).cast<long long>());
  } else if (PyFloat_Check(value.ptr()) || py::hasattr(value, "__float__")) {
    v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  } else {
    throw UserError(std::string(s.key), "expected " + setting_kind_text(s));
  }
  return api::checked_setting(s, std::move(v));
}

template SettingValue setting_value(const Setting<PhysicsOptions>&, const py::handle&);
template SettingValue setting_value(const Setting<SolverSettings>&, const py::handle&);
template SettingValue setting_value(const Setting<IntensitySpec>&, const py::handle&);
template SettingValue setting_value(const Setting<study::RunOptions>&, const py::handle&);

Keywords::Keywords(const py::kwargs& keywords) {
  for (const auto& [key, value] : keywords)
    if (!value.is_none()) given_[key.cast<std::string>()] = py::reinterpret_borrow<py::object>(value);
}

std::optional<py::object> Keywords::take(const std::string& key) {
  known_.push_back(key);
  const auto it = given_.find(key);
  if (it == given_.end()) return std::nullopt;
  py::object value = it->second;
  given_.erase(it);
  return value;
}

std::optional<double> Keywords::take_number(const std::string& key) {
  const auto value = take(key);
  if (!value) return std::nullopt;
  try {
    return py::float_(*value).cast<double>();
  } catch (const py::error_already_set&) {
    throw UserError(key, "expected a number");
  }
}

std::optional<std::string> Keywords::take_text(const std::string& key) {
  const auto value = take(key);
  if (!value) return std::nullopt;
  if (py::hasattr(*value, "__fspath__")) return py::str(value->attr("__fspath__")()).cast<std::string>();
  if (!py::isinstance<py::str>(*value)) throw UserError(key, "expected a string or a path");
  return value->cast<std::string>();
}

std::vector<double> to_doubles(const py::handle& value, const std::string& what) {
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!array || array.ndim() != 1) throw UserError(what, "expected a one-dimensional array of numbers");
  return std::vector<double>(array.data(), array.data() + array.size());
}

namespace {

/// A component given as an array of accelerations in g: in m/s² as a reader converts a
/// file in g (the same product, so an array read from a file gives the same case).
GroundMotion motion_in_g(const std::string& name, double dt_s, const std::vector<double>& accel_g) {
  std::vector<double> accel_m_s2(accel_g.size());
  const double factor = to_m_s2(AccelUnit::kG);
  std::transform(accel_g.begin(), accel_g.end(), accel_m_s2.begin(), [factor](double a) { return a * factor; });
  return GroundMotion(name, dt_s, std::move(accel_m_s2));
}

}  // namespace

namespace {

/// An array's dt, checked as a reader checks a file's (sampling_problem).
void check_array_sampling(const std::string& name, double dt_s, std::size_t samples) {
  if (const auto problem = sampling_problem(dt_s, samples); !problem.empty())
    throw UserError("dt_s", problem + " (" + name + ")");
}

}  // namespace

StationRecord Keywords::take_station(std::vector<std::string>& notes, api::RecordInput* used,
                                     std::vector<std::string>* warnings) {
  const auto h1 = take("ground_accel_g");
  PerComponent<std::optional<py::object>> arrays;
  for (std::size_t i = 0; i < kComponentCount; ++i) arrays[i] = take(std::string(kStationComponents[i].array_keyword));
  const bool others = std::any_of(arrays.begin(), arrays.end(), [](const auto& a) { return a.has_value(); });
  api::RecordInput input;
  input.az1_deg = take_number("azimuth_deg");
  input.az2_deg = take_number("h2_azimuth_deg");
  const auto dt_s = take_number("dt_s");
  if (h1) {
    if (!dt_s) throw UserError("ground_accel_g", "needs {}, its sample interval [s]", {"dt_s"});
    std::vector<std::string> file_keys{"record"};
    for (const auto& c : kStationComponents) file_keys.emplace_back(c.keyword);
    file_keys.emplace_back("synthetic");
    for (const auto& file_key : file_keys)
      if (take(file_key)) throw UserError(Where{}, "give either {} or {}, not both", {"ground_accel_g", file_key});
    const std::string name = take_text("name").value_or("ground_accel_g");
    StationRecord station{motion_in_g(name, *dt_s, to_doubles(*h1, "ground_accel_g")), input.az1_deg, std::nullopt,
                          input.az2_deg, std::nullopt};
    const auto members = component_members<StationRecord>();
    for (std::size_t i = 0; i < kComponentCount; ++i) {
      const ComponentInfo& c = kStationComponents[i];
      if (arrays[i])
        station.*members[i] = motion_in_g(name + " (" + std::string(c.key) + ")", *dt_s,
                                          to_doubles(*arrays[i], std::string(c.array_keyword)));
    }
    notes = station.align();
    check_array_sampling(name, *dt_s, station.h1.size());
    if (warnings != nullptr) add_warnings(api::implausible_arrays(station), *warnings);
    return station;
  }
  if (others) {
    std::vector<std::string> keys;
    for (const auto& c : kStationComponents) keys.emplace_back(c.array_keyword);
    keys.emplace_back("ground_accel_g");
    throw UserError(Where{}, and_list(std::vector<std::string>(kComponentCount, "{}")) + " go with {}", keys);
  }
  input.file = take_text("record").value_or("");
  for (std::size_t i = 0; i < kComponentCount; ++i)
    input.component_files[i] = take_text(std::string(kStationComponents[i].keyword)).value_or("");
  input.synthetic = take_text("synthetic").value_or("");
  input.format = take_text("format").value_or("");
  input.units = take_text("units").value_or("g");
  input.dt_s = dt_s.value_or(0.0);
  if (const auto rows = take_number("skip_rows")) input.skip_rows = static_cast<std::size_t>(*rows);
  if (const auto column = take_number("column")) input.column = static_cast<std::size_t>(*column);
  if (used != nullptr) *used = input;
  StationRecord station = input.load_station(notes);
  if (warnings != nullptr) add_warnings(api::implausible_records(input, station), *warnings);
  return station;
}

std::unique_ptr<Scene> scene_of(const SceneRequest& request, ScenePoint* point) {
  return api::scene_of(request.model, request.values, point);
}

std::unique_ptr<Scene> Keywords::take_scene() {
  SceneRequest request;
  const auto model = take_text("model");
  if (const auto frame = take("frame")) {
    py::object parameters = *frame;
    if (!py::isinstance<py::dict>(parameters)) {
      if (!py::hasattr(parameters, "parameters")) throw UserError("frame", "expected a dict of parameters or a pcrf.Frame");
      // A pcrf.Frame carries its model: model= may only repeat it.
      const auto frame_model = py::str(py::getattr(parameters, "model", py::str(std::string(default_scene_model().name)))).cast<std::string>();
      if (model && *model != frame_model)
        throw UserError("model", "'" + *model + "' but {} is a pcrf.Frame of model '" + frame_model + "'", {"frame"});
      request.model = frame_model;
      parameters = parameters.attr("parameters");
    }
    for (const auto& [key, value] : parameters.cast<py::dict>()) {
      const std::string name = py::str(key).cast<std::string>();
      try {
        request.values[name] = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
      } catch (const py::error_already_set&) {
        throw UserError(Where{{"frame", name}, {}, 0}, "expected a number");
      }
    }
  }
  if (model) request.model = *model;
  return scene_of(request);
}

SceneRequest Keywords::take_scene_parameters() {
  SceneRequest request;
  request.model = take_text("model").value_or(request.model);
  for (const auto& model : scene_models())
    for (const auto& parameter : model.parameters) {
      const std::string key(parameter.name);
      if (request.values.count(key) > 0) continue;  // a key several models share
      if (const auto value = take_number(key)) request.values[key] = *value;
    }
  return request;
}

void Keywords::add_warnings(const std::vector<UserError>& found, std::vector<std::string>& warnings) {
  if (!warnings_as_errors_) {
    const auto value = take("warnings_as_errors");
    warnings_as_errors_ = value && py::bool_(*value);
  }
  if (*warnings_as_errors_ && !found.empty()) throw found.front().followed_by(" (warnings_as_errors)");
  for (const auto& warning : found) warnings.push_back(warning.message(Dialect::kKeyword));
}

void Keywords::add_warnings(const std::vector<std::string>& found, std::vector<std::string>& warnings) {
  std::vector<UserError> errors;
  for (const auto& line : found)
    if (!line.empty()) errors.emplace_back(line);  // "": a check that found nothing
  add_warnings(errors, warnings);
}

void Keywords::finish() const {
  if (given_.empty()) return;
  const std::string& key = given_.begin()->first;
  const std::vector<std::string_view> known(known_.begin(), known_.end());
  const std::string hint = closest_word(key, known);
  if (hint.empty()) throw UserError(key, "unknown keyword");
  throw UserError(key, "unknown keyword (did you mean {}?)", {hint});
}

}  // namespace pcrf::python
