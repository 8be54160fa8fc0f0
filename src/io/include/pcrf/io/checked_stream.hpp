/// \file checked_stream.hpp
/// \brief A stream buffer over a file descriptor whose every write is checked: a failed
/// write throws OutputError naming the target and the operating system's reason, and a
/// closed pipe on standard output ends the process quietly, as Unix tools do.
#pragma once

#include <array>
#include <stdexcept>
#include <streambuf>
#include <string>

namespace pcrf::io {

/// An output that cannot be written: one line naming the file and the reason.
class OutputError : public std::runtime_error {
 public:
  /// `os_error`: the errno behind it (0: a refusal of ours, e.g. the output is an input).
  OutputError(const std::string& what, int os_error = 0) : std::runtime_error(what), os_error_(os_error) {}
  int os_error() const { return os_error_; }

 private:
  int os_error_;
};

/// Buffered writes to `fd` (not owned). A stream using it must have exceptions(badbit) set
/// for the OutputError to reach its caller (CheckedStdout and OutputFile do).
class CheckedStreamBuf : public std::streambuf {
 public:
  /// `target`: what the messages call the destination (a path, "standard output").
  CheckedStreamBuf(int fd, std::string target) : fd_(fd), target_(std::move(target)) { reset_area(); }
  /// Writes what is buffered. \throws OutputError, also for every call after a failed write
  /// (on EPIPE to standard output: ends the process by SIGPIPE, quietly).
  void drain();

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  void reset_area() { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int fd_;
  std::string target_;
  int error_ = 0;  ///< the first failed write's errno
  std::array<char, 1 << 16> buffer_{};
};

/// Routes std::cout through a CheckedStreamBuf on descriptor 1 for its lifetime (and unties
/// std::cerr from it: call finish() before an error line to keep the two in order).
class CheckedStdout {
 public:
  CheckedStdout();
  ~CheckedStdout();
  CheckedStdout(const CheckedStdout&) = delete;
  CheckedStdout& operator=(const CheckedStdout&) = delete;
  /// Writes what is left. \throws OutputError naming standard output and the reason.
  void finish();

 private:
  CheckedStreamBuf buffer_;
  std::streambuf* previous_;
  std::ostream* previous_tie_;
};

}  // namespace pcrf::io
