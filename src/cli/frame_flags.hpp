/// \file frame_flags.hpp
/// \brief The flags that choose and describe a scene, for every command that takes one:
/// --model NAME and one flag per parameter of the scene catalogue (model/scene_catalog.hpp),
/// its key with dashes (`--size-m` for size_m) plus the catalogue's older spellings. A new
/// scene's parameters are flags with no change here.
#pragma once

#include <CLI/CLI.hpp>

#include <deque>
#include <memory>
#include <string>

#include "pcrf/model/scene.hpp"
#include "pcrf/model/scene_catalog.hpp"

namespace pcrf::cli {

struct SceneFlags {
  std::string model = std::string(default_scene_model().name);

  void add_to(CLI::App* cmd);
  /// The scene the flags describe, and the point it was made from (when not null).
  /// \throws UserError as api::scene_of(): an unknown model, a parameter of another model, a
  /// value outside its domain (naming the key, which the command line prints as its flag).
  std::unique_ptr<Scene> scene(ScenePoint* point = nullptr) const;

 private:
  struct Entry {
    std::string_view key;
    double value;
    CLI::Option* option;
  };
  std::deque<Entry> entries_;  // stable addresses: CLI11 keeps pointers to `value`
};

}  // namespace pcrf::cli
