// Append-only record files with a CRC per record (see record_log.hpp).
#include "pcrf/io/record_log.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <libdeflate.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <optional>

#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/machine_memory.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kMagic = "pcrf-log";
constexpr std::size_t kFrameHeadBytes = 12;  // kind (4) and size (8)
constexpr std::size_t kFrameTailBytes = 4;   // CRC-32
/// Piece in which a payload is read to check its CRC (never a buffer sized by the file).
constexpr std::size_t kScanPieceBytes = std::size_t{1} << 20;

/// The CRC-32 (ISO-HDLC, zlib's crc32) of `data` continuing `crc` (0 to start), by libdeflate,
/// which folds it with carry-less multiplies where the CPU has them: the same value as zlib's
/// (a test compares them), at a fraction of its instructions (a worker's part: 330 a
/// non-lifting case by zlib, callgrind).
std::uint32_t crc_of(std::uint32_t crc, const char* data, std::size_t size) {
  return size == 0 ? crc : libdeflate_crc32(crc, data, size);
}

fs::path folder_of(const fs::path& file) { return file.parent_path().empty() ? fs::path(".") : file.parent_path(); }

void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);  // best effort: a journal whose entry is lost is one that was never made
  ::close(fd);
}

}  // namespace

std::uint64_t load_le(const char* bytes, std::size_t count) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < count; ++i) value |= std::uint64_t{static_cast<unsigned char>(bytes[i])} << (8 * i);
  return value;
}

void append_le(std::string& out, std::uint64_t value, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

void store_le(char* out, std::uint64_t value, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<char>((value >> (8 * i)) & 0xff);
}

// ---- reading ----

LogReader::LogReader(const fs::path& file, Checksums checksums) : file_(file), verify_(checksums == Checksums::kVerify) {
  // A regular file, not followed, opened without blocking: a FIFO or a link there is refused.
  fd_ = open_regular_to_read(file_, false, true);
  if (fd_ < 0) return;
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    throw OutputError(file_.string() + ": cannot read: " + std::strerror(error), error);
  }
  device_ = st.st_dev;
  inode_ = st.st_ino;
  measure(static_cast<std::uint64_t>(st.st_size), 0);
  max_record_bytes_ = static_cast<std::uint64_t>(kUsableMemoryShare * machine_memory_bytes());
  scan();
}

LogReader::~LogReader() {
  if (fd_ >= 0) ::close(fd_);
}

void LogReader::release() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void LogReader::reopen() {
  if (fd_ >= 0 || !is_log_) return;
  const int fd = open_regular_to_read(file_, false, false);
  if (!size_if_scanned(fd)) {
    ::close(fd);
    fail_replaced();
  }
  fd_ = fd;
}

/// The size of the file open at `fd` when it is the one scanned (device and inode) and still
/// holds every valid record; nothing when it was replaced or cut since.
std::optional<std::uint64_t> LogReader::size_if_scanned(int fd) const {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_dev != device_ || st.st_ino != inode_ ||
      static_cast<std::uint64_t>(st.st_size) < valid_bytes_)
    return std::nullopt;
  return static_cast<std::uint64_t>(st.st_size);
}

void LogReader::fail_replaced() const {
  throw OutputError(file_.string() + ": was replaced or cut since it was read; pcrf reads a log it checked only", 0);
}

/// The open file's size, `file_bytes`, and where its data end at or after `from`: its first
/// hole there (SEEK_HOLE; the end of the file where there is none, or where the file system
/// cannot tell). An appended log has no hole: a record reaching into one was never written (a
/// sparse, forged file) and is not checksummed.
void LogReader::measure(std::uint64_t file_bytes, std::uint64_t from) {
  file_bytes_ = file_bytes;
  const off_t hole = ::lseek(fd_, static_cast<off_t>(from), SEEK_HOLE);
  data_bytes_ = hole >= 0 ? std::min<std::uint64_t>(static_cast<std::uint64_t>(hole), file_bytes_) : file_bytes_;
}

bool LogReader::read_at(std::uint64_t offset, char* data, std::size_t size) const {
  while (size > 0) {
    const ssize_t n = ::pread(fd_, data, size, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw OutputError(file_.string() + ": cannot read: " + std::strerror(errno), errno);
    if (n == 0) return false;  // the file shrank under us: what follows is not there
    data += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
  return true;
}

void LogReader::extend() {
  if (fd_ < 0 || !is_log_) return;
  const auto size = size_if_scanned(fd_);
  if (!size) fail_replaced();
  measure(*size, valid_bytes_);
  scan_from(valid_bytes_);
}

void LogReader::scan() {
  std::array<char, kMagic.size()> magic{};
  if (file_bytes_ < magic.size() || !read_at(0, magic.data(), magic.size())) return;
  if (std::string_view(magic.data(), magic.size()) != kMagic) return;
  is_log_ = true;
  valid_bytes_ = magic.size();
  scan_from(valid_bytes_);
}

/// The records from `at` (the end of the last valid one) on, up to the first that is not.
void LogReader::scan_from(std::uint64_t at) {
  std::vector<char> piece(verify_ ? kScanPieceBytes : 0);
  for (;;) {
    char head[kFrameHeadBytes];
    if (data_bytes_ < at || data_bytes_ - at < kFrameHeadBytes + kFrameTailBytes || !read_at(at, head, sizeof head)) return;
    const auto kind = static_cast<std::uint32_t>(load_le(head, 4));
    const std::uint64_t size = load_le(head + 4, 8);
    // Checked before use: a size the file's data cannot hold is a torn (or damaged) tail,
    // and so is one that memory cannot (payload() reads a record whole).
    if (at + kFrameHeadBytes + kFrameTailBytes > data_bytes_ || size > data_bytes_ - at - kFrameHeadBytes - kFrameTailBytes ||
        size > max_record_bytes_)
      return;
    if (!verify_) {  // the frame alone: its size was checked against the file's bytes above
      records_.push_back({kind, at + kFrameHeadBytes, size});
      at += kFrameHeadBytes + size + kFrameTailBytes;
      valid_bytes_ = at;
      continue;
    }
    std::uint32_t crc = crc_of(0, head, sizeof head);
    for (std::uint64_t done = 0; done < size;) {
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(size - done, piece.size()));
      if (!read_at(at + kFrameHeadBytes + done, piece.data(), n)) return;
      crc = crc_of(crc, piece.data(), n);
      done += n;
    }
    char tail[kFrameTailBytes];
    if (!read_at(at + kFrameHeadBytes + size, tail, sizeof tail)) return;
    if (load_le(tail, 4) != crc) return;
    records_.push_back({kind, at + kFrameHeadBytes, size});
    at += kFrameHeadBytes + size + kFrameTailBytes;
    valid_bytes_ = at;
  }
}

std::string LogReader::payload(const LogRecord& record) const {
  std::string bytes(static_cast<std::size_t>(record.size), '\0');
  if (!read_at(record.offset, bytes.data(), bytes.size()))
    throw OutputError(file_.string() + ": cannot read: the file was cut short while read");
  return bytes;
}

void LogReader::read_payload(const LogRecord& record, char* out) const {
  if (!read_at(record.offset, out, static_cast<std::size_t>(record.size)))
    throw OutputError(file_.string() + ": cannot read: the file was cut short while read");
}

// ---- writing ----

LogWriter::LogWriter(fs::path file, std::uint64_t keep_bytes) : file_(std::move(file)) {
  const bool fresh = keep_bytes == 0;
  if (fresh) {
    // A log that is there (stale) is removed, and the new one made exclusively: never
    // truncated through a link, nor another file's second name.
    remove_stale_sidecar(file_, "journal");
    fd_ = create_exclusive(file_, O_WRONLY);  // the umask decides the mode
  } else {
    fd_ = open_sidecar(file_, O_WRONLY, "journal");
    if (fd_ < 0) errno = ENOENT;
  }
  if (fd_ < 0) fail("cannot write", errno);
  try {
    struct stat st {};
    if (!fresh && (::fstat(fd_, &st) != 0 || static_cast<std::uint64_t>(st.st_size) < keep_bytes))
      fail("cannot continue", ESTALE);  // not the log read: it was cut or replaced meanwhile
    if (fresh) {
      write_at(0, kMagic);
      written_ = kMagic.size();
      sync();
      sync_folder(folder_of(file_));
      return;
    }
    if (::ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0) fail("cannot cut the torn tail of", errno);
    size_ = written_ = keep_bytes;
  } catch (...) {
    ::close(fd_);  // no destructor runs for an object that was never made
    throw;
  }
}

LogWriter::~LogWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void LogWriter::fail(const char* action, int error) const {
  throw OutputError(file_.string() + ": " + action + ": " + std::strerror(error), error);
}

void LogWriter::cut_back(int error) {
  (void)::ftruncate(fd_, static_cast<off_t>(size_));  // best effort: readers drop a torn tail anyway
  written_ = size_;
  fail("cannot write", error);
}

bool LogWriter::write_at(std::uint64_t offset, std::span<const std::string_view> pieces) {
  constexpr std::size_t kPiecesPerCall = 64;  // iovecs a pwritev takes here (IOV_MAX is 1024)
  std::size_t next = 0, done = 0;  // the first piece not written whole; its bytes written
  while (true) {
    while (next < pieces.size() && pieces[next].size() == done) {  // written whole (or empty)
      ++next;
      done = 0;
    }
    if (next == pieces.size()) return true;
    iovec vector[kPiecesPerCall];
    int used = 0;
    for (std::size_t k = next; k < pieces.size() && used < static_cast<int>(kPiecesPerCall); ++k, ++used) {
      const std::size_t skip = k == next ? done : 0;
      vector[used] = {const_cast<char*>(pieces[k].data() + skip), pieces[k].size() - skip};
    }
    const ssize_t n = ::pwritev(fd_, vector, used, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = EIO;
    if (n <= 0) return false;
    offset += static_cast<std::uint64_t>(n);
    for (auto left = static_cast<std::size_t>(n); left > 0;) {  // past what was written
      const std::size_t rest = pieces[next].size() - done;
      if (left < rest) {
        done += left;
        break;
      }
      left -= rest;
      ++next;
      done = 0;
    }
  }
}

bool LogWriter::write_at(std::uint64_t offset, std::string_view bytes) {
  return write_at(offset, std::span<const std::string_view>(&bytes, 1));
}

void LogWriter::add(std::uint32_t kind, std::string_view payload) { add_pieces(kind, std::span<const std::string_view>(&payload, 1)); }

void LogWriter::add_pieces(std::uint32_t kind, std::span<const std::string_view> payload) {
  std::uint64_t size = 0;
  for (const std::string_view piece : payload) size += piece.size();
  char head[kFrameHeadBytes], tail[kFrameTailBytes];
  store_le(head, kind, 4);
  store_le(head + 4, size, 8);
  std::uint32_t crc = crc_of(0, head, sizeof head);
  for (const std::string_view piece : payload) crc = crc_of(crc, piece.data(), piece.size());
  store_le(tail, crc, 4);
  std::vector<std::string_view> pieces;
  pieces.reserve(payload.size() + 2);
  pieces.emplace_back(head, sizeof head);
  for (const std::string_view piece : payload)
    if (!piece.empty()) pieces.push_back(piece);
  pieces.emplace_back(tail, sizeof tail);
  if (!write_at(written_, pieces)) cut_back(errno);
  written_ += kFrameHeadBytes + size + kFrameTailBytes;
}

void LogWriter::sync() {
  if (::fdatasync(fd_) != 0) cut_back(errno);
  size_ = written_;
}

bool LogWriter::in_place() const {
  struct stat ours {}, there {};
  return ::fstat(fd_, &ours) == 0 && ::stat(file_.c_str(), &there) == 0 && ours.st_dev == there.st_dev &&
         ours.st_ino == there.st_ino;
}

}  // namespace pcrf::io
