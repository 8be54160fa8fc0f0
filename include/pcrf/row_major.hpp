/// \file row_major.hpp
/// \brief Row-major indexing of a multi-dimensional space (the last dimension varies
/// fastest): a case's linear index ↔ its coordinates, as the case space and the cube store them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pcrf {

/// Coordinates of linear index `index` in a space of `shape` into `coords` (as many).
inline void unravel_into(std::int64_t index, const std::vector<std::size_t>& shape, std::span<std::size_t> coords) {
  auto rest = static_cast<std::size_t>(index);
  for (std::size_t d = shape.size(); d-- > 0;) {
    coords[d] = rest % shape[d];
    rest /= shape[d];
  }
}

/// Coordinates of linear index `index` in a space of `shape`.
inline std::vector<std::size_t> unravel(std::int64_t index, const std::vector<std::size_t>& shape) {
  std::vector<std::size_t> coords(shape.size());
  unravel_into(index, shape, coords);
  return coords;
}

/// Linear index of `coords` in a space of `shape` (inverse of unravel).
inline std::int64_t ravel(const std::vector<std::size_t>& coords, const std::vector<std::size_t>& shape) {
  std::size_t index = 0;
  for (std::size_t d = 0; d < shape.size(); ++d) index = index * shape[d] + coords[d];
  return static_cast<std::int64_t>(index);
}

}  // namespace pcrf
