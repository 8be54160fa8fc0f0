// Files beside outputs and files read: never followed, never blocking (see file_kind.hpp).
#include "pcrf/io/file_kind.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>

#include "pcrf/io/checked_stream.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse_kind(const fs::path& file, mode_t mode, const std::string& what) {
  throw OutputError(file.string() + ": is " + kind_of(mode) + "; pcrf makes its " + what +
                    " itself and never writes through another file: remove it");
}

void check_sidecar_stat(const fs::path& file, const struct stat& st, const std::string& what) {
  if (!S_ISREG(st.st_mode)) refuse_kind(file, st.st_mode, what);
  if (st.st_nlink > 1)
    throw OutputError(file.string() + ": has " + std::to_string(st.st_nlink) + " names (a hard link to another file); pcrf makes its " +
                      what + " itself and never writes through another file: remove it");
}

/// One remembered temporary: state 0 free, 1 being filled or emptied, 2 set.
struct Slot {
  std::atomic<int> state{0};
  std::array<char, 4096> path{};
};
std::array<Slot, 32> slots;
static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");

extern "C" void remove_and_end(int number) {
  remove_temporaries();
  ::signal(number, SIG_DFL);
  ::raise(number);
}

}  // namespace

std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

int open_regular_to_read(const fs::path& file, bool follow, bool missing_ok) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | (follow ? 0 : O_NOFOLLOW));
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT && missing_ok) return -1;
    struct stat st {};
    if (!follow && error == ELOOP && ::lstat(file.c_str(), &st) == 0)
      throw OutputError(file.string() + ": is " + kind_of(st.st_mode) + ", not a regular file", error);
    throw OutputError(file.string() + ": cannot read: " + std::strerror(error), error);
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    throw OutputError(file.string() + ": cannot read: " + std::strerror(error), error);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    throw OutputError(file.string() + ": is " + kind_of(st.st_mode) + ", not a regular file");
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

int create_exclusive(const fs::path& file, int access) {
  return ::open(file.c_str(), access | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
}

int open_sidecar(const fs::path& file, int access, const std::string& what) {
  const int fd = ::open(file.c_str(), access | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT) return -1;
    struct stat st {};
    if (::lstat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) refuse_kind(file, st.st_mode, what);
    throw OutputError(file.string() + ": cannot open: " + std::strerror(error), error);
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    throw OutputError(file.string() + ": cannot open: " + std::strerror(error), error);
  }
  try {
    check_sidecar_stat(file, st, what);
  } catch (...) {
    ::close(fd);
    throw;
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

void check_sidecar(const fs::path& file, const std::string& what) {
  struct stat st {};
  if (::lstat(file.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    throw OutputError(file.string() + ": cannot look at it: " + std::strerror(errno), errno);
  }
  check_sidecar_stat(file, st, what);
}

void remove_stale_sidecar(const fs::path& file, const std::string& what) {
  check_sidecar(file, what);
  if (::unlink(file.c_str()) != 0 && errno != ENOENT)
    throw OutputError(file.string() + ": cannot remove it: " + std::strerror(errno), errno);
}

int remember_temporary(const fs::path& file) {
  const std::string& text = file.native();
  if (text.size() + 1 > slots[0].path.size()) return -1;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    int free = 0;
    if (!slots[i].state.compare_exchange_strong(free, 1)) continue;
    std::memcpy(slots[i].path.data(), text.c_str(), text.size() + 1);
    slots[i].state.store(2);
    return static_cast<int>(i);
  }
  return -1;
}

void forget_temporary(int slot) {
  if (slot >= 0 && static_cast<std::size_t>(slot) < slots.size()) slots[static_cast<std::size_t>(slot)].state.store(0);
}

void remove_temporaries() {
  for (auto& slot : slots)
    if (slot.state.load() == 2) ::unlink(slot.path.data());
}

void remove_temporaries_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_and_end;
  sigemptyset(&action.sa_mask);
  for (const int number : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&action.sa_mask, number);
  for (const int number : {SIGTERM, SIGINT, SIGHUP}) ::sigaction(number, &action, nullptr);
}

}  // namespace pcrf::io
