// Outputs that never destroy inputs (see output_file.hpp).
#include "pcrf/io/output_file.hpp"

#include <sys/stat.h>

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

/// stat() following links; false when the path is not there (or cannot be looked at).
bool stat_of(const fs::path& p, struct stat& st) { return ::stat(p.c_str(), &st) == 0; }

/// `target`, once check_output() accepts it.
fs::path checked(fs::path target, const std::vector<fs::path>& inputs, bool overwrite) {
  check_output(target, inputs, overwrite);
  return target;
}

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  struct stat sa, sb;
  if (stat_of(a, sa) && stat_of(b, sb)) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  const auto ca = fs::weakly_canonical(fs::absolute(a, ea), ea), cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return !ea && !eb && ca == cb;
}

void check_output(const fs::path& output, const std::vector<fs::path>& inputs, bool overwrite) {
  for (const auto& input : inputs)
    if (same_file(output, input)) {
      const std::string is = output == input ? "is the input" : "resolves to the input " + input.string();
      throw OutputError(output.string() + ": " + is + "; choose another output (--overwrite does not apply to inputs)");
    }
  struct stat st;
  if (!stat_of(output, st)) return;
  if (S_ISDIR(st.st_mode)) throw OutputError(output.string() + ": is a folder; name a file");
  if (S_ISREG(st.st_mode) && !overwrite) throw OutputError(output.string() + ": already exists; use --overwrite to replace it");
}

OutputFile::OutputFile(fs::path target, const std::vector<fs::path>& inputs, bool overwrite)
    : file_(checked(std::move(target), inputs, overwrite), overwrite),
      buffer_(file_.fd(), file_.target().string()), stream_(&buffer_) {
  stream_.exceptions(std::ios::badbit);
}

void OutputFile::commit() {
  stream_.flush();
  buffer_.drain();
  file_.commit();
}

}  // namespace pcrf::io
