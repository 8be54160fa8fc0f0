// Checked TOML table access for the study parser (see toml_fields.hpp).
#include "study/toml_fields.hpp"

#include <algorithm>
#include <cmath>

#include "pcrf/user_error.hpp"

namespace pcrf::study::detail {
namespace {

std::string list_words(const std::vector<std::string_view>& words) {
  std::string text;
  for (auto w : words) text += (text.empty() ? "" : ", ") + std::string(w);
  return text;
}

}  // namespace

Fields::Fields(const toml::table& table, std::vector<std::string> prefix, std::string file,
               const std::vector<std::string_view>& known)
    : table_(table), prefix_(std::move(prefix)), file_(std::move(file)) {
  for (const auto& [key, value] : table_) {
    if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
    std::string problem = "unknown key";
    const auto hint = closest_word(key.str(), known);
    problem += hint.empty() ? " (known keys: " + list_words(known) + ")" : " (did you mean '" + hint + "'?)";
    fail_at(file_, &value, path(key.str()), problem);
  }
}

std::vector<std::string> Fields::path(std::string_view key) const {
  auto keys = prefix_;
  keys.emplace_back(key);
  return keys;
}

std::string Fields::type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

std::vector<std::string> Fields::entry_path(std::string_view key, std::size_t i) const {
  auto keys = path(key);
  keys.push_back(key_index(i));
  return keys;
}

Where Fields::where_at(const std::string& file, const toml::node* node, std::vector<std::string> path) {
  const int line = node != nullptr ? static_cast<int>(node->source().begin.line) : 0;
  return Where{std::move(path), file, line};
}

void Fields::fail_at(const std::string& file, const toml::node* node, std::vector<std::string> path,
                     const std::string& problem) {
  throw UserError(where_at(file, node, std::move(path)), problem);
}

Where Fields::where(std::string_view key) const {
  const toml::node* n = node(key);
  // A missing key points at its table; at the root that says nothing: the file alone.
  return where_at(file_, n != nullptr ? n : (prefix_.empty() ? nullptr : &table_), path(key));
}

void Fields::fail(std::string_view key, const std::string& problem) const {
  const toml::node* n = node(key);
  fail_at(file_, n != nullptr ? n : (prefix_.empty() ? nullptr : &table_), path(key), problem);
}

double Fields::number_at(const std::string& file, const toml::node& node, const std::vector<std::string>& path) {
  double value = 0.0;
  if (const auto* i = node.as_integer())
    value = static_cast<double>(i->get());
  else if (const auto* f = node.as_floating_point())
    value = f->get();
  else
    fail_at(file, &node, path, "expected a number, got " + type_name(node));
  if (!std::isfinite(value)) fail_at(file, &node, path, "must be a finite number");
  return value;
}

std::optional<double> Fields::number(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  return number_at(file_, *n, path(key));
}

std::optional<std::int64_t> Fields::integer(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  if (const auto* i = n->as_integer()) return i->get();
  fail(key, "expected an integer, got " + type_name(*n));
}

std::optional<std::string> Fields::text(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  if (const auto* s = n->as_string()) return s->get();
  fail(key, "expected a string, got " + type_name(*n));
}

std::optional<bool> Fields::flag(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  if (const auto* b = n->as_boolean()) return b->get();
  fail(key, "expected true or false, got " + type_name(*n));
}

const toml::table* Fields::subtable(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return nullptr;
  if (const auto* t = n->as_table()) return t;
  std::string header;
  for (const auto& k : path(key)) header += (header.empty() ? "" : ".") + k;
  fail(key, "expected a table ([" + header + "]), got " + type_name(*n));
}

const toml::array* Fields::array(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return nullptr;
  if (const auto* a = n->as_array()) return a;
  fail(key, "expected an array, got " + type_name(*n));
}

SettingValue Fields::raw_value(std::string_view key) const {
  const toml::node& n = *node(key);
  if (const auto* i = n.as_integer()) return static_cast<std::int64_t>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  if (const auto* b = n.as_boolean()) return b->get();
  if (const auto* s = n.as_string()) return s->get();
  if (const auto* a = n.as_array()) {  // a list of words, as one comma-separated value
    std::string words;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const auto* w = (*a)[i].as_string();
      if (w == nullptr) fail_at(file_, &(*a)[i], entry_path(key, i), "expected a string");
      words += (i ? "," : "") + w->get();
    }
    return words;
  }
  fail(key, "expected a single value, got " + type_name(n));
}

std::vector<std::string> Fields::texts(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return {};
  if (const auto* s = n->as_string()) return {s->get()};
  const auto* a = n->as_array();
  if (a == nullptr) fail(key, "expected a string or an array of strings, got " + type_name(*n));
  if (a->empty()) fail(key, "empty list");
  std::vector<std::string> values;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* s = (*a)[i].as_string();
    if (s == nullptr)
      fail_at(file_, &(*a)[i], entry_path(key, i),
              "expected a string, got " + type_name((*a)[i]));
    values.push_back(s->get());
  }
  return values;
}

}  // namespace pcrf::study::detail
