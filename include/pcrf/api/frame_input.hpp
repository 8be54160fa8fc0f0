/// \file frame_input.hpp
/// \brief What `pcrf frame` and pcrf.Frame both check of a request for a scene's properties
/// (the scene itself comes from the catalogue, model/scene_catalog.hpp, for both).
#pragma once

namespace pcrf::api {

/// \throws InputError when a pushover curve of `points` rotations cannot be drawn (< 2).
void check_pushover_points(int points);

}  // namespace pcrf::api
