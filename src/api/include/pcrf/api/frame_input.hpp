/// \file frame_input.hpp
/// \brief What `pcrf run|frame --model` and pcrf.run / pcrf.Frame both do with a request for a
/// scene: build it from the catalogue (model/scene_catalog.hpp) and name a bad input the one
/// way both print it.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "pcrf/model/scene_catalog.hpp"

namespace pcrf::api {

/// The command-line flag of a scene parameter's key: `--restitution` for given_restitution
/// (the key says "given" because `restitution` is the metric of the r a case used), otherwise
/// flag_name(key) (`--size-m` for size_m).
std::string scene_flag(std::string_view key);

/// The scene `model` with `values` given by key, every other parameter at its default, and the
/// point it was made from (when `point` is not null).
/// \throws InputError with the catalogue's one-line message, each input named by its flag
/// (`--model: unknown scene 'blok'`, `--kappa does not apply to model "block" (…)`,
/// `give either --size-m or --frequency-parameter-rad-s, not both`), the same for the command
/// line and the module, as the settings' messages are.
std::unique_ptr<Scene> scene_of(const std::string& model, const std::map<std::string, double, std::less<>>& values,
                                ScenePoint* point = nullptr);

/// \throws InputError when a pushover curve of `points` rotations cannot be drawn (< 2).
void check_pushover_points(int points);

}  // namespace pcrf::api
