#include "mpi_greedy.hpp"

#include <algorithm>
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

// Every rank: its block of points filled in `values` (`width` entries a point); afterwards every
// rank holds all blocks (in point order, as the serial sweep's vector). The Allreduce first, so
// that a rank whose sweep threw does not leave the others in the gather.
bool all_gather(MpiWorld& world, std::vector<double>& values, std::size_t width, bool ok) {
  int mine = ok ? 1 : 0, all = 0;
  MPI_Request pending = MPI_REQUEST_NULL;
  MPI_Iallreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  if (all == 0) return false;
  std::vector<int> counts, displs;
  require(width > 0 && values.size() % width == 0, "internal: a gathered sweep of " + std::to_string(values.size()) +
                                                      " entries in records of " + std::to_string(width));
  for (int r = 0; r < world.size(); ++r) {
    const auto [b, e] = rank_block(values.size() / width, r, world.size());
    counts.push_back(to_int(width * (e - b), "training points"));
    displs.push_back(to_int(width * b, "training points"));
  }
  MPI_Iallgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, values.data(), counts.data(), displs.data(), MPI_DOUBLE,
                  MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  return true;
}

// The step's point k on rank k mod size. Each rank packs its results as records [u64 length]
// [pack_solved bytes] (status 0) or its error message (status 1); all ranks gather every rank's
// {status, length} and then the bytes, so that each rank assembles the step's whole set, or throws
// the first failing rank's error.
io::SnapshotSet share(MpiWorld& world, const offline::GreedyDistribution::SolveFn& solve,
                      const offline::SnapshotRequest& step) {
  const std::size_t K = step.mu.size();
  const auto size = static_cast<std::size_t>(world.size());
  offline::SnapshotRequest part = step;
  part.mu.clear();
  std::vector<std::uint64_t> mine;
  for (std::size_t k = static_cast<std::size_t>(world.rank()); k < K; k += size) {
    mine.push_back(k);
    part.mu.push_back(step.mu[k]);
  }
  std::uint64_t head[2] = {0, 0};  // status, bytes
  std::vector<char> bytes;
  std::exception_ptr error;
  if (!mine.empty()) {
    try {
      const io::SnapshotSet set = solve(part);
      require(set.snapshots.size() == mine.size(), "internal: the greedy's HF solves gave " +
                                                       std::to_string(set.snapshots.size()) + " snapshots for " +
                                                       std::to_string(mine.size()) + " points");
      offline::SnapshotLayout layout;
      layout.valid = set.num_dofs > 0;  // assemble_snapshot_set leaves num_dofs 0 without a solver
      layout.num_dofs = set.num_dofs;
      layout.free_dofs = set.free_dofs;
      layout.contact_dofs = set.contact_dofs;
      layout.slave = set.slave;
      layout.master = set.master;
      layout.constraint = set.constraint;
      for (std::size_t j = 0; j < mine.size(); ++j) {
        const std::vector<char> record = offline::pack_solved(mine[j], set.snapshots[j], layout);
        const std::uint64_t length = record.size();
        const char* l = reinterpret_cast<const char*>(&length);
        bytes.insert(bytes.end(), l, l + sizeof length);
        bytes.insert(bytes.end(), record.begin(), record.end());
      }
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
  }
  head[1] = bytes.size();
  // Ranks without a point (or done first) wait here for the others' HF solves, polling.
  std::vector<std::uint64_t> heads(2 * size);
  MPI_Request pending = MPI_REQUEST_NULL;
  MPI_Iallgather(head, 2, MPI_UINT64_T, heads.data(), 2, MPI_UINT64_T, MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  std::vector<int> counts(size), displs(size);
  std::size_t total = 0;
  for (std::size_t r = 0; r < size; ++r) {
    counts[r] = to_int(heads[2 * r + 1], "bytes of one rank's HF solves");
    displs[r] = to_int(total, "bytes of a step's HF solves");
    total += heads[2 * r + 1];
  }
  to_int(total, "bytes of a step's HF solves");
  std::vector<char> all(total);
  MPI_Iallgatherv(bytes.data(), counts[static_cast<std::size_t>(world.rank())], MPI_BYTE, all.data(), counts.data(),
                  displs.data(), MPI_BYTE, MPI_COMM_WORLD, &pending);
  wait_polling(pending);
  if (error) std::rethrow_exception(error);
  for (std::size_t r = 0; r < size; ++r) {
    if (heads[2 * r] != 0) {
      const auto begin = all.begin() + displs[r];
      throw Error("greedy: the HF solve on MPI rank " + std::to_string(r) +
                  " failed: " + std::string(begin, begin + counts[r]));
    }
  }
  std::vector<io::Snapshot> snapshots(K);
  std::vector<offline::SnapshotLayout> layouts(K);
  std::vector<char> seen(K, 0);
  for (std::size_t at = 0; at < total;) {
    std::uint64_t length = 0;
    require(total - at >= sizeof length, "internal: a truncated HF result from another MPI rank");
    std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(at), sizeof length, reinterpret_cast<char*>(&length));
    at += sizeof length;
    require(length <= total - at, "internal: a truncated HF result from another MPI rank");
    const auto first = all.begin() + static_cast<std::ptrdiff_t>(at);
    const std::vector<char> record(first, first + static_cast<std::ptrdiff_t>(length));
    at += length;
    std::uint64_t index = 0;
    io::Snapshot snapshot;
    offline::SnapshotLayout layout;
    offline::unpack_solved(record, index, snapshot, layout);
    require(index < K && !seen[index], "internal: an unexpected HF result index from another MPI rank");
    seen[index] = 1;
    snapshots[index] = std::move(snapshot);
    layouts[index] = std::move(layout);
  }
  for (std::size_t k = 0; k < K; ++k) require(seen[k] != 0, "internal: an HF result missing after the MPI gather");
  return offline::assemble_snapshot_set(step, std::move(snapshots), layouts);
}

}  // namespace

offline::GreedyDistribution mpi_greedy_distribution(MpiWorld& world) {
  offline::GreedyDistribution d;
  MpiWorld* w = &world;
  d.block = [w](std::size_t n) { return rank_block(n, w->rank(), w->size()); };
  d.gather = [w](std::vector<double>& values, std::size_t width, bool ok) { return all_gather(*w, values, width, ok); };
  d.share = [w](const offline::GreedyDistribution::SolveFn& solve, const offline::SnapshotRequest& step) {
    return share(*w, solve, step);
  };
  d.max = [](std::vector<double>& values) {
    MPI_Request pending = MPI_REQUEST_NULL;
    MPI_Iallreduce(MPI_IN_PLACE, values.data(), to_int(values.size(), "values of a max over the ranks"), MPI_DOUBLE,
                   MPI_MAX, MPI_COMM_WORLD, &pending);
    wait_polling(pending);
  };
  return d;
}

#else

offline::GreedyDistribution mpi_greedy_distribution(MpiWorld& world) {
  require(world.size() == 1, "internal: the MPI greedy in a build without MPI");
  return {};
}

#endif

}  // namespace contactrb::app
