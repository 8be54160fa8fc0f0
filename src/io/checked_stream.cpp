// Checked writes to a file descriptor (see checked_stream.hpp).
#include "pcrf/io/checked_stream.hpp"

#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <iostream>

namespace pcrf::io {
namespace {

/// A reader that went away (`pcrf … | head`): end as Unix tools do, by SIGPIPE, quietly.
[[noreturn]] void end_by_closed_pipe() {
  std::signal(SIGPIPE, SIG_DFL);
  std::raise(SIGPIPE);
  std::_Exit(128 + SIGPIPE);  // SIGPIPE blocked: the same exit status
}

}  // namespace

void CheckedStreamBuf::drain() {
  // Sticky: a stream that swallowed the exception (operator<<(streambuf*) does) cannot
  // carry on as if the lost bytes had been written.
  if (error_ != 0) throw OutputError(target_ + ": cannot write: " + std::strerror(error_), error_);
  const char* data = pbase();
  std::size_t left = static_cast<std::size_t>(pptr() - pbase());
  while (left > 0) {
    const ssize_t n = ::write(fd_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      reset_area();
      error_ = error;
      if (error == EPIPE && fd_ == STDOUT_FILENO) end_by_closed_pipe();
      throw OutputError(target_ + ": cannot write: " + std::strerror(error), error);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  reset_area();
}

CheckedStreamBuf::int_type CheckedStreamBuf::overflow(int_type c) {
  drain();
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  *pptr() = traits_type::to_char_type(c);
  pbump(1);
  return c;
}

int CheckedStreamBuf::sync() {
  drain();
  return 0;
}

CheckedStdout::CheckedStdout() : buffer_(STDOUT_FILENO, "standard output") {
  std::cout.flush();
  previous_ = std::cout.rdbuf(&buffer_);
  std::cout.exceptions(std::ios::badbit);
  // std::cerr flushes std::cout before each write: a failed stdout would then throw from an
  // error message. Callers write stdout out (finish()) before their error lines instead.
  previous_tie_ = std::cerr.tie(nullptr);
}

CheckedStdout::~CheckedStdout() {
  std::cout.exceptions(std::ios::goodbit);
  try {
    buffer_.drain();  // normally done by finish(); on an exception's way out, best effort
  } catch (const OutputError&) {
  }
  std::cout.rdbuf(previous_);
  std::cerr.tie(previous_tie_);
}

void CheckedStdout::finish() {
  buffer_.drain();  // std::cout's buffer: no flush() through a stream an earlier failure made bad
}

}  // namespace pcrf::io
