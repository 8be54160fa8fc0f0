// A new cube made by every rank together (see cube_creation.hpp).
#include "pcrf/run/cube_creation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <thread>

#include "pcrf/cube/sealed_chunk.hpp"

namespace pcrf::run {
namespace {

// Rank 0's words to every worker (broadcasts).
constexpr int kWordFailed = 0;  ///< rank 0 could not make the cube: the run ends
constexpr int kWordSeal = 1;    ///< rank 0's writer asks for pieces
constexpr int kWordMade = 2;    ///< the cube is made (or opened): the run goes on
// Point-to-point messages of the phase (the scheduler's are 101-103; the run starts after
// every one of these is matched).
constexpr int kTagAsk = 201;    ///< rank 0 → worker: one int, 1 "seal your next piece", 0 "stop"
constexpr int kTagPiece = 202;  ///< worker → rank 0: the sealed bytes, then their PieceHeader
constexpr int kAskNext = 1;
constexpr int kAskStop = 0;

struct PieceHeader {
  std::uint64_t coordinate = 0;
  std::uint64_t piece = 0;
};

/// How long a waiting rank sleeps between two looks at its message [µs]: waiting ranks leave
/// the cores to those that seal and write (an oversubscribed machine), and spend a few
/// instructions a look, not a spin's worth. A piece takes milliseconds to seal.
/// Not a blocking MPI_Wait: Open MPI's (4.1, Debian 12) spins in its progress engine until
/// the message comes. Measured on rank 0 (rank_costs.py --ranks 4, two sizes, callgrind):
/// 9-13 M instructions in take() against 0.5-4 M for this loop. What either counts is
/// waiting, ~630 instructions a look: it grows with the time the workers take to seal, and
/// is gone once rank 0 writes slower than they seal (many workers), not a cost a case.
constexpr auto kLookEvery = std::chrono::microseconds(100);

void wait_quietly(MPI_Request& request, MPI_Status* status) {
  for (int done = 0;;) {
    MPI_Test(&request, &done, status);
    if (done) return;
    std::this_thread::sleep_for(kLookEvery);
  }
}

/// Worker w's share of n pieces (w in 1 … workers): w - 1, w - 1 + workers, …
std::size_t first_of(int worker) { return static_cast<std::size_t>(worker - 1); }
int owner_of(std::size_t position, int workers) { return 1 + static_cast<int>(position % static_cast<std::size_t>(workers)); }

}  // namespace

WorkerCoordinates::WorkerCoordinates(const parallel::MpiSession& mpi)
    : mpi_(mpi), asked_(static_cast<std::size_t>(mpi.size()), 0) {}

WorkerCoordinates::~WorkerCoordinates() = default;

void WorkerCoordinates::ask(int worker, int word) {
  MPI_Send(&word, 1, MPI_INT, worker, kTagAsk, mpi_.comm());
  if (word == kAskNext) asked_[static_cast<std::size_t>(worker)] = 1;
}

/// The piece `worker` was asked for, into buffer_: the bytes received (header and piece).
std::size_t WorkerCoordinates::take(int worker) {
  MPI_Request request;
  MPI_Irecv(buffer_.get(), static_cast<int>(buffer_size_), MPI_BYTE, worker, kTagPiece, mpi_.comm(), &request);
  MPI_Status status;
  wait_quietly(request, &status);
  asked_[static_cast<std::size_t>(worker)] = 0;
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  return static_cast<std::size_t>(count);
}

std::span<const char> WorkerCoordinates::sealed(const cube::CubeLayout& layout, const cube::CoordinatePiece& piece) {
  const int workers = mpi_.size() - 1;
  if (!started_) {
    started_ = true;
    pieces_ = cube::coordinate_pieces(layout);
    // At most a header and a piece of the largest chunk a coordinate has (filtered_bound), not
    // cleared: MPI writes what it receives, and only that is read (8 MiB cleared for a case
    // number of 2^20 values was 6 M instructions on rank 0 before the first hand-out).
    std::size_t largest = 0;
    for (const auto& p : pieces_) largest = std::max(largest, p.chunk_values);
    buffer_size_ = sizeof(PieceHeader) + cube::filtered_bound(largest, sizeof(double));
    buffer_ = std::make_unique_for_overwrite<char[]>(buffer_size_);
    mpi_.broadcast(kWordSeal);
    for (int w = 1; w <= workers; ++w)
      if (first_of(w) < pieces_.size()) ask(w, kAskNext);  // each worker seals its first piece at once
  }
  const std::string what = "coordinate '" + layout.coordinates.at(piece.coordinate).name + "', piece " +
                           std::to_string(piece.piece);
  if (next_ >= pieces_.size() || !(pieces_[next_] == piece))
    throw cube::CubeError("the cube's creation asked for " + what + " out of order");
  const int worker = owner_of(next_, workers);
  const std::size_t received = take(worker);
  if (next_ + static_cast<std::size_t>(workers) < pieces_.size()) ask(worker, kAskNext);  // its next, while this one is written
  ++next_;
  PieceHeader header;
  if (received < sizeof header) throw cube::CubeError("rank " + std::to_string(worker) + " sent no " + what);
  const std::size_t bytes = received - sizeof header;
  std::memcpy(&header, buffer_.get() + bytes, sizeof header);
  if (header.coordinate != piece.coordinate || header.piece != piece.piece)
    throw cube::CubeError("rank " + std::to_string(worker) + " sent another piece than " + what);
  return std::span<const char>(buffer_.get(), bytes);
}

void WorkerCoordinates::finish(bool made) {
  if (finished_) return;
  finished_ = true;
  if (started_) {
    for (int w = 1; w < mpi_.size(); ++w) {
      if (asked_[static_cast<std::size_t>(w)]) take(w);  // a piece no longer wanted: matched, dropped
      ask(w, kAskStop);
    }
  }
  mpi_.broadcast(made ? kWordMade : kWordFailed);
}

bool seal_coordinates_for_rank0(const parallel::MpiSession& mpi, const std::function<cube::CubeLayout()>& layout) {
  int word = mpi.broadcast(0);
  if (word == kWordSeal) {
    const cube::CubeLayout made = layout();
    const auto pieces = cube::coordinate_pieces(made);
    const int workers = mpi.size() - 1;
    std::size_t position = first_of(mpi.rank());
    for (;;) {
      int ask = kAskStop;
      MPI_Request request;
      MPI_Irecv(&ask, 1, MPI_INT, 0, kTagAsk, mpi.comm(), &request);
      wait_quietly(request, MPI_STATUS_IGNORE);
      if (ask != kAskNext) break;
      if (position >= pieces.size())
        throw std::runtime_error("rank 0 asked for a coordinate piece beyond this rank's share (another layout?)");
      const cube::CoordinatePiece& piece = pieces[position];
      // The header goes after the bytes: within the capacity the deflate left, nothing moves.
      std::vector<char> message =
          cube::seal_coordinate_piece(made.coordinates[piece.coordinate], piece.chunk_values, piece.piece);
      const PieceHeader header{piece.coordinate, piece.piece};
      const std::size_t bytes = message.size();
      message.resize(bytes + sizeof header);
      std::memcpy(message.data() + bytes, &header, sizeof header);
      MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, kTagPiece, mpi.comm(), &request);
      wait_quietly(request, MPI_STATUS_IGNORE);
      position += static_cast<std::size_t>(workers);
    }
    word = mpi.broadcast(0);
  }
  return word == kWordMade;
}

}  // namespace pcrf::run
