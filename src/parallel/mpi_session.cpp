// MPI lifetime for one `pcrf study` run (see mpi_session.hpp).
#include "pcrf/parallel/mpi_session.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include <csignal>
#include <sys/prctl.h>
#include <unistd.h>

namespace pcrf::parallel {
namespace {

bool started_by_launcher() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (std::getenv(var) != nullptr) return true;
  return false;
}

/// If the launcher that forked us dies (e.g. SIGKILL to mpirun), die too: an orphaned
/// rank 0 would go on writing the cube while the user resumes it.
void die_with_launcher() {
  const pid_t parent = ::getppid();
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) std::_Exit(137);  // the launcher died before prctl took hold
}

}  // namespace

std::string MpiSession::startup_problem() {
  const char* tmpdir = std::getenv("TMPDIR");
  if (tmpdir == nullptr || *tmpdir == '\0') return "";
  // A folder made and removed: the only test that a read-only mount, a file or a missing path fails.
  std::string probe = std::string(tmpdir) + "/pcrf_probe_XXXXXX";
  if (::mkdtemp(probe.data()) != nullptr) {
    ::rmdir(probe.c_str());
    return "";
  }
  return std::string("TMPDIR ") + tmpdir + " is not a writable folder (" + std::strerror(errno) +
         "); Open MPI needs one: set TMPDIR to one, e.g. TMPDIR=/tmp";
}

MpiSession::MpiSession() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    if (started_by_launcher()) die_with_launcher();
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    owns_ = true;
    if (provided < MPI_THREAD_FUNNELED) {
      MPI_Finalize();
      throw std::runtime_error("the MPI library does not support MPI_THREAD_FUNNELED");
    }
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (owns_) MPI_Finalize();
}

namespace {

/// Waits for a non-blocking collective, testing it every 2 ms.
void wait_quietly(MPI_Request& request) {
  int done = 0;
  for (;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace

void MpiSession::quiet_barrier() const {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  wait_quietly(request);
}

int MpiSession::broadcast(int value) const {
  MPI_Request request;
  MPI_Ibcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait_quietly(request);
  return value;
}

std::string MpiSession::broadcast(std::string text) const {
  const int size = broadcast(static_cast<int>(text.size()));
  text.resize(static_cast<std::size_t>(size));
  MPI_Bcast(text.data(), size, MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

void MpiSession::abort(int exit_code) const {
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::_Exit(exit_code);  // MPI_Abort does not return; keeps [[noreturn]] honest
}

}  // namespace pcrf::parallel
