// pcrf._pcrf.frame: a scene's properties and pushover curve, as `pcrf frame --model M` computes
// them: the scene from the catalogue (model/scene_catalog.hpp), its properties from
// model/frame_properties.hpp.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/api/frame_input.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::python {
namespace {

/// The scene's parameters by key, those absent (NaN: an optional one not given, the other
/// of two exclusive keys) left out: given again (pcrf.run(frame=...)), they make this scene.
py::dict parameters_dict(const SceneModel& model, const ScenePoint& point) {
  py::dict d;
  for (std::size_t k = 0; k < model.parameters.size(); ++k)
    if (!std::isnan(point[k])) d[py::str(std::string(model.parameters[k].name))] = point[k];
  return d;
}

py::array_t<double> numbers(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

/// {"model", "parameters", "properties" (key → value), "units" (key → unit),
/// "fracture_tendon", "pushover_theta_rad", "pushover_accel_g"}.
py::dict frame(const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  const SceneRequest request = keywords.take_scene_parameters();
  const auto physics = keywords.take_settings(physics_settings());
  const double asked = keywords.take_number("points").value_or(api::kDefaultPushoverPoints);
  keywords.finish();
  const int points = api::pushover_points(asked);
  ScenePoint point;
  const auto scene = scene_of(request, &point);
  FrameProperties p;
  {
    py::gil_scoped_release released;
    const double fracture_strain = api::resolve_settings(physics_settings(), physics).fracture_strain;
    p = frame_properties(*scene, fracture_strain, points);
  }
  py::dict properties, units;
  for (const auto& info : frame_property_table()) {
    // NaN where `pcrf frame --json` writes null (JSON has no infinity): a block's fracture angle.
    const double value = p.*info.member;
    properties[py::str(std::string(info.key))] = std::isfinite(value) ? value : std::nan("");
    units[py::str(std::string(info.key))] = std::string(info.units);
  }
  std::vector<double> theta, accel;
  for (const auto& sample : p.pushover) theta.push_back(sample.theta_rad), accel.push_back(sample.accel_g);
  py::dict d;
  d["model"] = request.model;
  d["parameters"] = parameters_dict(scene_model(request.model), point);
  d["properties"] = properties;
  d["units"] = units;
  d["fracture_tendon"] = p.fracture_tendon;
  d["pushover_theta_rad"] = numbers(theta);
  d["pushover_accel_g"] = numbers(accel);
  return d;
}

}  // namespace

void bind_frame(py::module_& m) {
  m.def("frame", &frame, "A scene's properties and pushover curve, as `pcrf frame --model M`; see pcrf.Frame.");
}

}  // namespace pcrf::python
