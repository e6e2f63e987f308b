#pragma once
// `mpirun -np K contactrb snapshots ...`: the solves of offline::generate_snapshots distributed over
// the ranks (docs/parallel.md). Rank 0 hands out the indices one at a time to whichever rank
// asks (solve times vary with mu), solves values itself on a second thread, gathers the results
// and reports the progress; ranks 1..K-1 solve what they are given. The solves are those of the
// serial run in its schedule (warm-start waves included), so the set equals the serial one bit
// for bit but the timings.
#include <cstddef>
#include <future>
#include <optional>

#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "mpi_world.hpp"

namespace contactrb::app {

// The first value of each rank is fixed (the first wave of the schedule, in order: rank r solves
// its r-th index, first_task), so that a rank can solve it before MPI is up: cmd_snapshots.cpp
// does its setup and that solve on a thread while MPI_Init waits (0.2-0.3 s of little CPU with
// OpenMPI's default transports), and hands the result over as `early`.

// The index of request.mu that rank `rank` solves first, nullopt when the first wave has no
// value for it (then it asks the coordinator for one).
std::optional<std::size_t> first_task(const offline::SnapshotSchedule& schedule, int rank);

// A value solved before the run (offline::solve_snapshot of `index`, cold).
struct EarlySolve {
  std::size_t index = 0;
  io::Snapshot snapshot;
  offline::SnapshotLayout layout;
};

// Every rank calls it with the same request (its setup done). Returns the whole set on rank 0
// and nullopt on the other ranks. Throws contactrb::Error on rank 0 when some rank's setup
// failed (that rank printed why). options.jobs is ignored: each rank solves one value at a time.
// `early` (when valid): this rank's first task, solved or being solved on another thread; used
// when its index is first_task(rank) (else the task is solved anew, e.g. when the launcher's
// rank guess was not MPI's rank).
std::optional<io::SnapshotSet> mpi_generate_snapshots(MpiWorld& world, const offline::SnapshotRequest& request,
                                                      const offline::SnapshotRunOptions& options,
                                                      std::future<std::optional<EarlySolve>> early = {});

}  // namespace contactrb::app
