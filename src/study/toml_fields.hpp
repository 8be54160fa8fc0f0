// Checked access to the keys of one TOML table: unknown keys, wrong types and bad values
// become StudyError messages "FILE:LINE: dotted.key: problem".
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pcrf::study::detail {

class Fields {
 public:
  /// \param prefix dotted path of the table ("" for the root, "axes", "records[2]")
  /// \param allowed the keys this table may hold; any other key is an error
  Fields(const toml::table& table, std::string prefix, std::string file,
         std::initializer_list<std::string_view> allowed);

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
  /// A string or an array of strings.
  std::vector<std::string> texts(std::string_view key) const;

  /// "FILE:LINE" of a key (or of the table when the key is absent).
  std::string where(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

  /// Error at any node, for values nested in arrays.
  [[noreturn]] static void fail_at(const std::string& file, const toml::node* node,
                                   const std::string& path, const std::string& problem);
  static std::string where_at(const std::string& file, const toml::node* node);
  /// A finite number from an integer or float node. \throws StudyError.
  static double number_at(const std::string& file, const toml::node& node, const std::string& path);
  static std::string type_name(const toml::node& node);

  const std::string& file() const { return file_; }

 private:
  const toml::table& table_;
  std::string prefix_;
  std::string file_;
};

/// The closest allowed word within two edits (else one that starts with `word`), for
/// "did you mean" hints; empty if none.
std::string closest_word(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace pcrf::study::detail
