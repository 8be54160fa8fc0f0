/// \file byte_order_mark.hpp
/// \brief The byte-order mark a text file may start with. A spreadsheet's "CSV UTF-8" and
/// some editors write U+FEFF (EF BB BF) before the first character: it is no part of the text,
/// and every text the engine reads (a hazard curve, a record) skips it. A UTF-16 mark (FF FE,
/// FE FF) says the text is not UTF-8 at all: readers refuse it by name.
#pragma once

#include <string_view>

namespace pcrf {

/// The UTF-8 encoding of U+FEFF.
inline constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

/// `text` without a leading UTF-8 byte-order mark.
inline std::string_view without_byte_order_mark(std::string_view text) {
  if (text.substr(0, kUtf8ByteOrderMark.size()) == kUtf8ByteOrderMark) text.remove_prefix(kUtf8ByteOrderMark.size());
  return text;
}

/// Whether `text` starts with a UTF-16 byte-order mark (either byte order).
inline bool starts_as_utf16(std::string_view text) {
  return text.size() >= 2 && ((text[0] == '\xFF' && text[1] == '\xFE') || (text[0] == '\xFE' && text[1] == '\xFF'));
}

}  // namespace pcrf
