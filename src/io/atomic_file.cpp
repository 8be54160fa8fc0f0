// The one crash-safe way to replace a file (see atomic_file.hpp).
#include "pcrf/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/file_kind.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

/// The folder that holds a file ("." for a bare name).
fs::path folder_of(const fs::path& file) { return file.parent_path().empty() ? fs::path(".") : file.parent_path(); }

/// The mode a new file gets from open(…, 0666): mkstemp's 0600 is for secrets, not results.
mode_t user_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
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

bool is_other_than_regular(const fs::path& p) {
  struct stat st;
  return ::stat(p.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

}  // namespace

AtomicFile::AtomicFile(fs::path target, bool overwrite, Temporary naming)
    : target_(std::move(target)), overwrite_(overwrite), name_temporary_(naming == Temporary::kPartial) {
  if (naming == Temporary::kUnique && is_other_than_regular(target_)) {  // a device or a pipe: nothing to rename
    // Without blocking: a FIFO that no process reads would wait for one for ever.
    fd_ = ::open(target_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0 && errno == ENXIO)
      throw OutputError(target_.string() + ": is a FIFO that no process reads; start its reader first, or name a file", errno);
    if (fd_ < 0) throw OutputError(target_.string() + ": cannot open: " + std::strerror(errno), errno);
    if (const int flags = ::fcntl(fd_, F_GETFL); flags >= 0) (void)::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
    return;
  }
  if (naming == Temporary::kPartial) {
    // A killed run's .partial (a regular file of one name) is removed and made anew,
    // exclusively: never truncated through a link to another file.
    temporary_ = target_.string() + ".partial";
    remove_stale_sidecar(temporary_, "partial cube (a fold's temporary)");
    fd_ = create_exclusive(temporary_, O_WRONLY);  // the umask decides the mode
    if (fd_ < 0) fail("cannot write", errno);
    slot_ = remember_temporary(temporary_);
    return;
  }
  const fs::path folder = folder_of(target_);
  std::string pattern = (folder / ("." + target_.filename().string() + ".XXXXXX")).string();
  fd_ = ::mkostemp(pattern.data(), O_CLOEXEC);
  if (fd_ < 0)
    throw OutputError(target_.string() + ": cannot create a file in " + folder.string() + ": " + std::strerror(errno), errno);
  temporary_ = pattern;
  slot_ = remember_temporary(temporary_);
  if (::fchmod(fd_, user_file_mode()) != 0) {
    const int error = errno;
    throw OutputError(target_.string() + ": cannot set the mode of " + pattern + ": " + std::strerror(error), error);
  }
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
  forget_temporary(slot_);
}

void AtomicFile::fail(const char* action, int error) const {
  std::string text = target_.string() + ": " + action;
  if (name_temporary_) text += " " + temporary_.string();
  throw OutputError(text + ": " + std::strerror(error), error);
}

void AtomicFile::write(const char* data, std::size_t size) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write", n < 0 ? errno : EIO);
    done += static_cast<std::size_t>(n);
  }
}

void AtomicFile::copy_from(const fs::path& source) {
  struct Source {
    int fd;
    ~Source() {
      if (fd >= 0) ::close(fd);
    }
  } in{open_regular_to_read(source)};  // never a FIFO, which would block
  bool kernel_copy = true;
  for (;;) {
    ssize_t n = 0;
    if (kernel_copy) {
      n = ::copy_file_range(in.fd, nullptr, fd_, nullptr, std::size_t{1} << 30, 0);
      if (n < 0 && (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP)) {
        kernel_copy = false;  // a file system or kernel without it: through a buffer
        continue;
      }
    } else {
      char buffer[1 << 16];
      n = ::read(in.fd, buffer, sizeof buffer);
      if (n > 0) write(buffer, static_cast<std::size_t>(n));
    }
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) return;
    if (n < 0) fail("cannot write", errno);
  }
}

void AtomicFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot write", errno);
}

void AtomicFile::sync() {
  close();
  if (synced_ || temporary_.empty()) return;
  // By path: a writer given temporary() may have replaced the file there.
  const int fd = ::open(temporary_.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    fail("cannot write", error);
  }
  ::close(fd);
  synced_ = true;
}

void AtomicFile::commit() {
  sync();
  if (temporary_.empty()) {
    committed_ = true;
    return;
  }
  if (!rename_into_place(temporary_, target_, overwrite_)) {
    const int error = errno;
    if (error == EEXIST) throw OutputError(target_.string() + ": appeared while it was written; use --overwrite to replace it");
    throw OutputError(target_.string() + ": cannot replace it with " + temporary_.string() + ": " + std::strerror(error), error);
  }
  committed_ = true;
  forget_temporary(slot_);
  slot_ = -1;
  sync_folder(folder_of(target_));
}

}  // namespace pcrf::io
