// The statuses of a cube's cases, kept per chunk, per code and, for a chunk of mixed codes,
// per case (see status_book.hpp).
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
    : grid_(std::move(grid)),
      uniform_(grid_.chunk_count(), kStatusNotRun),
      mixed_(grid_.chunk_count()),
      chunk_done_(grid_.chunk_count(), 0) {
  first_.reserve(grid_.chunk_count() + 1);
  std::int64_t end = 0;  // of the last chunk
  for (std::size_t c = 0; c < grid_.chunk_count(); ++c) {
    const auto r = grid_.range(c);
    first_.push_back(r.first);
    end = r.first + r.count;
  }
  first_.push_back(end);
  if (end != static_cast<std::int64_t>(cases))
    throw std::invalid_argument("StatusBook: a grid of " + std::to_string(end) + " cases for " +
                                std::to_string(cases) + " cases");
  at(counts_, kStatusNotRun) = static_cast<std::int64_t>(cases);
}

std::int8_t StatusBook::operator[](std::size_t index) const {
  const std::size_t chunk = grid_.chunk_of(static_cast<std::int64_t>(index));
  const auto& own = mixed_[chunk];
  return own.empty() ? uniform_[chunk] : own[index - static_cast<std::size_t>(first_[chunk])];
}

std::span<const std::int8_t> StatusBook::chunk_codes(std::size_t chunk, std::vector<std::int8_t>& scratch) const {
  if (!mixed_[chunk].empty()) return mixed_[chunk];
  scratch.assign(static_cast<std::size_t>(count(chunk)), uniform_[chunk]);
  return scratch;
}

std::vector<std::int8_t> StatusBook::codes() const {
  std::vector<std::int8_t> all;
  all.reserve(cases());
  std::vector<std::int8_t> scratch;
  for (std::size_t c = 0; c < mixed_.size(); ++c) {
    const auto codes = chunk_codes(c, scratch);
    all.insert(all.end(), codes.begin(), codes.end());
  }
  return all;
}

std::int64_t StatusBook::done() const {
  return first_.back() - count_of(counts_, kStatusNotRun);
}

std::size_t StatusBook::mixed_chunks() const {
  return static_cast<std::size_t>(std::count_if(mixed_.begin(), mixed_.end(), [](const auto& own) { return !own.empty(); }));
}

void StatusBook::set(std::size_t chunk, std::int64_t index, std::int8_t code) {
  auto& own = mixed_[chunk];
  const auto cases = static_cast<std::size_t>(count(chunk));
  if (own.empty()) {
    if (uniform_[chunk] == code) return;
    own.assign(cases, uniform_[chunk]);  // the chunk's codes differ from now on
  }
  std::int8_t& old = own[static_cast<std::size_t>(index - first_[chunk])];
  if (old == code) return;
  --at(counts_, old);
  ++at(counts_, code);
  chunk_done_[chunk] += (code != kStatusNotRun) - (old != kStatusNotRun);
  old = code;
  // A chunk done case by case holds its byte a case until its last case, then its one code
  // if they all ended alike: one comparison a chunk.
  if (chunk_done_[chunk] == static_cast<std::int64_t>(cases) && all_alike(own)) {
    uniform_[chunk] = own.front();
    std::vector<std::int8_t>().swap(own);
  }
}

/// Takes the codes of a chunk's `cases` cases out of the counts, before new ones replace them.
void StatusBook::forget_chunk(std::size_t chunk, std::int64_t cases) {
  const auto& own = mixed_[chunk];
  if (own.empty()) {
    at(counts_, uniform_[chunk]) -= cases;
    return;
  }
  for (const std::int8_t code : own) --at(counts_, code);
}

void StatusBook::keep_mixed(std::size_t chunk, std::span<const std::int8_t> codes) {
  for (const std::int8_t code : codes) ++at(counts_, code);
  std::int64_t done = 0;
  for (const std::int8_t code : codes) done += code != kStatusNotRun;
  chunk_done_[chunk] = done;
  mixed_[chunk].assign(codes.begin(), codes.end());
}

void StatusBook::set_chunk(std::size_t chunk, std::span<const std::int8_t> codes) {
  const auto cases = count(chunk);
  if (codes.size() != static_cast<std::size_t>(cases))
    throw std::invalid_argument("StatusBook: " + std::to_string(codes.size()) + " codes for a chunk of " +
                                std::to_string(cases) + " cases");
  if (!codes.empty() && all_alike(codes)) return set_chunk_to(chunk, codes.front());
  forget_chunk(chunk, cases);
  keep_mixed(chunk, codes);
}

void StatusBook::set_chunk_to(std::size_t chunk, std::int8_t code) {
  const auto cases = count(chunk);
  forget_chunk(chunk, cases);
  at(counts_, code) += cases;
  chunk_done_[chunk] = code != kStatusNotRun ? cases : 0;
  uniform_[chunk] = code;
  std::vector<std::int8_t>().swap(mixed_[chunk]);
}

void StatusBook::assign(const std::vector<std::int8_t>& codes) {
  if (codes.size() != cases())
    throw std::invalid_argument("StatusBook: " + std::to_string(codes.size()) + " codes for " +
                                std::to_string(cases()) + " cases");
  for (std::size_t c = 0; c < mixed_.size(); ++c) {
    set_chunk(c, std::span<const std::int8_t>(codes).subspan(static_cast<std::size_t>(first_[c]), static_cast<std::size_t>(count(c))));
  }
}

}  // namespace pcrf::cube
