// Byte form of a ResultBatch: a flat little header, then per case its index, its status, its
// row and its note. Both ends run the same binary, so native byte order and sizes are fine.
#include "pcrf/parallel/result_batch.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace pcrf::parallel {
namespace {

class Writer {
 public:
  template <class T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void put_bytes(const char* data, std::size_t n) { bytes_.insert(bytes_.end(), data, data + n); }
  std::vector<char> take() { return std::move(bytes_); }

 private:
  std::vector<char> bytes_;
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes, std::size_t end) : bytes_(bytes), end_(end) {}
  template <class T>
  T get() {
    T value{};
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  const char* take(std::size_t n) {
    if (n > end_ - pos_) throw std::runtime_error("result message is truncated");
    const char* p = bytes_.data() + pos_;
    pos_ += n;
    return p;
  }
  bool at_end() const { return pos_ == end_; }
  std::size_t position() const { return pos_; }

 private:
  const std::vector<char>& bytes_;
  std::size_t end_;
  std::size_t pos_ = 0;
};

void put_results(Writer& w, const ResultBatch& batch, std::size_t row_width) {
  w.put(static_cast<std::uint64_t>(batch.size()));
  w.put(static_cast<std::uint64_t>(row_width));
  for (const auto& outcome : batch) {
    if (outcome.row.size() != row_width)
      throw std::invalid_argument("case " + std::to_string(outcome.case_index) + ": row has " +
                                  std::to_string(outcome.row.size()) + " values, expected " +
                                  std::to_string(row_width));
    w.put(outcome.case_index);
    w.put(outcome.status);
    w.put_bytes(reinterpret_cast<const char*>(outcome.row.data()), row_width * sizeof(double));
    w.put(static_cast<std::uint64_t>(outcome.note.size()));
    w.put_bytes(outcome.note.data(), outcome.note.size());
  }
}

ResultBatch get_results(Reader& r, std::size_t row_width) {
  const auto count = r.get<std::uint64_t>();
  const auto width = r.get<std::uint64_t>();
  if (width != row_width)
    throw std::runtime_error("result message has rows of " + std::to_string(width) +
                             " values, expected " + std::to_string(row_width));
  ResultBatch batch(count);
  for (auto& outcome : batch) {
    outcome.case_index = r.get<std::int64_t>();
    outcome.status = r.get<std::int8_t>();
    outcome.row.resize(row_width);
    std::memcpy(outcome.row.data(), r.take(row_width * sizeof(double)), row_width * sizeof(double));
    const auto note_size = r.get<std::uint64_t>();
    outcome.note.assign(r.take(note_size), note_size);
  }
  return batch;
}

}  // namespace

namespace {
/// This thread's rows given back, their values stale.
std::vector<std::vector<double>>& row_pool() {
  thread_local std::vector<std::vector<double>> pool;
  return pool;
}
}  // namespace

std::vector<double> pooled_row(std::size_t width, double fill) {
  auto& pool = row_pool();
  if (pool.empty()) return std::vector<double>(width, fill);
  std::vector<double> row = std::move(pool.back());
  pool.pop_back();
  row.assign(width, fill);
  return row;
}

void recycle_rows(std::span<CaseOutcome> outcomes) {
  auto& pool = row_pool();
  if (pool.capacity() < kPooledRows) pool.reserve(kPooledRows);
  for (CaseOutcome& outcome : outcomes) {
    if (pool.size() == kPooledRows) return;
    if (outcome.row.capacity() > 0) pool.push_back(std::move(outcome.row));
  }
}

std::vector<char> pack_results(const ResultBatch& batch, std::size_t row_width) {
  Writer w;
  put_results(w, batch, row_width);
  return w.take();
}

ResultBatch unpack_results(const std::vector<char>& bytes, std::size_t row_width) {
  Reader r(bytes, bytes.size());
  ResultBatch batch = get_results(r, row_width);
  if (!r.at_end()) throw std::runtime_error("result message has trailing bytes");
  return batch;
}

std::vector<char> pack_message(const ResultBatch& batch, const SealedUnits& sealed, std::size_t row_width) {
  Writer w;
  put_results(w, batch, row_width);
  w.put(static_cast<std::uint64_t>(sealed.size()));
  for (const auto& s : sealed) {
    w.put(s.unit);
    w.put(s.cases);
    w.put(static_cast<std::uint8_t>(s.kept ? 1 : 0));
    w.put(s.failed);
    w.put(static_cast<std::uint64_t>(s.bytes.size()));
    w.put_bytes(s.bytes.data(), s.bytes.size());
  }
  return w.take();
}

std::pair<ResultBatch, SealedUnits> unpack_message(const std::vector<char>& bytes, std::size_t row_width) {
  Reader r(bytes, bytes.size());
  ResultBatch batch = get_results(r, row_width);
  const auto count = r.get<std::uint64_t>();
  if (count > bytes.size()) throw std::runtime_error("result message counts more sealed units than it has bytes");
  SealedUnits sealed(count);
  for (auto& s : sealed) {
    s.unit = r.get<std::int64_t>();
    s.cases = r.get<std::int64_t>();
    s.kept = r.get<std::uint8_t>() != 0;
    s.failed = r.get<std::int64_t>();
    const auto size = r.get<std::uint64_t>();
    if (s.cases < 0) throw std::runtime_error("result message has a sealed unit of negative size");
    if (s.failed < 0 || s.failed > s.cases) throw std::runtime_error("result message has a sealed unit of more failures than cases");
    const char* data = r.take(size);
    s.bytes.assign(data, data + size);
  }
  if (!r.at_end()) throw std::runtime_error("result message has trailing bytes");
  return {std::move(batch), std::move(sealed)};
}

}  // namespace pcrf::parallel
