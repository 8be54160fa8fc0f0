/// \file settings_doc.hpp
/// \brief The key tables of studies/README.md, rendered from the setting descriptions
/// (`pcrf settings` prints them; a test compares them with the README).
#pragma once

#include <string>

#include "pcrf/setting.hpp"

namespace pcrf::study {

/// A Markdown table: | key | type | default | meaning |, one row per setting.
template <class Target>
std::string markdown_table(const SettingTable<Target>& table) {
  std::string text = "| key | type | default | meaning |\n| --- | --- | --- | --- |\n";
  for (const auto& s : table.settings)
    text += "| `" + std::string(s.key) + "` | " + setting_kind_text(s) + " | `" +
            setting_display(s.get(table.defaults)) + "` | " + std::string(s.doc) + " |\n";
  return text;
}

/// Every table a study file takes settings from ([intensity], [physics], [solver], [run]), each under a
/// marker line `<!-- settings:NAME -->` and closed by `<!-- /settings -->`, as the README holds them.
std::string all_settings_markdown();

}  // namespace pcrf::study
