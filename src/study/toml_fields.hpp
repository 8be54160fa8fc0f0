// Checked access to the keys of one TOML table: unknown keys, wrong types and bad values
// become UserError messages "FILE:LINE: dotted.key: problem".
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/closest_word.hpp"
#include "pcrf/setting.hpp"

namespace pcrf::study::detail {

class Fields {
 public:
  /// \param prefix dotted path of the table ("" for the root, "axes", "records[2]")
  /// \param allowed the keys this table may hold; any other key is an error
  Fields(const toml::table& table, std::string prefix, std::string file,
         const std::vector<std::string_view>& allowed);

  const toml::table& table() const { return table_; }
  bool has(std::string_view key) const { return table_.contains(key); }
  const toml::node* node(std::string_view key) const { return table_.get(key); }
  std::string path(std::string_view key) const;

  std::optional<double> number(std::string_view key) const;
  std::optional<std::int64_t> integer(std::string_view key) const;
  std::optional<std::string> text(std::string_view key) const;
  std::optional<bool> flag(std::string_view key) const;
  const toml::table* subtable(std::string_view key) const;
  const toml::array* array(std::string_view key) const;
  /// The value of a described setting, checked against its description (nullopt when the
  /// key is absent). \throws UserError naming the key and the problem.
  template <class Target>
  std::optional<SettingValue> setting(const Setting<Target>& s) const {
    const toml::node* n = node(s.key);
    if (n == nullptr) return std::nullopt;
    SettingValue value = raw_value(s.key);
    if (const auto problem = check_setting(s, value); !problem.empty())
      fail(s.key, problem.rfind("expected", 0) == 0 ? problem + ", got " + type_name(*n) : problem);
    return value;
  }
  /// A string or an array of strings.
  std::vector<std::string> texts(std::string_view key) const;

  /// "FILE:LINE" of a key (or of the table when the key is absent).
  std::string where(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

  /// Error at any node, for values nested in arrays.
  [[noreturn]] static void fail_at(const std::string& file, const toml::node* node,
                                   const std::string& path, const std::string& problem);
  static std::string where_at(const std::string& file, const toml::node* node);
  /// A finite number from an integer or float node. \throws UserError.
  static double number_at(const std::string& file, const toml::node& node, const std::string& path);
  static std::string type_name(const toml::node& node);

  const std::string& file() const { return file_; }

 private:
  /// A scalar node as a SettingValue (integer, float, boolean or string).
  SettingValue raw_value(std::string_view key) const;

  const toml::table& table_;
  std::string prefix_;
  std::string file_;
};

using pcrf::closest_word;  // "did you mean" hints (pcrf/closest_word.hpp)

/// Reads the table `table.name` of `top` into `target` (starting from table.defaults):
/// every key must be described, values are checked and applied in description order.
/// `lines` receives "FILE:LINE" of each key given, by "table.key". `other_keys` are keys the
/// table may also hold that the caller reads itself (no setting of Target).
template <class Target>
void read_setting_table(const Fields& top, const SettingTable<Target>& table, Target& target,
                        std::map<std::string, std::string>& lines, std::vector<std::string_view> other_keys = {}) {
  target = table.defaults;
  const toml::table* node = top.subtable(table.name);
  if (node == nullptr) return;
  std::vector<std::string_view> keys;
  for (const auto& s : table.settings) keys.push_back(s.key);
  keys.insert(keys.end(), other_keys.begin(), other_keys.end());
  const Fields fields(*node, std::string(table.name), top.file(), keys);
  for (const auto& s : table.settings) {
    if (auto value = fields.setting(s)) {
      s.set(target, *value);
      lines[fields.path(s.key)] = fields.where(s.key);
    }
  }
}

}  // namespace pcrf::study::detail
