/// \file cube_merge.hpp
/// \brief Joins the cubes of a sharded run into the cube the unsharded run would have made.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pcrf::cube {

/// Checks that `parts` are cubes of one study (same fingerprint and shape), that no case is
/// in two of them, and that together they hold every case; then writes their union to
/// `output` by the one output rule (io::OutputFile: never one of the parts, refused when it
/// exists unless `overwrite`, renamed into place only when complete). Side variables take
/// each value from the part that has it; messages are joined.
///
/// `runs_variable` names a side variable that a cube of an adaptive plan carries (the
/// caller's vocabulary, not the cube's): over every dimension but the last, how many of the
/// row's cases along the last dimension were run, the first ones; the others are not
/// missing. Empty, or absent from the cube: every case must be in a part.
/// 	hrows CubeError naming the file and the problem (what is missing, which case is twice);
/// io::OutputError for an output refused or not written.
void merge_cubes(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& output, bool overwrite,
                 const std::string& runs_variable = {});

}  // namespace pcrf::cube
