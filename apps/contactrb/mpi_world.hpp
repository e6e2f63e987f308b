#pragma once
// The MPI world of a run started by mpirun (docs/parallel.md). contactrb uses MPI only when it
// was built with it (CONTACTRB_HAVE_MPI) and started by mpirun/mpiexec; a plain start runs as
// before, without initializing MPI. Only the main thread calls MPI (MPI_THREAD_FUNNELED).
#include <memory>

namespace contactrb::app {

class MpiWorld {
 public:
  // The world when this process was started by mpirun with more than one process (the
  // launcher's environment: OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_SIZE), nullptr otherwise
  // (`mpirun -np 1` runs as a plain start). Throws contactrb::Error
  // when started by mpirun with more than one process by a build without MPI (every process
  // would do the whole run and write the same files).
  static std::unique_ptr<MpiWorld> start_if_launched();

  // Every rank calls agree() once, after its setup (options, case, mesh) and before the
  // distributed work: true when every rank's setup succeeded. A rank whose setup threw calls
  // it from the destructor with false, so that no rank waits for it.
  bool agree(bool ok);

  // Ends the job at once (every rank), after an internal error in the distributed work
  // (a rank that stopped answering would leave the others waiting).
  [[noreturn]] void abort(int code);

  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  MpiWorld();
  int rank_ = 0;
  int size_ = 1;
  bool agreed_ = false;
};

// True when this build has MPI.
bool built_with_mpi();

// The number of processes mpirun started (from its environment), 0 when not started by it.
int mpirun_processes();

// This process's rank as the launcher's environment gives it (OMPI_COMM_WORLD_RANK, PMI_RANK or
// PMIX_RANK), -1 when it gives none: known before MPI_Init, for work that starts before it
// (cmd_snapshots.cpp). MpiWorld::rank() is the rank; a caller checks the two agree.
int mpirun_rank();

}  // namespace contactrb::app
