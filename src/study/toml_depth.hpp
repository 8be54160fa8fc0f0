// A guard run on study text before toml++ parses it: toml++ 3.3 (Debian 12 and 13) recurses
// once per part of a dotted key or table header, so one key of tens of thousands of parts
// overflows the stack. No study key has more than a handful of parts.
#pragma once

#include <cstddef>
#include <string>

namespace pcrf::study::detail {

/// Parts a dotted key or table header may have ("a.b.c" has 3).
inline constexpr std::size_t kMaxKeyParts = 64;

/// \throws UserError "FILE:LINE: ..." at the first dotted name of more than kMaxKeyParts
/// parts (dots outside strings and comments, between two of `= [ ] { } ,` or line ends).
void refuse_deep_keys(const std::string& text, const std::string& file);

}  // namespace pcrf::study::detail
