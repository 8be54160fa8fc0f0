// Checked access to the keys of one TOML table: unknown keys, wrong types and bad values
// become a UserError at the key's Where (its key path, file and line), which the front end
// renders ("FILE:LINE: [table] key: problem").
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
#include "pcrf/user_error.hpp"

namespace pcrf::study::detail {

class Fields {
 public:
  /// \param prefix key path of the table ({} for the root, {"axes"}, {"records", key_index(2)})
  /// \param allowed the keys this table may hold; any other key is an error
  Fields(const toml::table& table, std::vector<std::string> prefix, std::string file,
         const std::vector<std::string_view>& allowed);

  const toml::table& table() const { return table_; }
  bool has(std::string_view key) const { return table_.contains(key); }
  const toml::node* node(std::string_view key) const { return table_.get(key); }
  /// The key path of `key` in this table.
  std::vector<std::string> path(std::string_view key) const;
  /// The key path of entry `i` (from 0) of the array `key`.
  std::vector<std::string> entry_path(std::string_view key, std::size_t i) const;

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

  /// Where a key is: its path, the file and its line (the table's when the key is absent).
  Where where(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

  /// Error at any node, for values nested in arrays.
  [[noreturn]] static void fail_at(const std::string& file, const toml::node* node,
                                   std::vector<std::string> path, const std::string& problem);
  /// Where a node is: `path`, the file and the node's line.
  static Where where_at(const std::string& file, const toml::node* node, std::vector<std::string> path);
  /// A finite number from an integer or float node. \throws UserError.
  static double number_at(const std::string& file, const toml::node& node, const std::vector<std::string>& path);
  static std::string type_name(const toml::node& node);

  const std::string& file() const { return file_; }

 private:
  /// A scalar node as a SettingValue (integer, float, boolean or string).
  SettingValue raw_value(std::string_view key) const;

  const toml::table& table_;
  std::vector<std::string> prefix_;
  std::string file_;
};

using pcrf::closest_word;  // "did you mean" hints (pcrf/closest_word.hpp)

/// Reads the table `table.name` of `top` into `target` (starting from table.defaults):
/// every key must be described, values are checked and applied in description order.
/// `given_at` receives where each key given is, by "table.key". `other_keys` are keys the
/// table may also hold that the caller reads itself (no setting of Target).
template <class Target>
void read_setting_table(const Fields& top, const SettingTable<Target>& table, Target& target,
                        std::map<std::string, Where>& given_at, std::vector<std::string_view> other_keys = {}) {
  target = table.defaults;
  const toml::table* node = top.subtable(table.name);
  if (node == nullptr) return;
  given_at[std::string(table.name)] = top.where(table.name);
  std::vector<std::string_view> keys;
  for (const auto& s : table.settings) keys.push_back(s.key);
  keys.insert(keys.end(), other_keys.begin(), other_keys.end());
  const Fields fields(*node, {std::string(table.name)}, top.file(), keys);
  for (const auto& s : table.settings) {
    if (auto value = fields.setting(s)) {
      s.set(target, *value);
      given_at[std::string(table.name) + "." + std::string(s.key)] = fields.where(s.key);
    }
  }
}

}  // namespace pcrf::study::detail
