// Outputs that never destroy inputs (see output_file.hpp).
#include "pcrf/io/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

std::string reason(int error) { return std::strerror(error); }

/// The folder that holds a file ("." for a bare name).
fs::path folder_of(const fs::path& file) { return file.parent_path().empty() ? fs::path(".") : file.parent_path(); }

/// stat() following links; false when the path is not there (or cannot be looked at).
bool stat_of(const fs::path& p, struct stat& st) { return ::stat(p.c_str(), &st) == 0; }

/// The mode a new file gets from open(…, 0666): mkstemp's 0600 is for secrets, not results.
mode_t user_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  (void)::fsync(fd);  // best effort: the rename itself is done
  ::close(fd);
}

/// rename() that, unless `overwrite`, refuses a target that exists at that instant.
bool rename_into_place(const fs::path& from, const fs::path& to, bool overwrite) {
  if (overwrite) return std::rename(from.c_str(), to.c_str()) == 0;
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return true;
  if (errno != EINVAL && errno != ENOSYS) return false;
  struct stat st;  // a file system without RENAME_NOREPLACE: check, then rename
  if (::lstat(to.c_str(), &st) == 0) {
    errno = EEXIST;
    return false;
  }
  return std::rename(from.c_str(), to.c_str()) == 0;
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

OutputFile::Opened OutputFile::open(const fs::path& target, const std::vector<fs::path>& inputs, bool overwrite) {
  check_output(target, inputs, overwrite);
  struct stat st;
  if (stat_of(target, st) && !S_ISREG(st.st_mode)) {  // a device or a pipe: in place, nothing to rename
    const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw OutputError(target.string() + ": cannot open: " + reason(errno), errno);
    return {{}, fd};
  }
  const fs::path folder = folder_of(target);
  std::string pattern = (folder / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkostemp(pattern.data(), O_CLOEXEC);
  if (fd < 0) throw OutputError(target.string() + ": cannot create a file in " + folder.string() + ": " + reason(errno), errno);
  if (::fchmod(fd, user_file_mode()) != 0) {
    const int error = errno;
    ::close(fd);
    ::unlink(pattern.c_str());
    throw OutputError(target.string() + ": cannot set the mode of " + pattern + ": " + reason(error), error);
  }
  return {pattern, fd};
}

OutputFile::OutputFile(fs::path target, const std::vector<fs::path>& inputs, bool overwrite)
    : OutputFile(target, overwrite, open(target, inputs, overwrite)) {}

OutputFile::OutputFile(fs::path target, bool overwrite, Opened opened)
    : target_(std::move(target)), temporary_(std::move(opened.temporary)), overwrite_(overwrite), fd_(opened.fd),
      buffer_(fd_, target_.string()), stream_(&buffer_) {
  stream_.exceptions(std::ios::badbit);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
}

void OutputFile::commit() {
  stream_.flush();
  buffer_.drain();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw OutputError(target_.string() + ": cannot write: " + reason(errno), errno);
  if (temporary_.empty()) {
    committed_ = true;
    return;
  }
  // By path: a writer given temporary() may have replaced the file there.
  const int sync_fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
  if (sync_fd < 0 || ::fsync(sync_fd) != 0) {
    const int error = errno;
    if (sync_fd >= 0) ::close(sync_fd);
    throw OutputError(target_.string() + ": cannot write: " + reason(error), error);
  }
  ::close(sync_fd);
  if (!rename_into_place(temporary_, target_, overwrite_)) {
    const int error = errno;
    if (error == EEXIST) throw OutputError(target_.string() + ": appeared while it was written; use --overwrite to replace it");
    throw OutputError(target_.string() + ": cannot replace it with " + temporary_.string() + ": " + reason(error), error);
  }
  committed_ = true;
  sync_folder(folder_of(target_));
}

}  // namespace pcrf::io
