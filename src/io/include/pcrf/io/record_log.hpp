/// \file record_log.hpp
/// \brief An append-only file of records, each framed by its kind, its size and a CRC-32
/// (zlib's), so that a reader keeps every record a writer completed and drops a torn tail: a
/// process killed, a machine that lost power or a disk that filled in the middle of an append.
/// Knows nothing of what the records hold (the cube's journal, cube_journal.hpp, does).
///
/// File: the 8 bytes "pcrf-log", then records, each: kind (4 bytes), size (8 bytes), `size`
/// bytes of payload, CRC-32 of the kind, size and payload (4 bytes); integers little-endian.
///
/// The file is untrusted input: it is opened only when it is a regular file (not followed,
/// without blocking: a link or a FIFO there is an OutputError); a size is checked against the
/// bytes the file really has (up to its first hole: a sparse file declaring 64 GiB holds
/// none of them) and against a memory budget (kUsableMemoryShare of the machine's) before it
/// is used, a payload is read in bounded pieces to check its CRC, and the first record that
/// does not fit or does not match its CRC ends what is read (nothing after it is trusted).
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pcrf::io {

/// Appends `value` as `count` little-endian bytes (the log's integers, and its users').
void append_le(std::string& out, std::uint64_t value, std::size_t count);
/// Writes `value` as `count` little-endian bytes at `out`.
void store_le(char* out, std::uint64_t value, std::size_t count);
/// The `count` little-endian bytes at `bytes` as a number.
std::uint64_t load_le(const char* bytes, std::size_t count);

/// One complete, checksum-valid record of a log.
struct LogRecord {
  std::uint32_t kind = 0;
  std::uint64_t offset = 0;  ///< of the payload, in bytes from the start of the file
  std::uint64_t size = 0;    ///< of the payload [bytes]
  /// Where the record ends (after its CRC) [bytes from the start of the file].
  std::uint64_t end() const { return offset + size + 4; }
};

/// Reads a log: its valid records, then their payloads on demand.
class LogReader {
 public:
  /// How a scan checks the records' payloads.
  enum class Checksums {
    kVerify,  ///< every record's CRC-32 (an untrusted file: what a kill or damage left)
    /// Frames only (kinds, sizes against the file's bytes and the memory budget), not the
    /// CRCs: for a log its writer synced within this same run and that no kill can have torn
    /// since (a rank's part at the run's end, cube_part.hpp). Its content is checked by its reader.
    kFramesOnly,
  };
  /// Opens and scans `file`. A missing file reads as a log of no record.
  /// \throws OutputError naming the file when it exists but cannot be read.
  explicit LogReader(const std::filesystem::path& file, Checksums checksums = Checksums::kVerify);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  bool exists() const { return fd_ >= 0; }
  /// False when the file is missing, shorter than the magic or starts otherwise.
  bool is_log() const { return is_log_; }
  /// The complete, checksum-valid records, in file order, up to the first that is not.
  const std::vector<LogRecord>& records() const { return records_; }
  /// End of the last valid record [bytes] (of the magic when none; 0 when not a log).
  std::uint64_t valid_bytes() const { return valid_bytes_; }
  /// Size of the file [bytes]; more than valid_bytes() when a tail was dropped.
  std::uint64_t file_bytes() const { return file_bytes_; }
  /// A record's payload (its size was checked against the file when scanned).
  /// \throws OutputError naming the file when it cannot be read.
  std::string payload(const LogRecord& record) const;
  /// The same into `out`, which has room for record.size bytes (no string to fill first).
  void read_payload(const LogRecord& record, char* out) const;
  /// Closes the file, keeping what was scanned (a reader of many logs holds one open at a time).
  void release();
  /// Opens the released file again for payload(): the same file (device and inode) with at
  /// least the bytes scanned. \throws OutputError naming it when it is gone or was replaced.
  void reopen();
  /// Reads the records its writer completed since the last scan (a log another process is
  /// still appending to: a rank's part during the run, cube_part.hpp), from where that scan
  /// stopped, checked as the constructor checks them. The file must be open (reopen()) and
  /// the one scanned. \throws OutputError naming the file when it was replaced or cut since.
  void extend();

 private:
  void scan();
  void scan_from(std::uint64_t at);
  std::optional<std::uint64_t> size_if_scanned(int fd) const;
  [[noreturn]] void fail_replaced() const;
  void measure(std::uint64_t file_bytes, std::uint64_t from);
  bool read_at(std::uint64_t offset, char* data, std::size_t size) const;

  std::filesystem::path file_;
  int fd_ = -1;
  bool is_log_ = false;
  std::vector<LogRecord> records_;
  std::uint64_t valid_bytes_ = 0;
  std::uint64_t file_bytes_ = 0;
  std::uint64_t data_bytes_ = 0;       ///< up to the file's first hole (its real data)
  std::uint64_t max_record_bytes_ = 0;  ///< a memory budget: kUsableMemoryShare of the machine's
  bool verify_ = true;                  ///< Checksums::kVerify
  dev_t device_ = 0;                    ///< of the file scanned (reopen checks it is the same)
  ino_t inode_ = 0;
};

/// Appends records to a log. One writer per file (its owner's lock keeps others off).
class LogWriter {
 public:
  /// Opens `file` to append after its first `keep_bytes` bytes (a LogReader's valid_bytes(),
  /// so that a torn tail is cut off), or, with `keep_bytes` 0, creates it anew with the magic,
  /// synced with its folder: a regular file there (a stale log) is removed first and the new
  /// one created exclusively. Never through a link: a symbolic link, a FIFO or a file of
  /// several names there is refused (io/file_kind.hpp). \throws OutputError.
  LogWriter(std::filesystem::path file, std::uint64_t keep_bytes);
  ~LogWriter();
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;

  const std::filesystem::path& file() const { return file_; }
  /// Bytes of the log, records synced only.
  std::uint64_t size() const { return size_; }
  /// Writes a record at the end of the log (framed as it goes: no copy of the payload), not
  /// yet synced. On failure the file is cut back to its last synced size (best effort: a
  /// kill then leaves a torn tail, which readers drop). \throws OutputError naming the file.
  void add(std::uint32_t kind, std::string_view payload);
  /// The same with a payload of several pieces, one after another (written as they are, by one
  /// pwritev: a record assembled from buffers that are already there, without a copy).
  void add_pieces(std::uint32_t kind, std::span<const std::string_view> payload);
  /// Syncs what add() wrote to disk (fdatasync): the records are then committed.
  /// \throws OutputError naming the file.
  void sync();
  /// True while `file` names the file this writer appends to (not removed, not replaced).
  bool in_place() const;

 private:
  [[noreturn]] void fail(const char* action, int error) const;

  std::filesystem::path file_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  [[noreturn]] void cut_back(int error);
  /// pwrite() of all of `bytes` at `offset`; false (errno set) on failure.
  bool write_at(std::uint64_t offset, std::string_view bytes);
  /// The same for `pieces` one after another.
  bool write_at(std::uint64_t offset, std::span<const std::string_view> pieces);

  std::uint64_t written_ = 0;  ///< size after add(), before sync()
};

}  // namespace pcrf::io
