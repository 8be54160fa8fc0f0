// Chunk layout of a cube (see chunk_grid.hpp).
#include "pcrf/cube/chunk_grid.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {

ChunkGrid::ChunkGrid(std::vector<std::size_t> shape, std::size_t target_cases, std::vector<std::size_t> multiples)
    : shape_(std::move(shape)), chunk_(shape_.size(), 1) {
  if (shape_.empty()) throw std::invalid_argument("ChunkGrid: a cube needs a dimension");
  for (auto n : shape_)
    if (n == 0) throw std::invalid_argument("ChunkGrid: empty dimension");
  if (!multiples.empty() && multiples.size() != shape_.size())
    throw std::invalid_argument("ChunkGrid: one multiple per dimension");
  if (std::find(multiples.begin(), multiples.end(), std::size_t{0}) != multiples.end())
    throw std::invalid_argument("ChunkGrid: a multiple of 0");
  target_cases = std::max<std::size_t>(target_cases, 1);
  // Take whole dimensions from the fastest one while they fit, then part of the next: as
  // many whole groups of it as fit, at least one. When everything fits, split_ stays 0 and
  // the single chunk is the whole cube.
  std::size_t cases = 1;
  for (std::size_t d = shape_.size(); d-- > 0;) {
    if (cases * shape_[d] > target_cases) {
      split_ = d;
      const std::size_t group = multiples.empty() ? 1 : multiples[d];
      chunk_[d] = std::min(shape_[d], std::max(group, target_cases / cases / group * group));
      break;
    }
    chunk_[d] = shape_[d];
    cases *= shape_[d];
  }
  derive();
}

bool ChunkGrid::valid_chunk_shape(const std::vector<std::size_t>& shape, const std::vector<std::size_t>& chunk) {
  if (shape.empty() || chunk.size() != shape.size()) return false;
  for (std::size_t d = 0; d < shape.size(); ++d)
    if (shape[d] == 0 || chunk[d] == 0 || chunk[d] > shape[d]) return false;
  // The cut: the last dimension not taken whole; every one before it is taken 1 at a time.
  std::size_t cut = shape.size();
  while (cut > 0 && chunk[cut - 1] == shape[cut - 1]) --cut;
  if (cut == 0) return true;  // one chunk: the whole cube
  for (std::size_t d = 0; d + 1 < cut; ++d)
    if (chunk[d] != 1) return false;
  return true;
}

ChunkGrid ChunkGrid::of_chunk_shape(std::vector<std::size_t> shape, const std::vector<std::size_t>& chunk) {
  if (!valid_chunk_shape(shape, chunk))
    throw std::invalid_argument("ChunkGrid: chunks that are not contiguous ranges of the cube's cases");
  ChunkGrid grid;
  grid.shape_ = std::move(shape);
  grid.chunk_ = chunk;
  std::size_t cut = grid.shape_.size();
  while (cut > 0 && grid.chunk_[cut - 1] == grid.shape_[cut - 1]) --cut;
  grid.split_ = cut == 0 ? 0 : cut - 1;
  grid.derive();
  return grid;
}

void ChunkGrid::derive() {
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

ChunkSpan chunk_span(const ChunkGrid& grid, std::size_t first_chunk, std::size_t end_chunk) {
  if (first_chunk > end_chunk || end_chunk > grid.chunk_count())
    throw std::out_of_range("chunks [" + std::to_string(first_chunk) + ", " + std::to_string(end_chunk) +
                            ") are outside the cube's " + std::to_string(grid.chunk_count()));
  ChunkSpan span;
  for (std::size_t c = first_chunk; c < end_chunk; ++c) {
    const auto r = grid.range(c);
    if (c == first_chunk) span.first = r.first;
    if (r.first != span.first + span.count) throw std::logic_error("chunk " + std::to_string(c) + " does not follow the one before it");
    span.count += r.count;
  }
  return span;
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

std::size_t coordinate_chunk_values(const ChunkGrid& grid, std::size_t dimension) {
  const std::size_t size = grid.shape().at(dimension);
  return std::min(size, std::max(grid.chunk_shape()[dimension], kCoordinateChunkMin));
}

std::size_t coordinate_chunk_values(const ChunkGrid& grid, std::size_t dimension, const Coordinate& c) {
  if (c.written_live()) return coordinate_chunk_values(grid, dimension);
  // Cut evenly: the last chunk pads at most one value a chunk (a chunk at the edge is sealed
  // and stored at its full extent).
  const std::size_t size = grid.shape().at(dimension);
  const std::size_t chunks = (size + kCreationCoordinateChunk - 1) / kCreationCoordinateChunk;
  return (size + chunks - 1) / chunks;
}

std::size_t coordinate_chunk_values(const CubeLayout& layout, const Coordinate& c) {
  const auto d = layout.find_dimension(c.dimension);
  if (!d) throw std::invalid_argument("coordinate '" + c.name + "' is over no dimension of the cube");
  return coordinate_chunk_values(layout_grid(layout), *d, c);
}

ChunkGrid layout_grid(const CubeLayout& layout) {
  if (layout.chunk_shape.empty()) return ChunkGrid(layout.shape());
  return ChunkGrid::of_chunk_shape(layout.shape(), layout.chunk_shape);
}

}  // namespace pcrf::cube
