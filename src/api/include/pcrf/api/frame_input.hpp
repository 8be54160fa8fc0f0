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

/// The rotations a pushover curve is drawn at unless asked (`pcrf frame`, pcrf.Frame), and
/// the most it is drawn at: each is a static solution of the frame, and the curve is printed
/// or returned whole (at 10⁵ points, a few MB and well under a second).
inline constexpr int kDefaultPushoverPoints = 41;
inline constexpr int kMaxPushoverPoints = 100000;

/// `points` as the number of rotations of a pushover curve: one check for both front ends.
/// \throws UserError at `points` unless it is a whole number from 2 to kMaxPushoverPoints.
int pushover_points(double points);

}  // namespace pcrf::api
