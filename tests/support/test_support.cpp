#include "support/test_support.hpp"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace pcrf::test {

std::optional<std::filesystem::path> records_dir() {
  std::filesystem::path dir = PCRF_DEFAULT_RECORDS_DIR;
  if (const char* env = std::getenv("PCRF_RECORDS_DIR")) dir = env;
  if (std::filesystem::is_directory(dir)) return dir;
  return std::nullopt;
}

std::filesystem::path pcrf_executable() {
  return std::filesystem::path(PCRF_BINARY_DIR) / "pcrf";
}

std::filesystem::path source_dir() { return PCRF_SOURCE_DIR; }

std::filesystem::path scratch_dir(const std::string& name) {
  auto dir = std::filesystem::path(PCRF_BINARY_DIR) / "test-scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path write_file(const std::filesystem::path& dir, const std::string& name,
                                 const std::string& bytes) {
  const auto path = dir / name;
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  return path;
}

static std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CommandResult run_command(const std::string& command) {
  auto dir = std::filesystem::temp_directory_path();
  static int counter = 0;
  const std::string stem = "pcrf-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const auto out_file = dir / (stem + ".out");
  const auto err_file = dir / (stem + ".err");
  const std::string full = "(" + command + ") >" + out_file.string() + " 2>" + err_file.string();
  const int status = std::system(full.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out_file);
  r.err = slurp(err_file);
  std::filesystem::remove(out_file);
  std::filesystem::remove(err_file);
  return r;
}

}  // namespace pcrf::test
