// The order of the units a study hands out (see unit_order.hpp).
#include "pcrf/run/unit_order.hpp"

#include <algorithm>

namespace pcrf::run {

bool hands_out_by_frame(const study::CaseSpace& space) { return space.size() > 1 && space.handout_index(1) != 1; }

std::pair<std::int64_t, std::int64_t> FrameColumns::positions(const cube::ChunkGrid& grid, std::size_t column) const {
  const auto r = grid.range(column);  // excitation 0's piece: its frames
  const auto e = static_cast<std::int64_t>(excitations);
  return {r.first * e, (r.first + r.count) * e};
}

FrameColumns frame_columns(const cube::ChunkGrid& grid, const study::CaseSpace& space) {
  const std::int64_t frames = space.distinct_frames();
  if (space.ida_runs() > 0 || frames < 1 || space.size() % frames != 0) return {};
  const auto& chunk = grid.chunk_shape();
  for (std::size_t d = 0; d < space.frame_dimension(); ++d)
    if (chunk[d] != 1) return {};  // a chunk spans excitations
  const auto excitations = static_cast<std::size_t>(space.size() / frames);
  if (grid.chunk_count() % excitations != 0 || grid.chunk_count() / excitations < 2) return {};
  const FrameColumns columns{grid.chunk_count() / excitations, excitations};
  const auto group = static_cast<std::int64_t>(std::max<std::size_t>(space.plan().frames_per_group(), 1));
  for (std::size_t q = 0; q < columns.columns; ++q) {
    const auto r = grid.range(q);
    if (r.first % group != 0 || (r.count % group != 0 && r.first + r.count != frames)) return {};
  }
  return columns;
}

std::vector<std::size_t> unit_order(const cube::ChunkGrid& grid, const study::CaseSpace& space) {
  std::vector<std::size_t> order;
  if (!hands_out_by_frame(space)) {
    order.resize(grid.chunk_count());
    for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
    return order;
  }
  const FrameColumns columns = frame_columns(grid, space);
  for (std::size_t q = 0; q < columns.columns; ++q)
    for (std::size_t e = 0; e < columns.excitations; ++e) order.push_back(columns.chunk(q, e));
  return order;
}

}  // namespace pcrf::run
