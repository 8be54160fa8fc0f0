// The flags that describe a frame (see frame_flags.hpp).
#include "cli/frame_flags.hpp"

#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/model/parameters.hpp"

namespace pcrf::cli {

/// --kappa … --pi-e-c and --h-m, --m-c-kg (older spelling --mc), from the parameter tables.
/// The older `--h` is gone: CLI11 2.4 refuses a one-letter long name beside `-h` (help).
void add_frame_flags(CLI::App* cmd, FrameParameters& frame) {
  const std::string group = "frame (default: the paper's basic model)";
  for (const auto& info : all_parameters())
    cmd->add_option(flag_name(info.name), frame.*info.member, std::string(info.long_name))
        ->capture_default_str()
        ->group(group);
  for (const auto& info : size_parameters()) {
    const std::string older = info.name == "m_c_kg" ? ",--mc" : "";
    cmd->add_option(flag_name(info.name) + older, frame.*info.member,
                    std::string(info.long_name) + " [" + std::string(info.units) + "]")
        ->capture_default_str()
        ->group(group);
  }
}


Frame frame_from_flags(const FrameParameters& frame) {
  try {
    return make_frame(frame);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace pcrf::cli
