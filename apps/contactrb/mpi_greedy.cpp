#include "mpi_greedy.hpp"

#include <climits>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/snapshot_wire.hpp"
#include "mpi_gather.hpp"
#include "poll_backoff.hpp"

#if CONTACTRB_HAVE_MPI
#include <mpi.h>
#endif

namespace contactrb::app {

#if CONTACTRB_HAVE_MPI

namespace {

int to_int(std::size_t n, const char* what) {
  require(n < static_cast<std::size_t>(INT_MAX), std::string("greedy under MPI: more than 2^31 ") + what);
  return static_cast<int>(n);
}

// Waits for a non-blocking collective, polling with sleeps: a rank that finished its block (or
// waits for rank 0's HF solve) would otherwise spin in OpenMPI's blocking call and take CPU from
// the ranks still working (as in mpi_snapshots.cpp).
void wait_polling(MPI_Request& request) {
  PollBackoff backoff;
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    backoff.sleep();
  }
}

// Every rank: its block filled in `values`; afterwards every rank holds all blocks (in point
// order, as the serial sweep's vector). The Allreduce first, so that a rank whose sweep threw does not leave the others in the gather.
bool all_gather(MpiWorld& world, std::vector<double>& values, bool ok) {
  int mine = ok ? 1 : 0, all = 0;
  MPI_Request pending = MPI_REQUEST_NULL;
  MPI_Iallreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  if (all == 0) return false;
  std::vector<int> counts, displs;
  for (int r = 0; r < world.size(); ++r) {
    const auto [b, e] = rank_block(values.size(), r, world.size());
    counts.push_back(to_int(e - b, "training points"));
    displs.push_back(to_int(b, "training points"));
  }
  MPI_Iallgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, values.data(), counts.data(), displs.data(), MPI_DOUBLE,
                  MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  return true;
}

// Rank 0 solves and broadcasts {status, size} then the bytes: the packed snapshot and layout
// (status 0) or the error message (status 1), which every rank then throws.
io::SnapshotSet share(MpiWorld& world, const std::function<io::SnapshotSet()>& solve, const rb::SnapshotRequest& one) {
  std::uint64_t head[2] = {0, 0};
  std::vector<char> bytes;
  io::SnapshotSet set;
  std::exception_ptr error;
  if (world.rank() == 0) {
    try {
      set = solve();
      require(set.snapshots.size() == 1, "internal: the greedy's HF solve gave " + std::to_string(set.snapshots.size()) +
                                              " snapshots");
      rb::SnapshotLayout layout;
      layout.valid = set.num_dofs > 0;  // assemble_snapshot_set leaves num_dofs 0 without a solver
      layout.num_dofs = set.num_dofs;
      layout.free_dofs = set.free_dofs;
      layout.contact_dofs = set.contact_dofs;
      layout.slave = set.slave;
      layout.master = set.master;
      layout.constraint = set.constraint;
      bytes = rb::pack_solved(0, set.snapshots.front(), layout);
      to_int(bytes.size(), "bytes in one snapshot");
    } catch (const std::exception& e) {
      error = std::current_exception();
      const std::string what = e.what();
      bytes.assign(what.begin(), what.end());
      head[0] = 1;
    } catch (...) {
      error = std::current_exception();
      const std::string what = "unknown exception";
      bytes.assign(what.begin(), what.end());
      head[0] = 1;
    }
    head[1] = bytes.size();
  }
  // The other ranks wait here during the whole HF solve.
  MPI_Request pending = MPI_REQUEST_NULL;
  MPI_Ibcast(head, 2, MPI_UINT64_T, 0, MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  bytes.resize(static_cast<std::size_t>(head[1]));
  MPI_Bcast(bytes.data(), static_cast<int>(head[1]), MPI_BYTE, 0, MPI_COMM_WORLD);
  if (world.rank() == 0) {
    if (error) std::rethrow_exception(error);
    return set;
  }
  if (head[0] != 0) throw Error("greedy: the HF solve on MPI rank 0 failed: " + std::string(bytes.begin(), bytes.end()));
  std::uint64_t index = 0;
  std::vector<io::Snapshot> snapshots(1);
  std::vector<rb::SnapshotLayout> layouts(1);
  rb::unpack_solved(bytes, index, snapshots.front(), layouts.front());
  require(index == 0, "internal: unexpected snapshot index from MPI rank 0");
  return rb::assemble_snapshot_set(one, std::move(snapshots), layouts);
}

}  // namespace

rb::GreedyDistribution mpi_greedy_distribution(MpiWorld& world) {
  rb::GreedyDistribution d;
  MpiWorld* w = &world;
  d.block = [w](std::size_t n) { return rank_block(n, w->rank(), w->size()); };
  d.gather = [w](std::vector<double>& values, bool ok) { return all_gather(*w, values, ok); };
  d.share = [w](const std::function<io::SnapshotSet()>& solve, const rb::SnapshotRequest& one) {
    return share(*w, solve, one);
  };
  return d;
}

#else

rb::GreedyDistribution mpi_greedy_distribution(MpiWorld& world) {
  require(world.size() == 1, "internal: the MPI greedy in a build without MPI");
  return {};
}

#endif

}  // namespace contactrb::app
