/// \file case_axis_layout.hpp
/// \brief The cube of the part and sealed-chunk tests: one `case` axis of `cases` cases, its
/// coordinate the case number, two metrics (theta_max_rad, impacts) and two statuses
/// (at_rest, overturned); `fingerprint` tells one test's cubes from another's.
#pragma once

#include <cstdint>
#include <string>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {

inline CubeLayout case_axis_layout(std::int64_t cases, const std::string& fingerprint) {
  CubeLayout l;
  l.dimensions = {{"case", static_cast<std::size_t>(cases)}};
  Coordinate index{"case", "case", "", "", {}, {}, false, true};
  for (std::int64_t i = 0; i < cases; ++i) index.numbers.push_back(static_cast<double>(i));
  l.coordinates = {index};
  l.metrics = {{"theta_max_rad", "rad", ""}, {"impacts", "1", ""}};
  l.status_flags = {{0, "at_rest"}, {3, "overturned"}};
  l.attributes = {{kFingerprintName, fingerprint}};
  return l;
}

}  // namespace pcrf::cube
