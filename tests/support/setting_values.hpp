/// \file setting_values.hpp
/// \brief For tests that loop over every described setting: a valid value other than a
/// given one, and a value the description must reject.
#pragma once

#include <optional>
#include <string>

#include "pcrf/setting.hpp"

namespace pcrf::test {

/// A valid value different from `current`: numbers doubled (0 → 0.5), integers doubled,
/// flags flipped, choices the next word.
template <class Target>
SettingValue other_value(const Setting<Target>& s, const SettingValue& current) {
  switch (s.type) {
    case SettingType::kFlag: return !std::get<bool>(current);
    case SettingType::kInteger: return std::get<std::int64_t>(current) * 2 + 1;
    case SettingType::kWords: return s.choices.front();
    case SettingType::kChoice:
      for (std::size_t i = 0; i < s.choices.size(); ++i)
        if (s.choices[i] == std::get<std::string>(current)) return s.choices[(i + 1) % s.choices.size()];
      return s.choices.front();
    case SettingType::kNumber: break;
  }
  if (std::holds_alternative<std::string>(current)) return 2.0;  // a word ("until-rest"): a number instead
  const double v = std::get<double>(current);
  if (s.bound == Bound::kFraction || s.bound == Bound::kOpenUnit) return v == 0.0 ? 0.5 : 0.5 * v;
  return v == 0.0 ? 0.5 : 2.0 * v;
}

/// A value of the right type outside the setting's bound, or nullopt when every value of
/// its type is allowed.
template <class Target>
std::optional<std::string> out_of_bound_text(const Setting<Target>& s) {
  if (s.type == SettingType::kChoice || s.type == SettingType::kWords) return std::string("no-such-word");
  if (s.type == SettingType::kFlag) return std::string("maybe");
  switch (s.bound) {
    case Bound::kAny: return std::nullopt;
    case Bound::kPositive: return std::string("0");
    case Bound::kNonNegative: return std::string("-1");
    case Bound::kAtLeastOne: return std::string("0");
    case Bound::kAtLeast: return number_text(s.at_least - 1.0);
    case Bound::kFraction: return std::string("1");
    case Bound::kOpenUnit: return std::string("1");
  }
  return std::nullopt;
}

/// A value as a TOML literal.
inline std::string toml_literal(const SettingValue& value) {
  if (const auto* word = std::get_if<std::string>(&value)) return "\"" + *word + "\"";
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  return setting_text(value);
}

}  // namespace pcrf::test
