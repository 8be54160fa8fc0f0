/// \file output_file.hpp
/// \brief The one rule for every file a command writes (CSV tables, histories, merged
/// cubes, figures): an output never is one of the command's inputs, an existing file is
/// replaced only when asked, and the file appears complete or not at all.
///
/// The file is written by the one atomic-file rule (io::AtomicFile, which cube checkpoints
/// follow too): a temporary beside the target, synced and renamed over it by commit(), so a
/// failed or interrupted write leaves any old file intact. Files get the user's umask
/// (0666 & ~umask). An existing output that is not a regular file (/dev/null, a pipe) is
/// written in place.
#pragma once

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "pcrf/io/atomic_file.hpp"
#include "pcrf/io/checked_stream.hpp"

namespace pcrf::io {

/// True when `a` and `b` are the same file: the same device and inode once symbolic links
/// are followed (hard links included); for a path not there yet, the same canonical path.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// Refuses `output` when it is, or resolves to, one of `inputs` (whatever `overwrite` says),
/// when it is a folder, and when it exists and `overwrite` is false.
/// \throws OutputError naming the output and the problem.
void check_output(const std::filesystem::path& output, const std::vector<std::filesystem::path>& inputs, bool overwrite);

class OutputFile {
 public:
  /// check_output(), then a temporary beside `target`.
  /// \throws OutputError naming the target and the reason.
  OutputFile(std::filesystem::path target, const std::vector<std::filesystem::path>& inputs, bool overwrite);
  /// Removes the temporary unless commit() succeeded.
  ~OutputFile() = default;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// The stream to write the content to; every write is checked (OutputError).
  std::ostream& stream() { return stream_; }
  /// Where the content is written until commit(): for writers that take a path (a cube
  /// writer); they may replace the file there.
  const std::filesystem::path& temporary() const { return file_.temporary(); }
  const std::filesystem::path& target() const { return file_.target(); }

  /// Writes what is buffered, syncs, and renames the temporary over the target (refused if
  /// a file appeared there meanwhile and `overwrite` was false).
  /// \throws OutputError naming the target and the reason; the target is then untouched.
  void commit();

 private:
  AtomicFile file_;
  CheckedStreamBuf buffer_;
  std::ostream stream_;
};

}  // namespace pcrf::io
