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
///
/// Missing cases are an error unless `allow_missing`: then the merged cube keeps them not
/// run and says how many in its attribute kMissingCasesName.
/// \throws CubeError naming the file and the problem (what is missing, which case is twice);
/// io::OutputError for an output refused or not written.
struct MergeResult {
  std::size_t missing = 0;  ///< cases in no part (allowed by `allow_missing`)
  std::size_t total = 0;    ///< cases of the cube
};
MergeResult merge_cubes(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& output, bool overwrite,
                        const std::string& runs_variable = {}, bool allow_missing = false);

/// Attribute of a merged cube that lacks cases (merge_cubes with `allow_missing`).
inline constexpr const char* kMissingCasesName = "merge_missing_cases";

}  // namespace pcrf::cube
