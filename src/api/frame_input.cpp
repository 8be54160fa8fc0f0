// A prestressed frame described by parameter name (see frame_input.hpp).
#include "pcrf/api/frame_input.hpp"

#include <stdexcept>

#include "pcrf/api/input_error.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/parameters.hpp"

namespace pcrf::api {
namespace {

template <class Visit>
void for_each_parameter(Visit visit) {
  for (const auto& info : all_parameters()) visit(info);
  for (const auto& info : size_parameters()) visit(info);
}

}  // namespace

std::vector<std::string> frame_parameter_names() {
  std::vector<std::string> names;
  for_each_parameter([&names](const ParameterInfo& info) { names.emplace_back(info.name); });
  return names;
}

FrameParameters frame_parameters(const NamedValues& named) {
  FrameParameters parameters;
  for (const auto& [name, value] : named) {
    bool known = false;
    for_each_parameter([&](const ParameterInfo& info) {
      if (info.name != name) return;
      parameters.*info.member = value;
      known = true;
    });
    if (known) continue;
    std::string expected;
    for (const auto& n : frame_parameter_names()) expected += (expected.empty() ? "" : ", ") + n;
    throw InputError("unknown frame parameter '" + name + "' (expected " + expected + ")");
  }
  return parameters;
}

std::unique_ptr<Scene> frame_scene(const FrameParameters& parameters) {
  try {
    return std::make_unique<EquationOfMotion>(make_frame(parameters));
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

void check_pushover_points(int points) {
  if (points < 2) throw InputError("--points must be at least 2");
}

}  // namespace pcrf::api
