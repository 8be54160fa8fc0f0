/// \file number_text.hpp
/// \brief The one way the engine writes a number as text for people and files: the shortest
/// text that reads back as the same double ("0.005", "1.8", not "0.005000000000000000104").
#pragma once

#include <charconv>
#include <string>

namespace pcrf {

/// Shortest round-trip text of `value` (std::to_chars); "nan", "inf", "-inf" as it writes them.
inline std::string number_text(double value) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  return std::string(buffer, end);
}

}  // namespace pcrf
