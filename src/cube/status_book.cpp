// The statuses of a cube's cases, kept per case, per code and per chunk (see status_book.hpp).
#include "pcrf/cube/status_book.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {
namespace {

std::int64_t& at(StatusCounts& counts, std::int8_t code) { return counts[static_cast<std::uint8_t>(code)]; }

/// True when every code is the first one (a comparison of the span with itself shifted by one).
bool all_alike(std::span<const std::int8_t> codes) {
  return codes.size() < 2 || std::memcmp(codes.data(), codes.data() + 1, codes.size() - 1) == 0;
}

}  // namespace

StatusCounts count_statuses(std::span<const std::int8_t> status) {
  StatusCounts counts{};
  for (const std::int8_t s : status) ++at(counts, s);
  return counts;
}

StatusBook::StatusBook(ChunkGrid grid, std::size_t cases)
    : grid_(std::move(grid)), codes_(cases, kStatusNotRun), chunk_done_(grid_.chunk_count(), 0) {
  at(counts_, kStatusNotRun) = static_cast<std::int64_t>(cases);
}

std::int64_t StatusBook::done() const {
  return static_cast<std::int64_t>(codes_.size()) - count_of(counts_, kStatusNotRun);
}

void StatusBook::set(std::size_t chunk, std::int64_t index, std::int8_t code) {
  std::int8_t& old = codes_[static_cast<std::size_t>(index)];
  if (old == code) return;
  --at(counts_, old);
  ++at(counts_, code);
  chunk_done_[chunk] += (code != kStatusNotRun) - (old != kStatusNotRun);
  old = code;
}

/// Takes the codes of a chunk's cases out of the counts, before new ones replace them.
void StatusBook::forget_chunk(std::size_t chunk, std::int64_t first, std::int64_t count) {
  if (chunk_done_[chunk] == 0) {  // all not run: no need to look at them
    at(counts_, kStatusNotRun) -= count;
    return;
  }
  for (std::int64_t k = 0; k < count; ++k) --at(counts_, codes_[static_cast<std::size_t>(first + k)]);
}

void StatusBook::set_chunk(std::size_t chunk, std::span<const std::int8_t> codes) {
  const auto r = grid_.range(chunk);
  if (codes.size() != static_cast<std::size_t>(r.count))
    throw std::invalid_argument("StatusBook: " + std::to_string(codes.size()) + " codes for a chunk of " +
                                std::to_string(r.count) + " cases");
  if (!codes.empty() && all_alike(codes)) return set_chunk_to(chunk, codes.front());
  forget_chunk(chunk, r.first, r.count);
  for (const std::int8_t code : codes) ++at(counts_, code);
  std::int64_t done = 0;
  for (const std::int8_t code : codes) done += code != kStatusNotRun;
  chunk_done_[chunk] = done;
  std::memcpy(codes_.data() + r.first, codes.data(), codes.size());
}

void StatusBook::set_chunk_to(std::size_t chunk, std::int8_t code) {
  const auto r = grid_.range(chunk);
  forget_chunk(chunk, r.first, r.count);
  at(counts_, code) += r.count;
  chunk_done_[chunk] = code != kStatusNotRun ? r.count : 0;
  std::memset(codes_.data() + r.first, code, static_cast<std::size_t>(r.count));
}

void StatusBook::assign(std::vector<std::int8_t> codes) {
  if (codes.size() != codes_.size())
    throw std::invalid_argument("StatusBook: " + std::to_string(codes.size()) + " codes for " +
                                std::to_string(codes_.size()) + " cases");
  codes_ = std::move(codes);
  counts_ = count_statuses(codes_);
  std::fill(chunk_done_.begin(), chunk_done_.end(), 0);
  for (std::size_t c = 0; c < chunk_done_.size(); ++c) {
    const auto r = grid_.range(c);
    for (std::int64_t k = 0; k < r.count; ++k) chunk_done_[c] += codes_[static_cast<std::size_t>(r.first + k)] != kStatusNotRun;
  }
}

}  // namespace pcrf::cube
