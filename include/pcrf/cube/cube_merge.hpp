/// \file cube_merge.hpp
/// \brief Joins the cubes of a sharded run into the cube the unsharded run would have made.
#pragma once

#include <filesystem>
#include <vector>

namespace pcrf::cube {

/// Checks that `parts` are cubes of one study (same fingerprint and shape), that no case is
/// in two of them, and that together they hold every case; then writes their union to
/// `output` (refused when it exists, unless `overwrite`; never one of the parts). Side
/// variables take each value from the part that has it; messages are joined.
/// \throws CubeError naming the file and the problem (what is missing, which case is twice).
void merge_cubes(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& output, bool overwrite);

}  // namespace pcrf::cube
