/// \file cube_creation.hpp
/// \brief A new cube made by every rank together (issue 38: no rank pays per case before the
/// first hand-out). Rank 0 writes the file, as it always did (its image, then its long
/// coordinates, synced and renamed into place only when whole); the other ranks compute and
/// compress its coordinate pieces (cube::seal_coordinate_piece), which rank 0 copies in raw.
/// Since the coordinates along cases are written during the run (Coordinate::written_live:
/// each unit's worker seals its chunk of them, study_run.cpp's ChunkSealer), the pieces of the
/// creation are those of the case number only (cube::coordinate_pieces).
///
/// The phase, between rank 0's checks (the study, the lock) and the first hand-out:
///   - every worker waits for rank 0's word (a broadcast): "seal" once rank 0's writer asks
///     for its first piece (a cube opened by --resume, or refused, asks for none), then
///     "made" or "failed" once rank 0's writer is made or has failed;
///   - after "seal", rank 0 asks each worker for one piece at a time, a step ahead: worker
///     w (1 … W) seals the pieces w - 1, w - 1 + W, … of cube::coordinate_pieces, in that
///     order, each when asked, and sends it; "stop" ends its share early or late;
///   - rank 0 takes the pieces in order. Whatever happens to its writer, it collects every
///     piece it asked for and tells every worker to stop before its last word: no message
///     is left unmatched, and every rank leaves the phase in order.
/// Memory: one piece (cube::coordinate_chunk_values: at most cube::kCreationCoordinateChunk
/// values) on each rank at a time. A study of up to 2^20 cases has one piece: one worker seals it.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/parallel/mpi_session.hpp"

namespace pcrf::run {

/// Rank 0's side: the writer's source of sealed coordinate pieces, sealed by the workers.
/// Main thread only (MPI is FUNNELED). Needs at least one worker.
class WorkerCoordinates final : public cube::CoordinateSource {
 public:
  explicit WorkerCoordinates(const parallel::MpiSession& mpi);
  ~WorkerCoordinates() override;
  WorkerCoordinates(const WorkerCoordinates&) = delete;
  WorkerCoordinates& operator=(const WorkerCoordinates&) = delete;

  /// \throws cube::CubeError when a worker's piece is not the one asked for, or too large.
  std::span<const char> sealed(const cube::CubeLayout& layout, const cube::CoordinatePiece& piece) override;
  /// Ends the phase on every rank: collects the pieces still asked for, stops every worker,
  /// and says whether the cube was made (`made`) or not. Call once, whatever happened.
  void finish(bool made);

 private:
  void ask(int worker, int word);
  std::size_t take(int worker);

  const parallel::MpiSession& mpi_;
  bool started_ = false;
  bool finished_ = false;
  std::vector<cube::CoordinatePiece> pieces_;
  std::size_t next_ = 0;           ///< the position in pieces_ the writer asks for next
  std::vector<char> asked_;        ///< per worker (index = rank): a piece is asked and not taken
  /// Where each piece arrives (the bytes, then a header): sized once for the largest piece,
  /// never cleared nor shifted (callgrind counts a byte copied or cleared as an instruction).
  std::unique_ptr<char[]> buffer_;  ///< a piece received, then its header (not cleared)
  std::size_t buffer_size_ = 0;
};

/// A worker's side of the phase: waits for rank 0's word, seals its share of the pieces of
/// `layout()` when asked (made only then: the same layout as rank 0's, make_cube_layout), and
/// returns true when rank 0 made (or opened) the cube, false when it failed.
/// \throws what `layout` or sealing throws (the caller ends the run: receive_study's rule).
bool seal_coordinates_for_rank0(const parallel::MpiSession& mpi, const std::function<cube::CubeLayout()>& layout);

}  // namespace pcrf::run
