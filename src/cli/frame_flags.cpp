// The flags that choose and describe a scene (see frame_flags.hpp).
#include "cli/frame_flags.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "pcrf/api/frame_input.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::cli {
namespace {

/// "pcrf (the prestressed rocking frame …), block (…)": the models for --model's help.
std::string models_help() {
  std::string text = "the scene: ";
  for (const auto& m : scene_models())
    text += (&m == &scene_models().front() ? "" : ", ") + std::string(m.name) + " (" + std::string(m.description) + ")";
  return text;
}

/// Where a parameter is first described, and the models that take it: " (block, rocking-frame)".
std::string owners_help(std::string_view key) {
  std::string text;
  for (const auto& m : scene_models())
    if (m.index(key) != std::string::npos) text += (text.empty() ? "" : ", ") + std::string(m.name);
  return " (" + text + ")";
}

}  // namespace

/// The older `--h` is gone: CLI11 2.4 refuses a one-letter long name beside `-h` (help).
void SceneFlags::add_to(CLI::App* cmd) {
  const std::string group = "scene (default: the paper's basic model)";
  cmd->add_option("--model", model, models_help())->capture_default_str()->group(group);
  for (const auto& m : scene_models())
    for (const auto& p : m.parameters) {
      if (std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == p.name; })) continue;
      Entry& e = entries_.emplace_back(Entry{p.name, p.default_value, nullptr});
      std::string names = flag_name(p.name);
      for (auto alias : p.aliases) names += "," + std::string(alias);
      const std::string units = p.units == "1" ? "" : " [" + std::string(p.units) + "]";
      e.option = cmd->add_option(names, e.value, std::string(p.long_name) + units + owners_help(p.name))->group(group);
      if (!std::isnan(p.default_value)) e.option->capture_default_str();
    }
}

std::unique_ptr<Scene> SceneFlags::scene(ScenePoint* point) const {
  std::map<std::string, double, std::less<>> values;
  for (const Entry& e : entries_)
    if (e.option->count() > 0) values[std::string(e.key)] = e.value;
  return api::scene_of(model, values, point);
}

}  // namespace pcrf::cli
