/// \file setting.hpp
/// \brief One description per setting: key, member, unit, default, validity check and a
/// one-line doc. Study files, `pcrf run` flags, cube attributes, the study fingerprint and the
/// key tables of studies/README.md are all derived from these descriptions.
///
/// A SettingTable<Target> describes the members of one options struct (PhysicsOptions,
/// SolverSettings, the study's RunOptions, …) as they appear in one TOML table. The table
/// holds its defaults as a Target value, so a default is written once, in the struct or in
/// the preset that fills it. Readers apply values in table order, not in the order a user
/// wrote them: a setting that replaces others (the solver `preset`) comes first.
///
/// This header knows no TOML, no command line and no HDF5: it turns text or typed values
/// into checked member values and back.
#pragma once

#include "pcrf/number_text.hpp"
#include "pcrf/user_error.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace pcrf {

/// A setting's value as files and command lines carry it.
using SettingValue = std::variant<double, std::int64_t, bool, std::string>;

/// The kind of value a setting takes.
enum class SettingType {
  kNumber,   ///< a finite real number (TOML integer or float)
  kInteger,  ///< a whole number
  kFlag,     ///< true or false
  kChoice,   ///< one word out of a fixed list
  kWords,    ///< a list of distinct words out of a fixed list (TOML array; flag: comma-separated)
};

/// The range a number or integer setting admits.
enum class Bound {
  kAny,          ///< any finite value
  kPositive,     ///< > 0
  kNonNegative,  ///< ≥ 0
  kAtLeastOne,   ///< ≥ 1
  kAtLeast,      ///< ≥ the setting's `at_least`
  kFraction,     ///< in [0, 1)
  kOpenUnit,     ///< in (0, 1)
};

template <class Target>
struct Setting {
  std::string_view key;   ///< TOML key, also the flag (`tail_s` → `--tail-s`) and attribute suffix
  SettingType type = SettingType::kNumber;
  std::string_view unit;  ///< UDUNITS text ("s", "rad", "rad/s", "1"); empty for flags and choices
  Bound bound = Bound::kAny;
  double at_least = 0.0;  ///< Bound::kAtLeast: the least value admitted (stated where the rule lives)
  std::vector<std::string> choices;  ///< kChoice: the words allowed
  /// kNumber: words that stand for a value outside `bound` ("until-rest" for an unbounded
  /// tail). A value given as one of them is carried as the word (fingerprint, attributes).
  std::vector<std::string> number_words;
  std::string_view doc;              ///< one line, for help texts and the README tables
  /// False for keys that change how a run behaves but not what it computes ([run]), and
  /// for keys whose whole effect is captured by other keys (the solver `preset`).
  bool in_fingerprint = true;
  std::vector<std::string_view> aliases;  ///< older command-line spellings ("--tail")
  std::function<SettingValue(const Target&)> get;
  /// Stores a value that check_setting() accepted.
  std::function<void(Target&, const SettingValue&)> set;
};

/// The settings of one options struct, as one TOML table holds them.
template <class Target>
struct SettingTable {
  std::string_view name;  ///< TOML table, also the attribute prefix ("solver" → solver_rtol)
  Target defaults;        ///< the value of every setting the user does not give
  std::vector<Setting<Target>> settings;

  const Setting<Target>* find(std::string_view key) const {
    for (const auto& s : settings)
      if (s.key == key) return &s;
    return nullptr;
  }
};


// ---- values as text ------------------------------------------------------------------------

/// A value as the fingerprint, attributes and messages write it: numbers with 17 significant
/// digits, flags as 1 or 0, words as they are.
inline std::string setting_text(const SettingValue& value) {
  std::ostringstream out;
  out.precision(17);
  std::visit([&out](const auto& v) { out << v; }, value);
  return out.str();
}

/// For people: "true"/"false" for flags, the shortest text that reads back as the same
/// number, words as they are.
inline std::string setting_display(const SettingValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const double* d = std::get_if<double>(&value)) return number_text(*d);
  return setting_text(value);
}

/// What the setting admits, for messages and tables: "number > 0 [s]", "true or false", …
template <class Target>
std::string setting_kind_text(const Setting<Target>& s) {
  switch (s.type) {
    case SettingType::kFlag: return "true or false";
    case SettingType::kChoice:
    case SettingType::kWords: {
      std::string text = s.type == SettingType::kWords ? "list of " : "";
      for (std::size_t i = 0; i < s.choices.size(); ++i)
        text += (i == 0 ? "" : (i + 1 == s.choices.size() ? " or " : ", ")) + ("\"" + s.choices[i] + "\"");
      return text;
    }
    case SettingType::kNumber:
    case SettingType::kInteger: break;
  }
  std::string text = s.type == SettingType::kInteger ? "integer" : "number";
  switch (s.bound) {
    case Bound::kAny: break;
    case Bound::kPositive: text += " > 0"; break;
    case Bound::kNonNegative: text += " ≥ 0"; break;
    case Bound::kAtLeastOne: text += " ≥ 1"; break;
    case Bound::kAtLeast: text += " ≥ " + number_text(s.at_least); break;
    case Bound::kFraction: text += " in [0, 1)"; break;
    case Bound::kOpenUnit: text += " in (0, 1)"; break;
  }
  if (!s.unit.empty() && s.unit != "1") text += " [" + std::string(s.unit) + "]";
  for (const auto& w : s.number_words) text += " or \"" + w + "\"";
  return text;
}

/// Why `value` is not acceptable for `s`; empty when it is. A number given for an integer
/// setting is accepted only when it is whole.
template <class Target>
std::string check_setting(const Setting<Target>& s, SettingValue& value) {
  switch (s.type) {
    case SettingType::kFlag:
      return std::holds_alternative<bool>(value) ? "" : "expected true or false";
    case SettingType::kChoice: {
      const auto* word = std::get_if<std::string>(&value);
      if (word == nullptr) return "expected " + setting_kind_text(s);
      for (const auto& c : s.choices)
        if (c == *word) return "";
      return "unknown value \"" + *word + "\" (expected " + setting_kind_text(s) + ")";
    }
    case SettingType::kWords: {
      const auto* words = std::get_if<std::string>(&value);
      if (words == nullptr) return "expected " + setting_kind_text(s);
      std::vector<std::string> seen;
      std::stringstream in(*words);
      for (std::string word; std::getline(in, word, ',');) {
        bool known = false;
        for (const auto& c : s.choices) known = known || c == word;
        if (!known) return "unknown value \"" + word + "\" (expected " + setting_kind_text(s) + ")";
        for (const auto& w : seen)
          if (w == word) return "\"" + word + "\" is listed twice";
        seen.push_back(word);
      }
      return seen.empty() ? "the list is empty" : "";
    }
    case SettingType::kInteger:
      if (const double* d = std::get_if<double>(&value)) {
        if (!(std::isfinite(*d) && *d == std::floor(*d) && std::fabs(*d) < 9e15)) return "expected an integer";
        value = static_cast<std::int64_t>(*d);
      }
      if (!std::holds_alternative<std::int64_t>(value)) return "expected an integer";
      break;
    case SettingType::kNumber:
      if (const auto* i = std::get_if<std::int64_t>(&value)) value = static_cast<double>(*i);
      if (const auto* word = std::get_if<std::string>(&value); word != nullptr && !s.number_words.empty()) {
        for (const auto& w : s.number_words)
          if (w == *word) return "";
        return "unknown value \"" + *word + "\" (expected " + setting_kind_text(s) + ")";
      }
      if (!std::holds_alternative<double>(value)) return "expected a number";
      if (!std::isfinite(std::get<double>(value))) return "must be a finite number";
      break;
  }
  const double v = std::holds_alternative<double>(value) ? std::get<double>(value)
                                                         : static_cast<double>(std::get<std::int64_t>(value));
  bool ok = true;
  const char* rule = "";
  switch (s.bound) {
    case Bound::kAny: break;
    case Bound::kPositive: ok = v > 0.0, rule = "must be positive"; break;
    case Bound::kNonNegative: ok = v >= 0.0, rule = "must not be negative"; break;
    case Bound::kAtLeastOne: ok = v >= 1.0, rule = "must be at least 1"; break;
    case Bound::kAtLeast:
      if (v >= s.at_least) break;
      return "must be at least " + number_text(s.at_least) + " (got " + setting_text(value) + ")";
    case Bound::kFraction: ok = v >= 0.0 && v < 1.0, rule = "must be at least 0 and below 1"; break;
    case Bound::kOpenUnit: ok = v > 0.0 && v < 1.0, rule = "must be above 0 and below 1"; break;
  }
  if (ok) return "";  // the message is formatted only for a value that fails
  return rule + (" (got " + setting_text(value) + ")");
}

/// Parses command-line text into the setting's type (then check_setting() applies).
/// \throws std::invalid_argument naming the text when it is not of the setting's type.
template <class Target>
SettingValue parse_setting_text(const Setting<Target>& s, const std::string& text) {
  switch (s.type) {
    case SettingType::kFlag:
      if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
      if (text == "false" || text == "0" || text == "off" || text == "no") return false;
      throw std::invalid_argument("'" + text + "' is not true or false");
    case SettingType::kChoice:
    case SettingType::kWords: return text;
    case SettingType::kInteger:
    case SettingType::kNumber: {
      for (const auto& w : s.number_words)
        if (w == text) return text;
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != text.size()) throw std::invalid_argument("'" + text + "' is not a number");
      return value;
    }
  }
  return text;
}

// ---- building descriptions -------------------------------------------------------------------

/// A real-valued member.
template <class Target>
Setting<Target> number_setting(std::string_view key, double Target::*member, std::string_view unit, Bound bound,
                               std::string_view doc) {
  Setting<Target> s;
  s.key = key;
  s.type = SettingType::kNumber;
  s.unit = unit;
  s.bound = bound;
  s.doc = doc;
  s.get = [member](const Target& t) { return SettingValue(t.*member); };
  s.set = [member](Target& t, const SettingValue& v) { t.*member = std::get<double>(v); };
  return s;
}

/// A real-valued member that also takes words standing for values outside `bound`
/// (`words[k]` stores `values[k]`, and reads back as the word).
template <class Target>
Setting<Target> number_or_word_setting(std::string_view key, double Target::*member, std::string_view unit, Bound bound,
                                       std::vector<std::pair<std::string, double>> words, std::string_view doc) {
  Setting<Target> s = number_setting(key, member, unit, bound, doc);
  for (const auto& w : words) s.number_words.push_back(w.first);
  s.get = [member, words](const Target& t) {
    for (const auto& w : words)
      if (w.second == t.*member) return SettingValue(w.first);
    return SettingValue(t.*member);
  };
  s.set = [member, words](Target& t, const SettingValue& v) {
    if (const auto* word = std::get_if<std::string>(&v)) {
      for (const auto& w : words)
        if (w.first == *word) t.*member = w.second;
      return;
    }
    t.*member = std::get<double>(v);
  };
  return s;
}

/// An integer member of any integral type.
template <class Target, class Int>
Setting<Target> integer_setting(std::string_view key, Int Target::*member, Bound bound, std::string_view doc) {
  Setting<Target> s;
  s.key = key;
  s.type = SettingType::kInteger;
  s.unit = "1";
  s.bound = bound;
  s.doc = doc;
  s.get = [member](const Target& t) { return SettingValue(static_cast<std::int64_t>(t.*member)); };
  s.set = [member](Target& t, const SettingValue& v) { t.*member = static_cast<Int>(std::get<std::int64_t>(v)); };
  return s;
}

/// A boolean member.
template <class Target>
Setting<Target> flag_setting(std::string_view key, bool Target::*member, std::string_view doc) {
  Setting<Target> s;
  s.key = key;
  s.type = SettingType::kFlag;
  s.doc = doc;
  s.get = [member](const Target& t) { return SettingValue(t.*member); };
  s.set = [member](Target& t, const SettingValue& v) { t.*member = std::get<bool>(v); };
  return s;
}

/// A list of words held as one comma-separated string member.
template <class Target>
Setting<Target> words_setting(std::string_view key, std::string Target::*member, std::vector<std::string> choices,
                              std::string_view doc) {
  Setting<Target> s;
  s.key = key;
  s.type = SettingType::kWords;
  s.choices = std::move(choices);
  s.doc = doc;
  s.get = [member](const Target& t) { return SettingValue(t.*member); };
  s.set = [member](Target& t, const SettingValue& v) { t.*member = std::get<std::string>(v); };
  return s;
}

/// One text name of an enumeration value. A table of them is the enumeration's only
/// spelling: its text forms (name_of, parse_name) and its choices (values_of) read it.
template <class Enum>
struct EnumName {
  Enum value;
  const char* name;
};

template <class Enum, std::size_t N>
std::string name_of(const std::array<EnumName<Enum>, N>& names, Enum value) {
  for (const auto& n : names)
    if (n.value == value) return n.name;
  return "unknown";
}

/// \throws std::invalid_argument "unknown WHAT 'text' (expected a, b or c)".
template <class Enum, std::size_t N>
Enum parse_name(const std::array<EnumName<Enum>, N>& names, const std::string& text, std::string_view what) {
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) {
    if (text == names[i].name) return names[i].value;
    expected += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i].name);
  }
  throw std::invalid_argument("unknown " + std::string(what) + " '" + text + "' (expected " + expected + ")");
}

template <class Enum, std::size_t N>
std::vector<Enum> values_of(const std::array<EnumName<Enum>, N>& names) {
  std::vector<Enum> values;
  for (const auto& n : names) values.push_back(n.value);
  return values;
}

/// An enumeration member with text forms `format(value)` and `parse(text)`.
template <class Target, class Enum>
Setting<Target> choice_setting(std::string_view key, Enum Target::*member, std::vector<Enum> values,
                               std::string (*format)(Enum), Enum (*parse)(const std::string&), std::string_view doc) {
  Setting<Target> s;
  s.key = key;
  s.type = SettingType::kChoice;
  s.doc = doc;
  for (Enum e : values) s.choices.push_back(format(e));
  s.get = [member, format](const Target& t) { return SettingValue(format(t.*member)); };
  s.set = [member, parse](Target& t, const SettingValue& v) { t.*member = parse(std::get<std::string>(v)); };
  return s;
}

}  // namespace pcrf
