/// \file run_lock.hpp
/// \brief One writer per file: an exclusive advisory lock (flock) on `<file>.lock`, beside
/// the file, held for a run's whole length.
///
/// The lock file says who holds it (pid, host, start time), for the message a second run
/// gets. The kernel releases the lock when its holder dies, however it dies: a lock file left
/// by a killed run is stale and never blocks the next one (nothing to clean up by hand).
/// Shared file systems: on NFS (v4, or v3 with lockd) flock is carried to the server and
/// works across hosts; a client that crashes holds its lock until the server's lease ends
/// (NFSv4: about 90 s). File systems without locking (some FUSE and old NFS mounts) refuse
/// the lock: the run then stops with that reason rather than run unprotected.
///
/// The lock file is created exclusively (O_EXCL | O_NOFOLLOW); a killed holder's is reused
/// only when it is a regular file of one name. A symbolic link, a FIFO or a hard link at
/// `<file>.lock` is refused naming it (io/file_kind.hpp): the note would replace its content.
#pragma once

#include <filesystem>
#include <string>

namespace pcrf::io {

class RunLock {
 public:
  /// Takes the lock of `file` at once or not at all.
  /// \throws OutputError naming `file` and the holder, or the reason the lock cannot be taken.
  explicit RunLock(const std::filesystem::path& file);
  /// Releases the lock and removes the lock file.
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  /// False when the lock file was removed or replaced since the lock was taken: another run
  /// could then take a lock of its own on the same file.
  bool held() const;

  /// `<file>.lock`.
  static std::filesystem::path lock_path(const std::filesystem::path& file);
  /// Who holds the lock of `file` ("pid 12 on host a, started 2026-01-01T00:00:00Z"); empty
  /// when nobody does.
  static std::string holder(const std::filesystem::path& file);

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace pcrf::io
