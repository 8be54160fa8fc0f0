/// \file keywords.hpp
/// \brief A Python call's keyword arguments, taken one by one: values of the settings tables
/// by their keys (checked as the command line checks its flags), records as arrays or file
/// paths, frames as dicts. A keyword nobody took is refused with a suggestion.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pcrf/api/given_settings.hpp"
#include "pcrf/api/record_input.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/model/scene_catalog.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::python {

namespace py = pybind11;

/// How deep a keyword's value, or a study given as a dict, may nest lists, tuples and dicts
/// (a study's deepest is 5: a value of an inline table of an entry of an array of tables).
inline constexpr std::size_t kMaxNestingDepth = 32;

/// Refuses, before anything walks it, a value that holds itself (directly or through others)
/// or nests lists, tuples and dicts deeper than kMaxNestingDepth: UserError at `where`'s key
/// path, extended to the list or dict at fault ("frame['kappa']: holds itself"). Walks the
/// value without recursion beyond that depth: no container can crash the interpreter.
void check_nesting(const py::handle& value, const Where& where);

/// The error of a value nested deeper than kMaxNestingDepth at `where` (named up to its last
/// key that is a name).
UserError nested_too_deep(const Where& where);

/// A Python int (or an object with __index__) as a 64-bit integer. \throws UserError at
/// `where` when it lies outside [-2^63, 2^63 - 1].
std::int64_t whole_number(const py::handle& value, const Where& where);

/// A Python value as a setting of `s` takes it: booleans, integers, floats as they are,
/// text as the command line reads it, a list of words joined. \throws UserError.
template <class Target>
SettingValue setting_value(const Setting<Target>& s, const py::handle& value);

/// A scene as keywords name it: the catalogue's model name and the values given by its keys.
struct SceneRequest {
  std::string model = std::string(default_scene_model().name);
  std::map<std::string, double, std::less<>> values;
};

/// The scene of the catalogue and the point it was made from (when not null), through
/// api::scene_of: the command line's checks and messages. \throws UserError.
std::unique_ptr<Scene> scene_of(const SceneRequest& request, ScenePoint* point = nullptr);

class Keywords {
 public:
  explicit Keywords(const py::kwargs& keywords);

  /// The value of `key`, or nothing when it was not given (or given as None).
  std::optional<py::object> take(const std::string& key);
  std::optional<double> take_number(const std::string& key);
  std::optional<std::string> take_text(const std::string& key);  ///< str or os.PathLike
  /// A whole number (an int, or a float with no fraction) in [`low`, `high`]. \throws UserError.
  std::optional<std::int64_t> take_whole(const std::string& key, std::int64_t low, std::int64_t high);

  /// The values of the table's keys that were given, checked, in table order.
  template <class Target>
  api::GivenSettings<Target> take_settings(const SettingTable<Target>& table) {
    api::GivenSettings<Target> given;
    for (const auto& setting : table.settings)
      if (const auto value = take(std::string(setting.key))) given.emplace_back(&setting, setting_value(setting, *value));
    return given;
  }

  /// The record the keywords name: ground_accel_g (+ dt_s) with the other components'
  /// arrays (ground_accel_h2_g, …: kStationComponents), or record / synthetic with their
  /// files (record_h2, …) read like `pcrf run` reads its files; the azimuths; the notes of
  /// padding in `notes`; how the files were named in `input` (when not null); the record
  /// warnings (implausible_records for files, implausible_arrays for arrays) in `warnings`
  /// (when not null) by add_warnings.
  /// \throws UserError.
  StationRecord take_station(std::vector<std::string>& notes, api::RecordInput* input = nullptr,
                             std::vector<std::string>* warnings = nullptr);
  /// The scene of `model=` (pcrf, block, rocking-frame; default pcrf) with the parameters of
  /// `frame=` (a dict by the model's keys, or a pcrf.Frame), every other one at its default,
  /// built as `pcrf run --model` builds it (model/scene_catalog.hpp). \throws UserError.
  std::unique_ptr<Scene> take_scene();
  /// `model=` and every parameter of a scene given as a keyword by its catalogue key
  /// (pcrf.Frame(model="block", slenderness_rad=0.2)); checked by scene_of().
  SceneRequest take_scene_parameters();

  /// Adds `found` (what a check that warns found: UserErrors not thrown) to `warnings`, spelt
  /// as Python spells keys; with the keyword warnings_as_errors true the first is thrown.
  void add_warnings(const std::vector<UserError>& found, std::vector<std::string>& warnings);
  /// The same for lines that name no key (record checks).
  void add_warnings(const std::vector<std::string>& found, std::vector<std::string>& warnings);

  /// \throws UserError "unknown keyword 'x' (did you mean 'y'?)" for one not taken.
  void finish() const;

 private:
  std::map<std::string, py::object> given_;
  std::vector<std::string> known_;
  std::optional<bool> warnings_as_errors_;
};

/// A numpy float array as doubles. \throws UserError naming `what`.
std::vector<double> to_doubles(const py::handle& value, const std::string& what);

}  // namespace pcrf::python
