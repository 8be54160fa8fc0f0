// The flags that choose and describe a scene (see frame_flags.hpp).
#include "cli/frame_flags.hpp"

#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/api/frame_input.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/parameters.hpp"

namespace pcrf::cli {

/// The older `--h` is gone: CLI11 2.4 refuses a one-letter long name beside `-h` (help).
void SceneFlags::add_to(CLI::App* cmd) {
  const std::string group = "frame (default: the paper's basic model)";
  cmd->add_option("--model", model, "the scene: pcrf (the prestressed rocking frame), block (Housner's rigid block), "
                                    "rocking-frame (columns capped by a free beam, Makris & Vassiliou 2013)")
      ->capture_default_str()
      ->group(group);
  for (const auto& info : all_parameters())
    frame_options_.emplace_back(flag_name(info.name), cmd->add_option(flag_name(info.name), frame.*info.member,
                                                                      std::string(info.long_name) + " (pcrf)")
                                                          ->capture_default_str()
                                                          ->group(group));
  for (const auto& info : size_parameters()) {
    const std::string older = info.name == "m_c_kg" ? ",--mc" : "";
    frame_options_.emplace_back(
        flag_name(info.name),
        cmd->add_option(flag_name(info.name) + older, frame.*info.member,
                        std::string(info.long_name) + " [" + std::string(info.units) + "] (pcrf)")
            ->capture_default_str()
            ->group(group));
  }
  for (const auto& info : rocker_parameters()) {
    CLI::Option* option = cmd->add_option(flag_name(info.name), rocker.*info.member,
                                          std::string(info.long_name) + " [" + std::string(info.units) + "] (block, rocking-frame)")
                              ->capture_default_str()
                              ->group(group);
    rocker_options_.emplace_back(flag_name(info.name), option);
    if (info.name == "size_m") size_option_ = option;
  }
  frequency_option_ = cmd->add_option("--frequency-parameter-rad-s", frequency_parameter_rad_s,
                                      "p = sqrt(3g/4R) of the block (p-hat of the rocking frame) instead of --size-m [rad/s]")
                          ->group(group);
  restitution_option_ = cmd->add_option("--restitution", restitution,
                                        "coefficient of restitution of a block or rocking frame (default: from momentum)")
                            ->group(group);
  rocker_options_.emplace_back("--frequency-parameter-rad-s", frequency_option_);
  rocker_options_.emplace_back("--restitution", restitution_option_);
}

std::unique_ptr<Scene> SceneFlags::scene() const {
  const bool pcrf = model == "pcrf", block = model == "block", frame_model = model == "rocking-frame";
  if (!pcrf && !block && !frame_model)
    throw UsageError("--model: unknown scene '" + model + "' (expected pcrf, block or rocking-frame)");
  for (const auto& [flag, option] : pcrf ? rocker_options_ : frame_options_)
    if (option->count() > 0) throw UsageError(flag + " does not apply to --model " + model);
  try {
    if (pcrf) return api::frame_scene(frame);
    RockerParameters p = rocker;
    if (block && p.beam_mass_ratio != 0.0) throw UsageError("--beam-mass-ratio applies to --model rocking-frame");
    if (restitution_option_->count() > 0) p.restitution = restitution;
    if (frequency_option_->count() > 0) {
      if (size_option_->count() > 0) throw UsageError("give either --size-m or --frequency-parameter-rad-s, not both");
      if (!(frequency_parameter_rad_s > 0.0)) throw UsageError("--frequency-parameter-rad-s must be positive");
      // p̂² = (3g/4R)(1 + 2γ)/(1 + 3γ).
      const double gamma = p.beam_mass_ratio;
      p.size_m = 3.0 * p.gravity_m_s2 * (1.0 + 2.0 * gamma) /
                 (4.0 * frequency_parameter_rad_s * frequency_parameter_rad_s * (1.0 + 3.0 * gamma));
    }
    return std::make_unique<RigidRocker>(p);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace pcrf::cli
