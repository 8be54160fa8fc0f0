/// \file mpi_session.hpp
/// \brief MPI for the lifetime of one command: initialization, rank and size, a barrier
/// that sleeps instead of spinning, and abort.
#pragma once

#include <mpi.h>

#include <string>

namespace pcrf::parallel {

/// Initializes MPI (thread level FUNNELED: only the thread that made the session calls MPI)
/// and finalizes it on destruction. Works without a launcher (one rank, "singleton").
///
/// When started by a launcher (mpirun, srun) the process also asks the kernel to kill it
/// if the launcher dies, so that a killed `mpirun` never leaves ranks behind that keep
/// writing the output file.
class MpiSession {
 public:
  /// Why MPI cannot start here, found before MPI_Init prints dozens of lines about it: a
  /// TMPDIR that is not a writable folder (Open MPI keeps its session files there). Empty
  /// when none is known.
  static std::string startup_problem();

  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm comm() const { return MPI_COMM_WORLD; }
  bool is_master() const { return rank_ == 0; }

  /// Barrier that polls with short sleeps: ranks that are done wait without burning the
  /// cores that the remaining work needs (a plain MPI_Barrier spins in Open MPI).
  void quiet_barrier() const;

  /// Broadcasts an int from rank 0. Waits as quiet_barrier() does: the other ranks wait here
  /// while rank 0 checks the study and opens the cube, without spinning in MPI.
  int broadcast(int value) const;
  /// Broadcasts a string from rank 0.
  std::string broadcast(std::string text) const;

  /// Ends every rank at once (for errors after work has started).
  [[noreturn]] void abort(int exit_code) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool owns_ = false;  ///< false when MPI was already initialized by someone else
};

}  // namespace pcrf::parallel
