// pcrf._pcrf.frame: a frame's properties and pushover curve, as `pcrf frame` computes them
// (model/frame_properties.hpp).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::python {
namespace {

py::dict parameters_dict(const FrameParameters& p) {
  py::dict d;
  for (const auto& info : all_parameters()) d[py::str(std::string(info.name))] = p.*info.member;
  for (const auto& info : size_parameters()) d[py::str(std::string(info.name))] = p.*info.member;
  return d;
}

/// {"parameters", "properties" (key → value), "units" (key → unit), "fracture_tendon",
/// "pushover_theta_rad", "pushover_accel_g"}.
py::dict frame(const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  api::NamedValues named;
  for (const auto& name : api::frame_parameter_names())
    if (const auto value = keywords.take_number(name)) named.emplace_back(name, *value);
  const FrameParameters parameters = api::frame_parameters(named);
  const auto physics = keywords.take_settings(physics_settings());
  int points = 41;  // as `pcrf frame` prints by default
  if (const auto value = keywords.take_number("points")) points = static_cast<int>(*value);
  keywords.finish();
  api::check_pushover_points(points);
  FrameProperties p;
  {
    py::gil_scoped_release released;
    const double fracture_strain = api::resolve_settings(physics_settings(), physics).fracture_strain;
    p = frame_properties(*api::frame_scene(parameters), fracture_strain, points);
  }
  py::dict properties, units;
  for (const auto& info : frame_property_table()) {
    properties[py::str(std::string(info.key))] = p.*info.member;
    units[py::str(std::string(info.key))] = std::string(info.units);
  }
  std::vector<double> theta, accel;
  for (const auto& point : p.pushover) theta.push_back(point.theta_rad), accel.push_back(point.accel_g);
  py::dict d;
  d["parameters"] = parameters_dict(parameters);
  d["properties"] = properties;
  d["units"] = units;
  d["fracture_tendon"] = p.fracture_tendon;
  d["pushover_theta_rad"] = py::array_t<double>(static_cast<py::ssize_t>(theta.size()), theta.data());
  d["pushover_accel_g"] = py::array_t<double>(static_cast<py::ssize_t>(accel.size()), accel.data());
  return d;
}

}  // namespace

void bind_frame(py::module_& m) {
  m.def("frame", &frame, "A frame's properties and pushover curve, as `pcrf frame`; see pcrf.Frame.");
}

}  // namespace pcrf::python
