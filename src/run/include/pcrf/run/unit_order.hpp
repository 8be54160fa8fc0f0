/// \file unit_order.hpp
/// \brief The order in which a study hands out whole chunks of its cube (units, issue 38):
/// storage order, or for a plan handed out frame by frame (a Saltelli design) column by column.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/study/case_space.hpp"

namespace pcrf::run {

/// True when the plan hands its cases out frame by frame (study::CaseSpace::handout_index maps
/// position 1 to the second frame); false: in storage order, every position to itself.
bool hands_out_by_frame(const study::CaseSpace& space);

/// How a plan handed out frame by frame goes out in whole chunks: by columns. Where every
/// chunk lies within one excitation (a record, level and incidence) and holds whole groups of
/// frames (Plan::frames_per_group: a Saltelli base sample's d + 2), a column is one piece of
/// the frame axis for every excitation, chunk e·K + q being column q of excitation e. The
/// columns go out one after another, so that a run stopped after column q holds every base
/// sample of columns 0 … q, as the frame-by-frame order would; the column in progress is the
/// most it loses to that order (1/K of the base samples). Column q's cases are a run of
/// hand-out positions: frames [a, b) of every excitation are positions [a·E, b·E).
struct FrameColumns {
  std::size_t columns = 0;      ///< K: chunks per excitation; 0: none (the chunks allow no columns)
  std::size_t excitations = 0;  ///< E
  explicit operator bool() const { return columns > 0; }
  std::size_t chunk(std::size_t column, std::size_t excitation) const { return excitation * columns + column; }
  std::size_t column_of(std::size_t chunk) const { return chunk % columns; }
  /// The hand-out positions of column q: [first, end).
  std::pair<std::int64_t, std::int64_t> positions(const cube::ChunkGrid& grid, std::size_t column) const;
};

/// The columns of a plan handed out frame by frame, when its cube's chunks allow them: each
/// within one excitation, of whole groups of frames, at least two of them per excitation (one
/// would hold no base sample whole before the run's end). None otherwise: a cube of an earlier
/// version whose chunks split base samples, or chunks that span excitations (a frame axis
/// short enough that a chunk holds it whole for several excitations).
FrameColumns frame_columns(const cube::ChunkGrid& grid, const study::CaseSpace& space);

/// The chunks a study may hand out whole, in the order it hands them out: every chunk in
/// storage order; for a plan handed out frame by frame, column by column (FrameColumns), or
/// none where its chunks allow no columns (its cases then go case by case, frame by frame).
std::vector<std::size_t> unit_order(const cube::ChunkGrid& grid, const study::CaseSpace& space);

}  // namespace pcrf::run
