/// \file atomic_file.hpp
/// \brief The one rule by which a file is replaced safely, for every output a command
/// writes (io::OutputFile) and every checkpoint of a result cube: the new content goes to a
/// temporary beside the target (so on the same file system), is synced to disk, and is
/// renamed over the target, whose folder is then synced. A write that fails, or a process
/// killed at any moment, leaves the old file whole (or no file), never part of the new one.
///
/// The temporary gets the user's mode (0666 & ~umask), as the shell's redirections do. It is
/// created exclusively (never through a link), and removed when the process is stopped by a
/// signal where the command installed io::remove_temporaries_on_signals. A target that is a
/// FIFO is opened without blocking: refused when no process reads it.
#pragma once

#include <cstddef>
#include <filesystem>

namespace pcrf::io {

class AtomicFile {
 public:
  /// How the temporary is named.
  enum class Temporary {
    /// ".NAME.XXXXXX", made exclusively: for outputs, which no lock keeps other commands off.
    /// A target that exists and is not a regular file (/dev/null, a pipe) is written in place.
    kUnique,
    /// "NAME.partial": for a target whose writer holds its lock (a cube), so that the
    /// temporary of a killed run is replaced by the next, not piled up. One that is there is
    /// removed and made anew exclusively (O_EXCL | O_NOFOLLOW) when it is a regular file of
    /// one name; anything else there (a symbolic link, a FIFO) is refused (io::file_kind.hpp).
    kPartial,
  };

  /// Opens the temporary. `overwrite`: commit() may replace an existing target.
  /// \throws OutputError naming the target and the reason.
  AtomicFile(std::filesystem::path target, bool overwrite, Temporary naming = Temporary::kUnique);
  /// Removes the temporary unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& target() const { return target_; }
  /// Where the content goes until commit(); empty when the target is written in place.
  const std::filesystem::path& temporary() const { return temporary_; }
  /// The open temporary (or target, in place); -1 after close().
  int fd() const { return fd_; }

  /// Writes all of `size` bytes at the descriptor's position. \throws OutputError.
  void write(const char* data, std::size_t size);
  /// Writes the whole content of `source` (copy_file_range: no copy through user space).
  /// \throws OutputError naming the target (a source that cannot be read: its own name).
  void copy_from(const std::filesystem::path& source);
  /// Closes the descriptor: for writers that take the temporary's path (HDF5); they may
  /// replace the file there. \throws OutputError.
  void close();
  /// close(), then flushes the temporary to disk, found by its path. \throws OutputError.
  void sync();
  /// sync() unless done, renames the temporary over the target (refused when a file
  /// appeared there meanwhile and `overwrite` is false), then syncs the folder.
  /// \throws OutputError naming the target and the reason; the target is then untouched.
  void commit();

 private:
  /// An OutputError for an OS failure: "TARGET: <action>[ TEMPORARY]: <reason of errno>".
  [[noreturn]] void fail(const char* action, int error) const;

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool overwrite_;
  bool name_temporary_;  ///< messages name the temporary (a .partial the user may see)
  int fd_ = -1;
  bool synced_ = false;
  bool committed_ = false;
  int slot_ = -1;  ///< io::remember_temporary's: removed on SIGTERM, SIGINT, SIGHUP
};

}  // namespace pcrf::io
