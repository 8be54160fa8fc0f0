// One writer per file (see run_lock.hpp).
#include "pcrf/io/run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <string>

#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/file_kind.hpp"

namespace pcrf::io {
namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "?";
  return name;
}

/// What the lock file says about its holder (its one line), or "another process".
std::string read_holder(int fd) {
  char text[512] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string line = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "";
  if (const auto end = line.find('\n'); end != std::string::npos) line.resize(end);
  return line.empty() ? "another process" : line;
}

/// Takes the lock of the file open as `fd`; false (errno EWOULDBLOCK) when held.
bool try_lock(int fd) {
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0)
    if (errno != EINTR) return false;
  return true;
}

/// True when `fd` is still the file at `path` (a holder that ended removes it: a lock taken
/// on the removed file protects nothing).
bool is_current(int fd, const std::filesystem::path& path) {
  struct stat open_file {}, named {};
  return ::fstat(fd, &open_file) == 0 && ::stat(path.c_str(), &named) == 0 && open_file.st_dev == named.st_dev &&
         open_file.st_ino == named.st_ino;
}

}  // namespace

std::filesystem::path RunLock::lock_path(const std::filesystem::path& file) { return file.string() + ".lock"; }

RunLock::RunLock(const std::filesystem::path& file) : path_(lock_path(file)) {
  for (;;) {
    // Made exclusively, or a killed run's (a regular file of one name) reused: never a
    // link or another file's name, whose content the note below would replace.
    fd_ = create_exclusive(path_, O_RDWR);
    if (fd_ < 0 && errno == EEXIST) fd_ = open_sidecar(path_, O_RDWR, "lock file");
    if (fd_ < 0 && errno == ENOENT) continue;  // its holder removed it meanwhile: make it
    if (fd_ < 0) throw OutputError(file.string() + ": cannot make its lock " + path_.string() + ": " + std::strerror(errno), errno);
    if (!try_lock(fd_)) {
      const int error = errno;
      const std::string who = read_holder(fd_);
      ::close(fd_);
      if (error == EWOULDBLOCK)
        throw OutputError(file.string() + ": in use by another run (" + who + "); wait for it to end, or give another -o");
      throw OutputError(file.string() + ": cannot lock " + path_.string() + ": " + std::strerror(error), error);
    }
    if (is_current(fd_, path_)) break;
    ::close(fd_);  // locked the file its last holder was removing: take the new one
  }
  const std::string who = "pid " + std::to_string(::getpid()) + " on host " + host_name() + ", started " + utc_now() + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, who.data(), who.size(), 0) != static_cast<ssize_t>(who.size())) {
    // The lock holds without the note; a second run's message then says "another process".
  }
}

bool RunLock::held() const { return is_current(fd_, path_); }

RunLock::~RunLock() {
  ::unlink(path_.c_str());  // while still held: nobody can take the lock of a removed file
  ::close(fd_);
}

std::string RunLock::holder(const std::filesystem::path& file) {
  const std::filesystem::path path = lock_path(file);
  // Without following or blocking: a link or a FIFO there is no lock of a run.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return "";
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return "";
  }
  std::string who;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) who = read_holder(fd);
  ::close(fd);  // releases a lock taken just to look
  return who;
}

}  // namespace pcrf::io
