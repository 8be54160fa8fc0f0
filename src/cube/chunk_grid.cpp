// Chunk layout of a cube (see chunk_grid.hpp).
#include "pcrf/cube/chunk_grid.hpp"

#include <algorithm>
#include <stdexcept>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {

ChunkGrid::ChunkGrid(std::vector<std::size_t> shape, std::size_t target_cases)
    : shape_(std::move(shape)), chunk_(shape_.size(), 1) {
  if (shape_.empty()) throw std::invalid_argument("ChunkGrid: a cube needs a dimension");
  for (auto n : shape_)
    if (n == 0) throw std::invalid_argument("ChunkGrid: empty dimension");
  target_cases = std::max<std::size_t>(target_cases, 1);
  // Take whole dimensions from the fastest one while they fit, then part of the next.
  // When everything fits, split_ stays 0 and the single chunk is the whole cube.
  std::size_t cases = 1;
  for (std::size_t d = shape_.size(); d-- > 0;) {
    if (cases * shape_[d] > target_cases) {
      split_ = d;
      chunk_[d] = std::max<std::size_t>(1, target_cases / cases);
      break;
    }
    chunk_[d] = shape_[d];
    cases *= shape_[d];
  }
  // inner_ is the product of the dimensions after split_.
  inner_ = 1;
  for (std::size_t k = split_ + 1; k < shape_.size(); ++k) inner_ *= shape_[k];
  pieces_ = (shape_[split_] + chunk_[split_] - 1) / chunk_[split_];
}

std::size_t ChunkGrid::chunk_count() const {
  std::size_t outer = 1;
  for (std::size_t k = 0; k < split_; ++k) outer *= shape_[k];
  return outer * pieces_;
}

std::size_t ChunkGrid::chunk_of(std::int64_t index) const {
  const auto i = static_cast<std::size_t>(index);
  const std::size_t outer = i / (shape_[split_] * inner_);
  const std::size_t along = (i / inner_) % shape_[split_];
  return outer * pieces_ + along / chunk_[split_];
}

ChunkGrid::Range ChunkGrid::range(std::size_t chunk) const {
  const std::size_t outer = chunk / pieces_;
  const std::size_t first_along = (chunk % pieces_) * chunk_[split_];
  const std::size_t along = std::min(chunk_[split_], shape_[split_] - first_along);
  Range r;
  r.first = static_cast<std::int64_t>((outer * shape_[split_] + first_along) * inner_);
  r.count = static_cast<std::int64_t>(along * inner_);
  r.start = unravel(r.first, shape_);
  r.extent.assign(shape_.size(), 1);
  r.extent[split_] = along;
  for (std::size_t k = split_ + 1; k < shape_.size(); ++k) r.extent[k] = shape_[k];
  return r;
}

}  // namespace pcrf::cube
