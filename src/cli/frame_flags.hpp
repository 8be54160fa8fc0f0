/// \file frame_flags.hpp
/// \brief The flags that choose and describe a scene, for every command that takes one:
/// --model pcrf|block|rocking-frame, the prestressed frame's parameters (--kappa … --pi-e-c,
/// --h-m, --m-c-kg) and the rockers' (--slenderness-rad, --size-m or
/// --frequency-parameter-rad-s, --beam-mass-ratio, --restitution), all from the parameter
/// tables.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

#include "pcrf/model/frame.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/model/scene.hpp"

namespace pcrf::cli {

struct SceneFlags {
  std::string model = "pcrf";
  FrameParameters frame;        ///< --model pcrf (default: the paper's basic model)
  RockerParameters rocker;      ///< --model block | rocking-frame
  double restitution = -1.0;    ///< < 0: from momentum
  double frequency_parameter_rad_s = 0.0;  ///< > 0: sets the size instead of --size-m

  void add_to(CLI::App* cmd);
  /// The scene the flags describe. \throws UsageError for an unknown model, a parameter of
  /// another model, or an impossible scene (naming the parameter).
  std::unique_ptr<Scene> scene() const;

 private:
  std::vector<std::pair<std::string, CLI::Option*>> frame_options_, rocker_options_;
  CLI::Option* size_option_ = nullptr;
  CLI::Option* restitution_option_ = nullptr;
  CLI::Option* frequency_option_ = nullptr;
};

}  // namespace pcrf::cli
