/// \file given_settings.hpp
/// \brief Settings a user gave by name (a command-line flag, a Python keyword), checked
/// against their description and applied in table order, so that a setting which replaces
/// others (the solver `preset`) comes first whatever the order they were given in. A bad value
/// is a UserError at the setting's key, which each front end spells its own way
/// ("--tail-s: must be positive (got -1)", "tail_s=: must be positive (got -1)").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pcrf/user_error.hpp"
#include "pcrf/setting.hpp"

namespace pcrf::api {

template <class Target>
using GivenSettings = std::vector<std::pair<const Setting<Target>*, SettingValue>>;

/// `value` checked (and converted: a whole number for an integer) for `s`.
/// \throws UserError at the setting's key.
template <class Target>
SettingValue checked_setting(const Setting<Target>& s, SettingValue value) {
  if (const auto problem = check_setting(s, value); !problem.empty()) throw UserError(std::string(s.key), problem);
  return value;
}

/// `text` (as a command line gives it) read and checked for `s`. \throws UserError.
template <class Target>
SettingValue checked_setting_text(const Setting<Target>& s, const std::string& text) {
  SettingValue value;
  try {
    value = parse_setting_text(s, text);
  } catch (const std::invalid_argument& error) {
    throw UserError(std::string(s.key), error.what());
  }
  return checked_setting(s, std::move(value));
}

/// table.defaults with every given value applied, in table order.
template <class Target>
Target resolve_settings(const SettingTable<Target>& table, const GivenSettings<Target>& given) {
  Target target = table.defaults;
  for (const auto& setting : table.settings)
    for (const auto& [which, value] : given)
      if (which == &setting) setting.set(target, value);
  return target;
}

}  // namespace pcrf::api
