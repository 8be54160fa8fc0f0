// A Python call's keyword arguments (see keywords.hpp).
#include "keywords.hpp"

#include "pcrf/api/frame_input.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

namespace {

/// A dict's key as a key path names it: a str as it is, any other key by its repr (a repr
/// that cannot be made, by its type).
std::string key_text(const py::handle& key) {
  if (PyUnicode_Check(key.ptr())) return py::reinterpret_borrow<py::str>(key).cast<std::string>();
  try {
    return py::repr(key).cast<std::string>();
  } catch (const py::error_already_set&) {
    return "<" + py::str(key.get_type().attr("__name__")).cast<std::string>() + ">";
  }
}

/// A Python int for a message: its digits, or how many there are when they are many.
std::string integer_text(const py::handle& value) {
  constexpr std::size_t kShownDigits = 24;
  const std::string digits = py::str(value).cast<std::string>();
  if (digits.size() <= kShownDigits) return digits;
  return "an integer of " + std::to_string(digits.size() - (digits.front() == '-' ? 1 : 0)) + " digits";
}

/// The key path `keys` up to its last name: what a message names of a path nested too deep.
std::vector<std::string> up_to_last_name(std::vector<std::string> keys) {
  while (!keys.empty() && is_key_index(keys.back())) keys.pop_back();
  return keys;
}

/// check_nesting's walk: `open` holds the containers on the path to `value`, `keys` its key
/// path; the depth is bounded by kMaxNestingDepth, so this recursion is too.
void walk_nesting(const py::handle& value, std::vector<std::string>& keys, std::vector<PyObject*>& open,
                  const Where& where) {
  PyObject* object = value.ptr();
  const bool is_dict = PyDict_Check(object) != 0;
  if (!is_dict && PyList_Check(object) == 0 && PyTuple_Check(object) == 0) return;
  if (std::find(open.begin(), open.end(), object) != open.end())
    throw UserError(Where{keys, where.file, 0}, "holds itself (a list or dict that contains itself cannot be a value)");
  if (open.size() == kMaxNestingDepth) throw nested_too_deep(Where{keys, where.file, 0});
  open.push_back(object);
  if (is_dict) {
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      keys.push_back(key_text(key));
      walk_nesting(item, keys, open, where);
      keys.pop_back();
    }
  } else {
    // A list may change under a walk only through Python code, which none of this runs.
    const Py_ssize_t size = PySequence_Fast_GET_SIZE(object);
    for (Py_ssize_t i = 0; i < size; ++i) {
      keys.push_back(key_index(static_cast<std::size_t>(i)));
      walk_nesting(PySequence_Fast_GET_ITEM(object, i), keys, open, where);
      keys.pop_back();
    }
  }
  open.pop_back();
}

}  // namespace

UserError nested_too_deep(const Where& where) {
  return UserError(Where{up_to_last_name(where.keys), where.file, where.line},
                   "nests lists and dicts more than " + std::to_string(kMaxNestingDepth) + " deep");
}

void check_nesting(const py::handle& value, const Where& where) {
  std::vector<std::string> keys = where.keys;
  std::vector<PyObject*> open;
  walk_nesting(value, keys, open, where);
}

std::int64_t whole_number(const py::handle& value, const Where& where) {
  int overflow = 0;
  const long long number = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0)
    throw UserError(where, "is out of range: " + integer_text(value) + " lies outside a 64-bit integer's [-2**63, 2**63 - 1]");
  if (number == -1 && PyErr_Occurred() != nullptr) throw py::error_already_set();
  return static_cast<std::int64_t>(number);
}

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
  } else if (PyIndex_Check(value.ptr()) && s.type != SettingType::kNumber) {
    v = whole_number(value, Where{{std::string(s.key)}, {}, 0});
  } else if (PyIndex_Check(value.ptr()) || PyFloat_Check(value.ptr()) || py::hasattr(value, "__float__")) {
    try {
      v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    } catch (const py::error_already_set&) {
      if (PyIndex_Check(value.ptr()) != 0)  // an int beyond a double's range
        throw UserError(std::string(s.key), "is out of range: " + integer_text(value) + " is beyond any number a double holds");
      throw UserError(std::string(s.key), "expected " + setting_kind_text(s));
    }
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
  for (const auto& [key, value] : keywords) {
    if (value.is_none()) continue;
    const std::string name = key.cast<std::string>();
    check_nesting(value, Where{{name}, {}, 0});  // before anything walks it
    given_[name] = py::reinterpret_borrow<py::object>(value);
  }
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
    if (PyIndex_Check(value->ptr()) != 0)  // an int beyond a double's range
      throw UserError(key, "is out of range: " + integer_text(*value) + " is beyond any number a double holds");
    throw UserError(key, "expected a number");
  }
}

std::optional<std::int64_t> Keywords::take_whole(const std::string& key, std::int64_t low, std::int64_t high) {
  const auto value = take(key);
  if (!value) return std::nullopt;
  const std::string range = "[" + std::to_string(low) + ", " + std::to_string(high) + "]";
  std::int64_t number = 0;
  if (PyIndex_Check(value->ptr()) != 0 && !py::isinstance<py::bool_>(*value)) {
    number = whole_number(*value, Where{{key}, {}, 0});
  } else if (PyFloat_Check(value->ptr()) != 0) {
    const double x = value->cast<double>();
    // Exactly representable bounds: 2^63 is the first double past an int64's range.
    if (!(std::trunc(x) == x) || !(x >= -9223372036854775808.0 && x < 9223372036854775808.0))
      throw UserError(key, "expected a whole number in " + range + " (got " + py::str(*value).cast<std::string>() + ")");
    number = static_cast<std::int64_t>(x);
  } else {
    throw UserError(key, "expected a whole number");
  }
  if (number < low || number > high)
    throw UserError(key, "must lie in " + range + " (got " + std::to_string(number) + ")");
  return number;
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
  // As the command line's --skip-rows and --column read them: counts of lines and columns.
  constexpr std::int64_t kMaxLines = std::numeric_limits<std::int32_t>::max();
  if (const auto rows = take_whole("skip_rows", 0, kMaxLines)) input.skip_rows = static_cast<std::size_t>(*rows);
  if (const auto column = take_whole("column", 0, kMaxLines)) input.column = static_cast<std::size_t>(*column);
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
