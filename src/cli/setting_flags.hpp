/// \file setting_flags.hpp
/// \brief Command-line flags derived from a SettingTable: every key `snake_case` becomes
/// `--snake-case` (plus the description's aliases); a flag setting also gets `--no-key`
/// and takes `--key=false`. Values are checked against the description and applied in
/// table order, so `--preset` is applied before the single values it would otherwise reset.
#pragma once

#include <CLI/CLI.hpp>

#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "pcrf/api/given_settings.hpp"
#include "pcrf/setting.hpp"

namespace pcrf::cli {

template <class Target>
class SettingFlags {
 public:
  /// Adds one option per setting of `table` to `cmd`, in a group named after the table.
  SettingFlags(CLI::App* cmd, const SettingTable<Target>& table) : table_(table) {
    const std::string group = "[" + std::string(table.name) + "] settings";
    for (const auto& setting : table.settings) {
      Entry& e = entries_.emplace_back(Entry{&setting, {}, nullptr});
      std::string names = flag_name(setting.key);
      if (setting.type == SettingType::kFlag) names += "{true},--no-" + flag_name(setting.key).substr(2) + "{false}";
      for (auto alias : setting.aliases) names += "," + std::string(alias);
      const std::string help = std::string(setting.doc) + " (" + setting_kind_text(setting) +
                               "; default " + setting_display(setting.get(table.defaults)) + ")";
      e.option = setting.type == SettingType::kFlag ? cmd->add_flag(names, e.text, help)
                                                    : cmd->add_option(names, e.text, help);
      e.option->group(group);
    }
  }

  /// The values given on the command line, checked, in table order.
  /// \throws UserError "--flag: problem".
  api::GivenSettings<Target> given() const {
    api::GivenSettings<Target> values;
    for (const Entry& e : entries_)
      if (e.option->count() > 0) values.emplace_back(e.setting, api::checked_setting_text(*e.setting, e.text));
    return values;
  }

  /// The flags given, as a command line repeats them: "--name=value" ("--name" or
  /// "--no-name" for a flag), in table order.
  std::vector<std::string> given_words() const {
    std::vector<std::string> words;
    for (const Entry& e : entries_) {
      if (e.option->count() == 0) continue;
      const std::string name = flag_name(e.setting->key);
      if (e.setting->type == SettingType::kFlag) words.push_back(e.text == "false" ? "--no-" + name.substr(2) : name);
      else words.push_back(name + "=" + e.text);
    }
    return words;
  }

  /// table.defaults with every given value applied. \throws UserError.
  Target resolve() const { return api::resolve_settings(table_, given()); }

 private:
  struct Entry {
    const Setting<Target>* setting;
    std::string text;  ///< CLI11 writes the flag's text here
    CLI::Option* option;
  };
  const SettingTable<Target>& table_;
  std::deque<Entry> entries_;  // stable addresses: CLI11 keeps pointers to `text`
};

}  // namespace pcrf::cli
