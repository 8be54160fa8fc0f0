/// \file closest_word.hpp
/// \brief "Did you mean" hints: the closest allowed word to a misspelt one (study keys,
/// metric names, command-line flags).
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace pcrf {

/// Levenshtein distance (insertions, deletions, substitutions).
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The closest allowed word within two edits (else one that starts with `word`), for
/// "did you mean" hints; empty if none.
inline std::string closest_word(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string best;
  std::size_t best_distance = 3;
  for (auto c : candidates) {
    const auto d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(c);
    }
  }
  if (best.empty())  // a truncated name: "theta_max" for "theta_max_rad"
    for (auto c : candidates)
      if (word.size() >= 3 && c.substr(0, word.size()) == word) return std::string(c);
  return best;
}

}  // namespace pcrf
