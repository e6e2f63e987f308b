#include "mpi_world.hpp"

#include <cstdlib>
#include <string>

#include "contactrb/common/error.hpp"
#include "poll_backoff.hpp"

#if CONTACTRB_HAVE_MPI
#include <mpi.h>
#endif

namespace contactrb::app {

namespace {

// The number of processes the launcher started (0: not started by a launcher we know).
int launcher_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    const char* v = std::getenv(name);
    if (v != nullptr && *v != '\0') return std::atoi(v);
  }
  // PMIx launchers (OpenMPI 5's prterun) may set only the rank.
  const char* rank = std::getenv("PMIX_RANK");
  return rank != nullptr && *rank != '\0' ? 1 : 0;
}

}  // namespace

int mpirun_processes() { return launcher_size(); }

int mpirun_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    const char* v = std::getenv(name);
    if (v == nullptr || *v == '\0') continue;
    char* end = nullptr;
    const long r = std::strtol(v, &end, 10);
    return *end == '\0' && r >= 0 && r < 1 << 30 ? static_cast<int>(r) : -1;
  }
  return -1;
}

#if CONTACTRB_HAVE_MPI

bool built_with_mpi() { return true; }

std::unique_ptr<MpiWorld> MpiWorld::start_if_launched() {
  // One process has nothing to share: no MPI (a child of an MPI program, e.g. ParaView's
  // pvpython, inherits its OMPI_*/PMIX_* variables and must not initialize MPI).
  if (launcher_size() <= 1) return nullptr;
  return std::unique_ptr<MpiWorld>(new MpiWorld());
}

MpiWorld::MpiWorld() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  require(initialized == 0, "internal: MPI initialized twice");
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (provided < MPI_THREAD_FUNNELED) {
    // Rank 0 runs its own solver thread next to the main thread, which alone calls MPI.
    MPI_Finalize();
    throw Error("the MPI library does not support threads (MPI_THREAD_FUNNELED)");
  }
}

bool MpiWorld::agree(bool ok) {
  agreed_ = true;
  int mine = ok ? 1 : 0;
  int all = 0;
  // Polled (poll_backoff.hpp): the ranks that finish their setup (or their part) first would
  // otherwise spin until the last one gets here.
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
  PollBackoff backoff;
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    backoff.sleep();
  }
  return all == 1;
}

void MpiWorld::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();  // MPI_Abort does not return
}

MpiWorld::~MpiWorld() {
  if (!agreed_) agree(false);
  MPI_Finalize();
}

#else

bool built_with_mpi() { return false; }

std::unique_ptr<MpiWorld> MpiWorld::start_if_launched() {
  const int size = launcher_size();
  require(size <= 1, "this contactrb was built without MPI, but mpirun started " + std::to_string(size) +
                         " processes of it: each would do the whole run (rebuild with MPI: libopenmpi-dev, or run "
                         "without mpirun)");
  return nullptr;
}

MpiWorld::MpiWorld() = default;
bool MpiWorld::agree(bool ok) { return ok; }
void MpiWorld::abort(int code) { std::exit(code); }
MpiWorld::~MpiWorld() = default;

#endif

}  // namespace contactrb::app
