/// \file frame_input.hpp
/// \brief What `pcrf run|frame --model` and pcrf.run / pcrf.Frame both do with a request for a
/// scene: build it from the catalogue (model/scene_catalog.hpp).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "pcrf/model/scene_catalog.hpp"

namespace pcrf::api {

/// The scene `model` with `values` given by key, every other parameter at its default, and the
/// point it was made from (when `point` is not null).
/// \throws UserError as scene_model() and scene_point() throw it, naming the key; or
/// std::invalid_argument "impossible frame: …" for a point that makes no scene.
std::unique_ptr<Scene> scene_of(const std::string& model, const std::map<std::string, double, std::less<>>& values,
                                ScenePoint* point = nullptr);

/// \throws UserError at `points` when a pushover curve of `points` rotations cannot be drawn (< 2).
void check_pushover_points(int points);

}  // namespace pcrf::api
