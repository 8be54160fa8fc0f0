/// \file number_text.hpp
/// \brief The one way the engine writes a number as text for people and files: the shortest
/// text that reads back as the same double ("0.005", "1.8", not "0.005000000000000000104").
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace pcrf {

/// Shortest round-trip text of `value` (std::to_chars); "nan", "inf", "-inf" as it writes them.
inline std::string number_text(double value) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  return std::string(buffer, end);
}

/// The shortest decimal (at most 12 significant digits) within 4 units in the last place of
/// `value`, as a double; `value` itself when there is none. Values computed from decimals
/// (a range's from + t (to - from)) carry rounding errors of an ulp or two: this returns
/// the decimal the study meant (1.8, not 1.7999999999999998), so that a cube's coordinate
/// matches the number a reader types. Twelve digits bound the snapping: a value that is
/// not near a short decimal (1/3, a log-spaced value) stays as it is.
inline double shortest_decimal_near(double value) {
  if (!std::isfinite(value) || value == 0.0) return value;
  const double tolerance = 4.0 * (std::nextafter(std::fabs(value), HUGE_VAL) - std::fabs(value));
  char buffer[32];
  for (int digits = 1; digits <= 12; ++digits) {
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific, digits - 1).ptr;
    double decimal = 0.0;
    std::from_chars(buffer, end, decimal);
    if (std::fabs(decimal - value) <= tolerance) return decimal;
  }
  return value;
}

}  // namespace pcrf
