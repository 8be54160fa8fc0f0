/// \file scene_catalog.hpp
/// \brief Every scene a study, `pcrf run --model` or the Python module can name, each with
/// its parameter table: one place that turns a model name and parameter values into a Scene.
///
///   pcrf           the prestressed rocking frame (Zhao & Su 2021): the eight dimensionless
///                  parameters and the size (h_m, m_c_kg; not study axes)
///   block          Housner's rigid block: slenderness_rad, size_m or
///                  frequency_parameter_rad_s, given_restitution (default: from momentum)
///   rocking-frame  the Makris–Vassiliou frame: the block's keys and beam_mass_ratio
///
/// A scene's values are a ScenePoint: one number per parameter of its table, in table order,
/// NaN for an optional parameter not given. Adding a scene: its class, and one entry here;
/// the command line's flags and Python's keywords follow from the entry.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/model/scene.hpp"

namespace pcrf {

/// One value per parameter of a SceneModel, in its table's order.
using ScenePoint = std::vector<double>;

/// One parameter of a scene model, spelled as study keys, cube coordinates, Python keywords
/// and (with dashes) `pcrf run|frame` flags.
struct SceneParameter {
  std::string_view name;       ///< e.g. "slenderness_rad"
  std::string_view long_name;  ///< e.g. "slenderness alpha of the columns"
  std::string_view units;      ///< UDUNITS
  double default_value;        ///< NaN: optional, derived by the scene when not given
  bool axis;                   ///< may be a study axis (false: the base point sets it for every case)
  /// Why `value` is outside the parameter's domain on its own ("must be positive"); empty when inside.
  std::string (*problem)(double value);
  std::vector<std::string_view> aliases = {};  ///< older command-line spellings ("--mc")
};

struct SceneModel {
  std::string_view name;
  std::string_view description;
  std::vector<SceneParameter> parameters;
  /// The scene at `values`. \throws UserError at a key, or std::invalid_argument "impossible
  /// frame: …" for values each in its domain that together make no scene.
  std::unique_ptr<Scene> (*make)(std::span<const double> values);
  /// Keys of which at most one may be given (the block's size_m and frequency_parameter_rad_s).
  std::vector<std::string_view> exclusive;

  /// Position of a parameter in the table; npos when the model has none of that name.
  std::size_t index(std::string_view key) const;
  /// Every parameter at its default.
  ScenePoint defaults() const;
  /// "slenderness_rad, size_m, …": the model's keys, for messages.
  std::string keys_text() const;
};

/// The scene models, the default (pcrf) first.
const std::vector<SceneModel>& scene_models();
/// The model a study, `pcrf run` or pcrf.run solves when none is named: the first.
inline const SceneModel& default_scene_model() { return scene_models().front(); }

/// \throws UserError at `model`: "unknown scene 'x' (expected pcrf, block or rocking-frame)".
const SceneModel& scene_model(std::string_view name);

/// The names of the models that take `key`, "model \"block\" or \"rocking-frame\"", for
/// messages; empty when none does.
std::string models_taking(std::string_view key);

/// NaN-aware equality of two points of the same model (NaN: the same absent value).
bool same_point(const ScenePoint& a, const ScenePoint& b);

/// One scene as a study lays it out: its model and a point of that model's table. A study's
/// frames are SceneSpecs, so that one study may hold scenes of several models.
struct SceneSpec {
  const SceneModel* model;
  ScenePoint values;

  /// The scene. \throws std::invalid_argument as SceneModel::make.
  std::unique_ptr<Scene> make() const { return model->make(values); }
  /// The value of parameter `key`; NaN when the model has none of that name (or it is absent).
  double value(std::string_view key) const;
};

/// The same model at the same point (same_point).
bool same_scene(const SceneSpec& a, const SceneSpec& b);

/// The point a model's values given by key (the command line's flags, Python's keywords) make:
/// every parameter at its default, the given values set, and of a model's exclusive keys only
/// the one given (the others absent, NaN), so that the point's values that are not NaN, given
/// again, make the same scene. \throws UserError at the key: a key of another model ("does
/// not apply to model \"block\" (it is a parameter of model \"pcrf\")"), an unknown key, a value
/// outside its domain; or two exclusive keys both given.
ScenePoint scene_point(const SceneModel& model, const std::map<std::string, double, std::less<>>& values);

}  // namespace pcrf
