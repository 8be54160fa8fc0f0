/// \file frame_input.hpp
/// \brief A prestressed frame described by parameter name (the names of the parameter
/// tables, as study files spell them: kappa … pi_e_c, h_m, m_c_kg), every other parameter at
/// the paper's basic model; for front ends that take parameters by name (the Python module).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/model/frame.hpp"
#include "pcrf/model/scene.hpp"

namespace pcrf::api {

using NamedValues = std::vector<std::pair<std::string, double>>;

/// Every name a frame parameter goes by, in table order.
std::vector<std::string> frame_parameter_names();

/// The basic model with the named values set. \throws InputError for an unknown name.
FrameParameters frame_parameters(const NamedValues& named);

/// The prestressed frame as a scene. \throws InputError (as `pcrf run` reports it) for a
/// frame that cannot be built.
std::unique_ptr<Scene> frame_scene(const FrameParameters& parameters);

/// \throws InputError when a pushover curve of `points` rotations cannot be drawn (< 2).
void check_pushover_points(int points);

}  // namespace pcrf::api
