// The flags that choose and describe a scene (see frame_flags.hpp).
#include "cli/frame_flags.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/api/frame_input.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/model/scene_catalog.hpp"

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
  restitution_option_ = cmd->add_option(api::scene_flag("given_restitution"), restitution,
                                        "coefficient of restitution of a block or rocking frame (default: from momentum)")
                            ->group(group);
  rocker_options_.emplace_back("--frequency-parameter-rad-s", frequency_option_);
  rocker_options_.emplace_back(api::scene_flag("given_restitution"), restitution_option_);
}

std::unique_ptr<Scene> SceneFlags::scene() const {
  // The catalogue checks everything, through api::scene_of with the messages the Python module
  // gives too (a parameter of another model, a value outside its domain); here only which
  // flags were given.
  std::map<std::string, double, std::less<>> values;
  auto take = [&](const std::string& flag, CLI::Option* option, double value, std::string name = "") {
    if (option->count() == 0) return;
    if (name.empty()) name = flag.substr(2);
    std::replace(name.begin(), name.end(), '-', '_');
    values[name] = value;
  };
  for (std::size_t k = 0; k < frame_options_.size(); ++k) {
    const bool size = k >= all_parameters().size();
    const auto& info = size ? size_parameters()[k - all_parameters().size()] : all_parameters()[k];
    take(frame_options_[k].first, frame_options_[k].second, frame.*info.member);
  }
  for (const auto& info : rocker_parameters())
    for (const auto& [flag, option] : rocker_options_)
      if (flag == flag_name(info.name)) take(flag, option, rocker.*info.member);
  take("--frequency-parameter-rad-s", frequency_option_, frequency_parameter_rad_s);
  take(api::scene_flag("given_restitution"), restitution_option_, restitution, "given_restitution");
  return api::scene_of(model, values);
}

}  // namespace pcrf::cli
