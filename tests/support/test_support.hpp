/// \file test_support.hpp
/// \brief Helpers shared by the test suites: where the shared records are, where the
/// built `pcrf` executable is, running a command and capturing its output.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace pcrf::test {

/// ../shared/records (or $PCRF_RECORDS_DIR) if it exists; nullopt otherwise.
std::optional<std::filesystem::path> records_dir();

/// Path of the built `pcrf` executable.
std::filesystem::path pcrf_executable();

/// Root of the source tree (for studies/*.toml).
std::filesystem::path source_dir();

/// A fresh empty directory under the build tree's test scratch area.
std::filesystem::path scratch_dir(const std::string& name);

/// Writes `bytes` to dir/name exactly as given (binary: "\r\n" stays "\r\n").
/// The whole content of a file ("" when it cannot be read).
std::string read_file(const std::filesystem::path& path);
std::filesystem::path write_file(const std::filesystem::path& dir, const std::string& name,
                                 const std::string& bytes);

struct CommandResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};
/// Runs `command` through /bin/sh, capturing stdout and stderr.
CommandResult run_command(const std::string& command);

}  // namespace pcrf::test

/// Skips the current test when the shared records folder is absent.
#define PCRF_REQUIRE_RECORDS(var)                                              \
  auto var##_opt = ::pcrf::test::records_dir();                                \
  if (!var##_opt) GTEST_SKIP() << "../shared/records not present";             \
  const std::filesystem::path var = *var##_opt
