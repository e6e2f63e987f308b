#pragma once
// `mpirun -np K contactrb snapshots ...`: the solves of rb::generate_snapshots distributed over
// the ranks (docs/cluster.md). Rank 0 hands out the indices one at a time to whichever rank
// asks (solve times vary with mu), solves values itself on a second thread, gathers the results
// and reports the progress; ranks 1..K-1 solve what they are given. The solves are those of the
// serial run in its schedule (warm-start waves included), so the set equals the serial one bit
// for bit but the timings.
#include <optional>

#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "mpi_world.hpp"

namespace contactrb::app {

// Every rank calls it with the same request (its setup done). Returns the whole set on rank 0
// and nullopt on the other ranks. Throws contactrb::Error on rank 0 when some rank's setup
// failed (that rank printed why). options.jobs is ignored: each rank solves one value at a time.
std::optional<io::SnapshotSet> mpi_generate_snapshots(MpiWorld& world, const rb::SnapshotRequest& request,
                                                      const rb::SnapshotRunOptions& options);

}  // namespace contactrb::app
