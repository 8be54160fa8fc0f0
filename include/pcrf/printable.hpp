/// \file printable.hpp
/// \brief Text that is safe to show on a terminal: messages quote file contents (a header
/// line, a token), and a binary or UTF-16 file must not send raw bytes, NULs or escape
/// sequences to the user's terminal.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace pcrf {

/// `text` with valid UTF-8 kept as it is, and every control byte (below 0x20, 0x7F) and every
/// byte that is not part of a valid UTF-8 sequence written as \xNN.
inline std::string printable(std::string_view text) {
  auto escaped = [](unsigned char byte) {
    char buffer[5];
    std::snprintf(buffer, sizeof buffer, "\\x%02X", byte);
    return std::string(buffer);
  };
  auto continuation = [&](std::size_t i) {
    return i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;
  };
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    std::size_t length = 0;  // of a valid multi-byte sequence starting here
    if (byte >= 0xC2 && byte <= 0xDF) length = 2;
    else if (byte >= 0xE0 && byte <= 0xEF) length = 3;
    else if (byte >= 0xF0 && byte <= 0xF4) length = 4;
    bool valid = length > 0;
    for (std::size_t k = 1; valid && k < length; ++k) valid = continuation(i + k);
    if (valid) {
      out.append(text.substr(i, length));
      i += length;
    } else if (byte < 0x20 || byte >= 0x7F) {
      out += escaped(byte);
      ++i;
    } else {
      out.push_back(static_cast<char>(byte));
      ++i;
    }
  }
  return out;
}

}  // namespace pcrf
