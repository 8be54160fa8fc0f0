// The journal of a result cube (see cube_journal.hpp): records framed by io::LogWriter, their
// payloads encoded and checked here against the cube's layout.
#include "pcrf/cube/cube_journal.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <memory>
#include <string_view>

#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/record_log.hpp"

namespace pcrf::cube {
namespace {

constexpr auto kHeader = kJournalHeader, kCases = kJournalCases, kNotes = kJournalNotes, kHistory = kJournalHistory,
               kCommit = kJournalCommit, kSealed = kJournalSealed;
constexpr std::size_t kHeaderBytes = 8 + 8 + 4;
constexpr std::size_t kCasesHeadBytes = 8 + 4;  // chunk, n (of a record of cases or of a sealed chunk)
enum AttributeType : std::uint8_t { kText = 0, kReal = 1, kInteger = 2 };

/// A payload that does not say what its kind must (caught and named by JournalReader).
struct Malformed {
  std::string problem;
};

void put(std::string& out, std::uint64_t value, std::size_t bytes) { io::append_le(out, value, bytes); }

void put_text(std::string& out, std::string_view text) {
  put(out, text.size(), 4);
  out += text;
}

void put_doubles(std::string& out, const double* values, std::size_t n) {
  if constexpr (std::endian::native == std::endian::little) {
    out.append(reinterpret_cast<const char*>(values), n * sizeof(double));
  } else {
    for (std::size_t i = 0; i < n; ++i) put(out, std::bit_cast<std::uint64_t>(values[i]), 8);
  }
}

/// Reads a payload front to back; every length is checked against the bytes left before use.
class Cursor {
 public:
  explicit Cursor(std::string_view bytes) : bytes_(bytes) {}
  std::size_t left() const { return bytes_.size() - at_; }
  const char* take(std::uint64_t n) {
    if (n > left()) throw Malformed{"ends " + std::to_string(n - left()) + " bytes early"};
    const char* p = bytes_.data() + at_;
    at_ += static_cast<std::size_t>(n);
    return p;
  }
  std::uint64_t number(std::size_t bytes) { return io::load_le(take(bytes), bytes); }
  std::string text() {
    const auto n = number(4);
    return std::string(take(n), static_cast<std::size_t>(n));
  }
  /// `n` doubles, `n` checked against the bytes left before anything is allocated.
  std::vector<double> doubles(std::uint64_t n) {
    if (n > left() / sizeof(double)) throw Malformed{"declares " + std::to_string(n) + " values it does not hold"};
    std::vector<double> values(static_cast<std::size_t>(n));
    if (n == 0) return values;  // a history of no rows: no bytes to copy (and no buffer to copy them to)
    const char* p = take(n * sizeof(double));
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(values.data(), p, values.size() * sizeof(double));
    } else {
      for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::bit_cast<double>(io::load_le(p + 8 * i, 8));
    }
    return values;
  }
  /// A count of items of at least `min_bytes` each, checked against the bytes left.
  std::size_t count(std::size_t bytes, std::size_t min_bytes) {
    const auto n = number(bytes);
    if (n > left() / min_bytes) throw Malformed{"declares " + std::to_string(n) + " items it does not hold"};
    return static_cast<std::size_t>(n);
  }
  void expect_end() const {
    if (left() != 0) throw Malformed{"has " + std::to_string(left()) + " bytes too many"};
  }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

std::string header_payload(std::int64_t id, std::int64_t cases, std::size_t metrics) {
  std::string out;
  put(out, static_cast<std::uint64_t>(id), 8);
  put(out, static_cast<std::uint64_t>(cases), 8);
  put(out, metrics, 4);
  return out;
}

/// How a metric's values are stored in a record of cases: one per case, or one for all (a
/// metric that is the same for every case of the record, e.g. 0 or NaN where frames never lift).
enum ColumnForm : std::uint8_t { kEach = 0, kSame = 1 };

/// The bytes of a record of `n` cases: at most (every column kEach), at least (every kSame).
std::uint64_t cases_payload_bytes(std::uint64_t n, std::size_t metrics, bool each) {
  const auto m = static_cast<std::uint64_t>(metrics);
  return kCasesHeadBytes + n * (4 + 1) + m * (1 + 8 * (each ? n : 1));
}

/// True when every value is the same, bit for bit (NaN payloads and -0 kept).
bool all_same(const std::vector<double>& values) {
  const auto first = values.empty() ? 0 : std::bit_cast<std::uint64_t>(values.front());
  return std::all_of(values.begin(), values.end(), [&](double v) { return std::bit_cast<std::uint64_t>(v) == first; });
}

void put_attribute(std::string& out, const Attribute& a) {
  put_text(out, a.name);
  if (const auto* text = std::get_if<std::string>(&a.value)) {
    put(out, kText, 1);
    put_text(out, *text);
  } else if (const auto* real = std::get_if<double>(&a.value)) {
    put(out, kReal, 1);
    put_doubles(out, real, 1);
  } else {
    put(out, kInteger, 1);
    put(out, static_cast<std::uint64_t>(std::get<std::int64_t>(a.value)), 8);
  }
}

Attribute take_attribute(Cursor& in) {
  Attribute a;
  a.name = in.text();
  switch (in.number(1)) {
    case kText: a.value = in.text(); break;
    case kReal: a.value = in.doubles(1)[0]; break;
    case kInteger: a.value = static_cast<std::int64_t>(in.number(8)); break;
    default: throw Malformed{"has an attribute of unknown type"};
  }
  return a;
}

std::string history_payload(const HistoryTable& table) {
  std::string out;
  put_text(out, table.name);
  put(out, table.attributes.size(), 4);
  for (const auto& a : table.attributes) put_attribute(out, a);
  put(out, table.columns.size(), 4);
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    put_text(out, table.columns[c].name);
    put_text(out, table.columns[c].units);
    put_text(out, table.columns[c].long_name);
    const auto& values = c < table.values.size() ? table.values[c] : std::vector<double>{};
    put(out, values.size(), 8);
    put_doubles(out, values.data(), values.size());
  }
  return out;
}

/// Text shown in a message: at most 40 characters, bytes that are not printable as '?'.
std::string shown(const std::string& text) {
  std::string out;
  for (const char c : text.substr(0, 40)) out += c >= 0x20 && c < 0x7f ? c : '?';
  return "\"" + out + (text.size() > 40 ? "…" : "") + "\"";
}

/// A history as the writer can store it: checked here, so that a journal that cannot be
/// folded is found when it is read (--resume sets it aside), not at every fold.
HistoryTable take_history(Cursor& in) {
  HistoryTable table;
  table.name = in.text();
  if (!valid_group_name(table.name)) throw Malformed{"has a history named " + shown(table.name) + ", not a group name"};
  const std::size_t attributes = in.count(4, 4 + 1);
  for (std::size_t a = 0; a < attributes; ++a) {
    table.attributes.push_back(take_attribute(in));
    if (table.attributes.back().name.empty() || table.attributes.back().name.find('\0') != std::string::npos)
      throw Malformed{"has a history attribute without a name"};
  }
  const std::size_t columns = in.count(4, 3 * 4 + 8);
  if (columns == 0) throw Malformed{"has a history of no column"};
  for (std::size_t c = 0; c < columns; ++c) {
    MetricVariable column;
    column.name = in.text();
    column.units = in.text();
    column.long_name = in.text();
    if (!valid_group_name(column.name)) throw Malformed{"has a history column named " + shown(column.name) + ", not a variable name"};
    for (const auto& other : table.columns)
      if (other.name == column.name) throw Malformed{"has the history column " + shown(column.name) + " twice"};
    table.columns.push_back(std::move(column));
    table.values.push_back(in.doubles(in.number(8)));
    if (table.values.back().size() != table.values.front().size())
      throw Malformed{"has history columns of different lengths"};
  }
  in.expect_end();
  return table;
}

constexpr std::size_t kPieceHeadBytes = 4 + 8 + 8;  // coordinate, piece, size

/// Most bytes a sealed record of a chunk of `count` cases (`padded` values stored) may hold,
/// with at most `coordinates` coordinate pieces of at most `piece_bound` bytes each.
std::uint64_t sealed_payload_bound(std::uint64_t count, std::size_t metrics, std::size_t padded, std::size_t coordinates,
                                   std::size_t piece_bound) {
  return kCasesHeadBytes + count + 4 + metrics * (8 + filtered_bound(padded, sizeof(double))) + 8 + filtered_bound(padded, 1) +
         4 + coordinates * (kPieceHeadBytes + piece_bound);
}

using PieceVisitor = std::function<void(std::size_t, std::size_t, const char*, std::size_t)>;

/// The variables of a sealed record, after its statuses: their number checked against the
/// cube's metrics (and the status) and each size against its bound; `variable` is given each
/// one's bytes, in order. Then, in a record of this version (an earlier one's ends there), the
/// coordinate pieces its unit carries (SealedChunk::coordinates): their number, at most the
/// cube's coordinates, and each one's coordinate (one of the cube's), piece and size (at most
/// sealed_piece_size_bound), given to `piece` (may be empty). The record must end there.
void take_sealed_variables(Cursor& in, std::size_t metrics, std::size_t coordinates, const ChunkGrid& grid,
                           const std::function<void(std::size_t, const char*, std::size_t)>& variable,
                           const PieceVisitor& piece = {}) {
  if (in.number(4) != metrics + 1) throw Malformed{"seals another number of variables than the cube has"};
  const std::size_t padded = padded_elements(grid);
  for (std::size_t v = 0; v <= metrics; ++v) {
    const auto size = in.number(8);
    if (size == 0 || size > filtered_bound(padded, v < metrics ? sizeof(double) : 1))
      throw Malformed{"seals a variable of a wrong size"};
    variable(v, in.take(size), static_cast<std::size_t>(size));
  }
  if (in.left() == 0) return;  // an earlier version's record: no coordinate pieces
  const auto pieces = in.number(4);
  if (pieces > coordinates) throw Malformed{"carries more coordinate pieces than the cube has coordinates"};
  for (std::uint64_t k = 0; k < pieces; ++k) {
    const auto coordinate = in.number(4), number = in.number(8), size = in.number(8);
    if (coordinate >= coordinates) throw Malformed{"carries a piece of no coordinate of the cube"};
    if (size == 0 || size > sealed_piece_size_bound(grid)) throw Malformed{"carries a coordinate piece of a wrong size"};
    const char* bytes = in.take(size);
    if (piece) piece(static_cast<std::size_t>(coordinate), static_cast<std::size_t>(number), bytes, static_cast<std::size_t>(size));
  }
  in.expect_end();
}

}  // namespace

std::filesystem::path journal_path(const std::filesystem::path& cube) { return cube.string() + ".journal"; }

std::int64_t journal_id_of(const CubeLayout& layout) {
  for (const auto& a : layout.attributes)
    if (a.name == kJournalIdName)
      if (const auto* id = std::get_if<std::int64_t>(&a.value)) return *id;
  return 0;
}

// ---- reading ----

JournalReader::JournalReader(std::filesystem::path file, const CubeLayout& layout, bool verify_checksums)
    : file_(std::move(file)), metrics_(layout.metrics.size()), coordinates_(layout.coordinates.size()),
      cases_(layout.case_count()), grid_(layout_grid(layout)) {
  for (const auto& c : layout.coordinates) {
    const auto d = layout.find_dimension(c.dimension);
    piece_values_.push_back(d ? coordinate_chunk_values(grid_, *d) : 0);
  }
  for (const auto& flag : layout.status_flags)
    if (flag.value != kStatusNotRun) statuses_.push_back(flag.value);
  try {
    log_ = std::make_unique<io::LogReader>(
        file_, verify_checksums ? io::LogReader::Checksums::kVerify : io::LogReader::Checksums::kFramesOnly);
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
}

JournalReader::JournalReader(const std::filesystem::path& cube, const CubeLayout& layout, std::int64_t id)
    : JournalReader(journal_path(cube), layout) {
  const auto& records = log_->records();
  if (id == 0 || records.empty() || records.front().kind != kHeader || records.front().size != kHeaderBytes) return;
  const std::string header = payload(0);
  if (static_cast<std::int64_t>(io::load_le(header.data(), 8)) != id) return;  // stale: another fold's
  if (static_cast<std::int64_t>(io::load_le(header.data() + 8, 8)) != cases_ || io::load_le(header.data() + 16, 4) != metrics_)
    fail(0, "carries this cube's id but another shape (a forged or foreign journal)");
  index(false);
}

JournalReader::JournalReader(const std::filesystem::path& part, const CubeLayout& layout, const std::string& part_header,
                             bool verify_checksums)
    : JournalReader(part, layout, verify_checksums) {
  const auto& records = log_->records();
  if (!log_->exists() || log_->file_bytes() == 0) return;  // nothing, or a kill as it was created
  if (!log_->is_log()) {
    foreign_ = true;
    return;
  }
  if (records.empty()) return;  // its header torn: it holds nothing
  if (records.front().kind != kPartHeader || records.front().size != part_header.size() || payload(0) != part_header) {
    foreign_ = true;
    return;
  }
  index(true);
}

/// The records of a current journal or part, up to its last commit, checked against the cube.
void JournalReader::index(bool part) {
  current_ = true;
  part_ = part;
  kept_ = 1;  // the header is committed alone
  index_from(1);
}

/// index() of the records from `first` on (those before are indexed already, up to a commit).
void JournalReader::index_from(std::size_t first) {
  const auto& records = log_->records();
  for (std::size_t r = first; r < records.size(); ++r)
    if (records[r].kind == kCommit) kept_ = r + 1;
  valid_bytes_ = records[kept_ - 1].end();
  dropped_bytes_ = log_->file_bytes() - valid_bytes_;
  dropped_records_ = records.size() - kept_;
  damaged_ = log_->valid_bytes() < log_->file_bytes();
  dropped_results_ = 0;
  for (std::size_t r = kept_; r < records.size(); ++r)  // what the dropped records held
    if ((records[r].kind == kCases || records[r].kind == kSealed) && records[r].size >= kCasesHeadBytes)
      dropped_results_ += static_cast<std::int64_t>(
          io::load_le(payload_head(records[r]).data() + 8, 4));
  for (std::size_t r = first; r < kept_; ++r) {
    const auto& record = records[r];
    if (record.kind == kNotes || record.kind == kCommit) continue;
    if (part_ && record.kind != kSealed)
      fail(r, "is of kind " + std::to_string(record.kind) + ", which a part does not hold (sealed chunks, their notes, commits)");
    if (record.kind == kHistory) continue;
    if (record.kind != kCases && record.kind != kSealed)
      fail(r, "is of an unknown kind " + std::to_string(record.kind) + " (another version's journal?)");
    if (record.size < kCasesHeadBytes) fail(r, "is too short for cases");
    const std::string head = payload_head(record);
    const auto chunk = io::load_le(head.data(), 8), n = io::load_le(head.data() + 8, 4);
    if (chunk >= grid_.chunk_count())
      fail(r, "names chunk " + std::to_string(chunk) + " of a cube of " + std::to_string(grid_.chunk_count()));
    if (record.kind == kSealed) {
      const auto count = static_cast<std::uint64_t>(grid_.range(static_cast<std::size_t>(chunk)).count);
      if (n != count) fail(r, "seals " + std::to_string(n) + " cases of a chunk of " + std::to_string(count));
      if (record.size > sealed_payload_bound(count, metrics_, padded_elements(grid_), coordinates_, sealed_piece_size_bound(grid_)))
        fail(r, "holds " + std::to_string(record.size) + " bytes, more than a sealed chunk can");
      sealed_[static_cast<std::size_t>(chunk)].push_back(r);
      sealed_record_chunk_.resize(records.size(), kNoChunk);
      sealed_record_chunk_[r] = static_cast<std::size_t>(chunk);
      results_ += static_cast<std::int64_t>(n);
      continue;
    }
    if (n > static_cast<std::uint64_t>(grid_.range(static_cast<std::size_t>(chunk)).count) ||
        record.size > cases_payload_bytes(n, metrics_, true) || record.size < cases_payload_bytes(n, metrics_, false))
      fail(r, "holds " + std::to_string(record.size) + " bytes, not the " + std::to_string(n) + " cases it declares");
    chunks_[static_cast<std::size_t>(chunk)].push_back(r);
    results_ += static_cast<std::int64_t>(n);
  }
}

JournalReader::~JournalReader() = default;

void JournalReader::release_file() { log_->release(); }

void JournalReader::extend() {
  if (!current_ || !part_) return;
  const std::size_t first = kept_;
  try {
    log_->extend();
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
  index_from(first);
}

void JournalReader::reopen_file() {
  try {
    log_->reopen();
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
}

std::string JournalReader::payload_head(const io::LogRecord& record) const {
  try {
    return log_->payload({record.kind, record.offset, kCasesHeadBytes});
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
}

void JournalReader::fail(std::size_t record, const std::string& problem) const {
  const auto offset = record < log_->records().size() ? log_->records()[record].offset : 0;
  throw JournalDamage(file_.string() + ": record " + std::to_string(record) + " (at byte " + std::to_string(offset) + ") " +
                      problem);
}

void JournalReader::check_all() const {
  for_each_cases([](const JournalCases&) {});
  // A sealed chunk is folded by a raw write: what it holds must inflate to the chunk, and its
  // status variable say what its statuses say, before it may reach the cube.
  const std::size_t padded = padded_elements(grid_);
  for (const auto& [chunk, records] : sealed_)
    for (const std::size_t r : records) {
      const SealedChunk c = sealed(r);
      const std::string what = file_.string() + ": record " + std::to_string(r);
      try {
        for (std::size_t m = 0; m < metrics_; ++m) (void)unfilter(c.filtered[m], padded, sizeof(double), what);
        const std::vector<char> codes = unfilter(c.filtered[metrics_], padded, 1, what);
        if (std::memcmp(codes.data(), c.status.data(), c.status.size()) != 0)
          fail(r, "seals statuses that are not its status variable's");
        // Its coordinate pieces inflate to whole float64 chunks of at most a chunk's values
        // (the writer takes one only where it is the unit's piece of a coordinate stored so).
        for (const auto& piece : c.coordinates) {
          const std::size_t values = piece_values_[piece.coordinate];  // its index was checked
          if (values == 0) fail(r, "carries a coordinate piece that is no chunk of a coordinate");
          (void)unfilter(piece.filtered, values, sizeof(double), what);
        }
      } catch (const JournalDamage&) {
        throw;
      } catch (const CubeError&) {
        fail(r, "holds a sealed chunk that does not inflate to its chunk");
      }
    }
  (void)notes();
  if (part_)  // a part's notes follow their chunk's sealed record (a journal's follow all its chunks)
    for (const auto& [chunk, records] : sealed_)
      for (const std::size_t r : records) (void)notes_after(r);
  for_each_history([](HistoryTable&&) {});
}

std::string JournalReader::payload(std::size_t record) const {
  try {
    return log_->payload(log_->records().at(record));
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
}

JournalCases JournalReader::cases(std::size_t record) const {
  const std::string bytes = payload(record);  // its size was checked against its count
  Cursor in(bytes);
  JournalCases c;
  try {
    c.chunk = static_cast<std::size_t>(in.number(8));
    const auto n = static_cast<std::size_t>(in.number(4));
    const auto count = static_cast<std::uint64_t>(grid_.range(c.chunk).count);
    c.offsets.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      c.offsets[j] = static_cast<std::uint32_t>(in.number(4));
      if (c.offsets[j] >= count || (j > 0 && c.offsets[j] <= c.offsets[j - 1]))
        throw Malformed{"has case offsets out of order or outside its chunk"};
    }
    const auto* status = reinterpret_cast<const std::int8_t*>(in.take(n));
    c.status.assign(status, status + n);
    check_statuses(record, c.status.data(), n);
    c.values.reserve(n * metrics_);  // bounded by the chunk's size, checked above
    for (std::size_t m = 0; m < metrics_; ++m) {
      const auto form = in.number(1);
      if (form != kEach && form != kSame) throw Malformed{"has a column of unknown form"};
      const auto column = in.doubles(form == kEach ? n : 1);
      if (form == kEach) c.values.insert(c.values.end(), column.begin(), column.end());
      else c.values.insert(c.values.end(), n, column.front());
    }
    in.expect_end();
  } catch (const Malformed& m) {
    fail(record, m.problem);
  }
  return c;
}

SealedChunk JournalReader::sealed(std::size_t record) const {
  const std::string bytes = payload(record);  // its size was checked against its bound
  Cursor in(bytes);
  SealedChunk c;
  try {
    c.chunk = static_cast<std::size_t>(in.number(8));
    const auto n = static_cast<std::size_t>(in.number(4));  // the chunk's count, checked
    const auto* status = reinterpret_cast<const std::int8_t*>(in.take(n));
    c.status.assign(status, status + n);
    check_statuses(record, c.status.data(), n, true);
    take_sealed_variables(
        in, metrics_, coordinates_, grid_,
        [&c](std::size_t, const char* p, std::size_t size) { c.filtered.emplace_back(p, p + size); },
        [&c](std::size_t coordinate, std::size_t piece, const char* p, std::size_t size) {
          c.coordinates.push_back({coordinate, piece, std::vector<char>(p, p + size)});
        });
  } catch (const Malformed& m) {
    fail(record, m.problem);
  }
  return c;
}

/// Only the statuses the cube's flags name reach it (never 99 or -128); not_run only in a
/// sealed chunk (`sealed`), whose cases a worker chose not to run (an IDA curve's points past
/// its last run), never in a record of cases.
void JournalReader::check_statuses(std::size_t record, const std::int8_t* status, std::size_t n, bool sealed) const {
  if (statuses_.empty()) return;
  bool allowed[256] = {};
  for (const std::int8_t s : statuses_) allowed[static_cast<std::uint8_t>(s)] = true;
  if (sealed) allowed[static_cast<std::uint8_t>(kStatusNotRun)] = true;
  for (std::size_t k = 0; k < n; ++k)
    if (!allowed[static_cast<std::uint8_t>(status[k])])
      fail(record, "has the status code " + std::to_string(status[k]) + ", which the cube's flags do not name");
}

/// True when a case may have `code` in this cube (check_statuses' rule).
bool JournalReader::names(std::int8_t code) const {
  return statuses_.empty() || std::find(statuses_.begin(), statuses_.end(), code) != statuses_.end();
}

void JournalReader::with_sealed(std::size_t record, const std::function<void(const SealedStatuses&)>& statuses,
                                const std::function<void(std::size_t, const char*, std::size_t)>& variable,
                                const PieceVisitor& piece) const {
  const auto& r = log_->records().at(record);
  const auto bytes = std::make_unique_for_overwrite<char[]>(static_cast<std::size_t>(r.size));  // its size was checked
  try {
    log_->read_payload(r, bytes.get());
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
  Cursor in(std::string_view(bytes.get(), static_cast<std::size_t>(r.size)));
  std::vector<std::pair<const char*, std::size_t>> variables;
  struct Piece {
    std::size_t coordinate, number;
    const char* bytes;
    std::size_t size;
  };
  std::vector<Piece> pieces;
  SealedStatuses status;
  try {
    (void)in.number(8);                                     // the chunk, checked when indexed
    const auto n = static_cast<std::size_t>(in.number(4));  // its count, likewise
    const auto* head = reinterpret_cast<const std::int8_t*>(in.take(n));
    variables.reserve(metrics_ + 1);
    take_sealed_variables(
        in, metrics_, coordinates_, grid_,
        [&variables](std::size_t, const char* p, std::size_t size) { variables.emplace_back(p, size); },
        [&pieces](std::size_t coordinate, std::size_t number, const char* p, std::size_t size) {
          pieces.push_back({coordinate, number, p, size});
        });
    // A whole chunk of one code: its status variable is that chunk's one stream (a chunk at
    // the cube's edge, padded with not_run, never is), recognised by its bytes.
    if (n > 0 && head[0] != kStatusNotRun && names(head[0])) {
      const std::vector<char>& alike = uniform_status_stream(padded_elements(grid_), head[0]);
      const auto& [p, size] = variables.back();
      status.alike = size == alike.size() && std::memcmp(p, alike.data(), size) == 0;
      status.code = head[0];
    }
    if (!status.alike) {
      check_statuses(record, head, n, true);
      status.each = std::span<const std::int8_t>(head, n);
    }
  } catch (const Malformed& m) {
    fail(record, m.problem);
  }
  statuses(status);
  for (std::size_t v = 0; v < variables.size(); ++v) variable(v, variables[v].first, variables[v].second);
  if (piece)
    for (const Piece& p : pieces) piece(p.coordinate, p.number, p.bytes, p.size);
}

std::vector<std::int8_t> JournalReader::sealed_status(std::size_t record) const {
  const auto& r = log_->records().at(record);
  const auto n = static_cast<std::uint64_t>(grid_.range(sealed_chunk_of(record)).count);  // checked when indexed
  std::string head;
  try {
    head = log_->payload({r.kind, r.offset, kCasesHeadBytes + n});
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
  std::vector<std::int8_t> status(reinterpret_cast<const std::int8_t*>(head.data() + kCasesHeadBytes),
                                  reinterpret_cast<const std::int8_t*>(head.data() + head.size()));
  check_statuses(record, status.data(), status.size(), true);
  return status;
}

std::size_t JournalReader::sealed_chunk_of(std::size_t record) const {
  if (record >= sealed_record_chunk_.size() || sealed_record_chunk_[record] == kNoChunk) fail(record, "is not a sealed chunk");
  return sealed_record_chunk_[record];
}

std::vector<std::pair<std::int64_t, std::string>> JournalReader::notes_after(std::size_t sealed_record) const {
  const std::size_t next = sealed_record + 1;
  if (!current_ || !part_ || next >= kept_ || log_->records()[next].kind != kNotes) return {};
  auto notes = notes_of(next);
  const auto range = grid_.range(sealed_chunk_of(sealed_record));
  for (const auto& [index, text] : notes)
    if (index < range.first || index >= range.first + range.count)
      fail(next, "has a note of case " + std::to_string(index) + ", outside the chunk sealed before it");
  return notes;
}

void JournalReader::for_each_cases(const std::function<void(const JournalCases&)>& visit) const {
  if (!current_) return;
  const auto& records = log_->records();
  for (std::size_t r = 1; r < kept_; ++r)
    if (records[r].kind == kCases) visit(cases(r));
}

std::vector<std::pair<std::int64_t, std::string>> JournalReader::notes() const {
  std::vector<std::pair<std::int64_t, std::string>> all;
  if (!current_) return all;
  const auto& records = log_->records();
  for (std::size_t r = 1; r < kept_; ++r) {
    if (records[r].kind != kNotes) continue;
    auto some = notes_of(r);
    all.insert(all.end(), std::make_move_iterator(some.begin()), std::make_move_iterator(some.end()));
  }
  return all;
}

std::vector<std::pair<std::int64_t, std::string>> JournalReader::notes_of(std::size_t r) const {
  std::vector<std::pair<std::int64_t, std::string>> all;
  const std::string bytes = payload(r);
  Cursor in(bytes);
  try {
    const std::size_t n = in.count(4, 8 + 4);
    for (std::size_t k = 0; k < n; ++k) {
      const auto index = static_cast<std::int64_t>(in.number(8));
      if (index < 0 || index >= cases_) fail(r, "has a note of case " + std::to_string(index) + ", outside the cube");
      all.emplace_back(index, in.text());
    }
    in.expect_end();
  } catch (const Malformed& m) {
    fail(r, m.problem);
  }
  return all;
}

void JournalReader::for_each_history(const std::function<void(HistoryTable&&)>& visit) const {
  if (!current_) return;
  const auto& records = log_->records();
  for (std::size_t r = 1; r < kept_; ++r) {
    if (records[r].kind != kHistory) continue;
    const std::string bytes = payload(r);
    Cursor in(bytes);
    HistoryTable table;
    try {
      table = take_history(in);
    } catch (const Malformed& m) {
      fail(r, m.problem);
    }
    visit(std::move(table));
  }
}

// ---- writing ----

JournalWriter::JournalWriter(const std::filesystem::path& cube, const CubeLayout& layout, std::int64_t id,
                             std::uint64_t keep_bytes)
    : file_(journal_path(cube)), metrics_(layout.metrics.size()) {
  guarded([&] {
    log_ = std::make_unique<io::LogWriter>(file_, keep_bytes);
    if (keep_bytes > 0) return;
    log_->add(kHeader, header_payload(id, layout.case_count(), metrics_));
    log_->sync();
  });
}

JournalWriter::JournalWriter(const std::filesystem::path& part, std::size_t metrics, const std::string& part_header)
    : file_(part), metrics_(metrics) {
  guarded([&] {
    log_ = std::make_unique<io::LogWriter>(file_, 0);
    log_->add(kPartHeader, part_header);
    log_->sync();
  });
}

JournalWriter::~JournalWriter() = default;

template <class Action>
void JournalWriter::guarded(Action action) {
  try {
    action();
  } catch (const io::OutputError& e) {
    throw CubeError(e.what(), CubeError::cause_of(e.os_error()));
  }
}

void JournalWriter::add_cases(std::size_t chunk, const std::vector<char>& stored, const std::vector<double>& values,
                              const std::int8_t* status) {
  const std::size_t count = stored.size();
  std::vector<std::uint32_t> offsets;
  for (std::size_t k = 0; k < count; ++k)
    if (stored[k]) offsets.push_back(static_cast<std::uint32_t>(k));
  payload_.clear();
  payload_.reserve(static_cast<std::size_t>(cases_payload_bytes(offsets.size(), metrics_, true)));
  put(payload_, chunk, 8);
  put(payload_, offsets.size(), 4);
  for (auto k : offsets) put(payload_, k, 4);
  for (auto k : offsets) payload_.push_back(static_cast<char>(status[k]));
  column_.resize(offsets.size());
  for (std::size_t m = 0; m < metrics_; ++m) {
    for (std::size_t j = 0; j < offsets.size(); ++j) column_[j] = values[m * count + offsets[j]];
    const bool same = !column_.empty() && all_same(column_);
    put(payload_, same ? kSame : kEach, 1);
    put_doubles(payload_, column_.data(), same ? 1 : column_.size());
  }
  guarded([&] { log_->add(kCases, payload_); });
}

void JournalWriter::add_sealed(const SealedChunk& sealed) { add_sealed(view_of(sealed)); }

void JournalWriter::add_sealed(const SealedChunkView& sealed) {
  // The record's own numbers go to payload_, each piece of the record a view of it or of the
  // sealed streams; payload_ is sized first, so that its views stay where they are.
  const std::size_t heads = 8 + 4 + 4 + 8 * sealed.filtered.size() + 4 + 20 * sealed.coordinates.size();
  payload_.clear();
  payload_.reserve(heads);
  std::vector<std::string_view> pieces;
  pieces.reserve(4 + 2 * sealed.filtered.size() + 2 * sealed.coordinates.size());
  auto number = [&](std::uint64_t value, std::size_t bytes) {  // joins the last piece when that is a number too
    const std::size_t at = payload_.size();
    put(payload_, value, bytes);
    const char* first = payload_.data() + at;
    if (!pieces.empty() && pieces.back().data() + pieces.back().size() == first)
      pieces.back() = {pieces.back().data(), pieces.back().size() + bytes};
    else
      pieces.emplace_back(first, bytes);
  };
  auto bytes = [&](const void* data, std::size_t size) {
    if (size > 0) pieces.emplace_back(static_cast<const char*>(data), size);
  };
  number(sealed.chunk, 8);
  number(sealed.status.size(), 4);
  bytes(sealed.status.data(), sealed.status.size());
  number(sealed.filtered.size(), 4);
  for (const auto f : sealed.filtered) {
    number(f.size(), 8);
    bytes(f.data(), f.size());
  }
  number(sealed.coordinates.size(), 4);  // this version's: the unit's coordinate pieces
  for (const auto& piece : sealed.coordinates) {
    number(piece.coordinate, 4);
    number(piece.piece, 8);
    number(piece.filtered.size(), 8);
    bytes(piece.filtered.data(), piece.filtered.size());
  }
  guarded([&] { log_->add_pieces(kSealed, pieces); });
}

void JournalWriter::add_notes(const std::vector<std::pair<std::int64_t, std::string>>& notes) {
  std::vector<std::pair<std::int64_t, std::string_view>> views;
  views.reserve(notes.size());
  for (const auto& [index, text] : notes) views.emplace_back(index, text);
  add_notes(views);
}

void JournalWriter::add_notes(std::span<const std::pair<std::int64_t, std::string_view>> notes) {
  if (notes.empty()) return;
  payload_.clear();
  put(payload_, notes.size(), 4);
  for (const auto& [index, text] : notes) {
    put(payload_, static_cast<std::uint64_t>(index), 8);
    put_text(payload_, text);
  }
  guarded([&] { log_->add(kNotes, payload_); });
}

void JournalWriter::add_history(const HistoryTable& table) {
  guarded([&] { log_->add(kHistory, history_payload(table)); });
}

void JournalWriter::commit() {
  guarded([&] { log_->add(kCommit, {}); });
}

void JournalWriter::sync() {
  guarded([&] { log_->sync(); });
}

std::uint64_t JournalWriter::bytes() const { return log_->size(); }

bool JournalWriter::in_place() const { return log_->in_place(); }

}  // namespace pcrf::cube
