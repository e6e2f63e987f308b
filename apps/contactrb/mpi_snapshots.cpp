#include "mpi_snapshots.hpp"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <deque>
#include <exception>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/common/printable.hpp"
#include "contactrb/offline/snapshot_wire.hpp"
#include "poll_backoff.hpp"

#if CONTACTRB_HAVE_MPI
#include <mpi.h>
#endif

namespace contactrb::app {

std::optional<std::size_t> first_task(const offline::SnapshotSchedule& schedule, int rank) {
  const std::vector<std::size_t>& wave = schedule.waves.front();
  if (rank < 0 || static_cast<std::size_t>(rank) >= wave.size()) return std::nullopt;
  return wave[static_cast<std::size_t>(rank)];
}

#if CONTACTRB_HAVE_MPI

namespace {

enum Tag : int { kReady = 1, kResult = 2, kTask = 3, kStop = 4 };

void send(const std::vector<char>& bytes, int to, Tag tag) {
  require(bytes.size() < static_cast<std::size_t>(INT_MAX), "internal: an MPI message of 2 GB or more");
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

// The next message from `from` (MPI_ANY_SOURCE: anyone), or none when `wait` is false and
// nothing has arrived. Waits by probing and sleeping (poll_backoff.hpp): OpenMPI's blocking
// calls spin, which would take a core from the solves of this machine.
bool probe(int from, bool wait, MPI_Status& status, PollBackoff& backoff) {
  for (;;) {
    int flag = 0;
    MPI_Iprobe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (flag != 0) {
      backoff.reset();
      return true;
    }
    if (!wait) return false;
    backoff.sleep();
  }
}

// The coordinator's longest sleep: a hundredth of the mean solve time of the results so far
// (a result then waits at most 1 % of a solve for its next task), between 0.1 and 5 ms; 1 ms
// before the first result.
PollBackoff::Duration coordinator_cap(double solve_seconds, int solves) {
  if (solves == 0) return PollBackoff::Duration(1000);
  const double us = 1e6 * solve_seconds / solves / 100;
  return PollBackoff::Duration(static_cast<long>(std::clamp(us, 100.0, 5000.0)));
}

std::vector<char> receive(const MPI_Status& status) {
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  std::vector<char> bytes(static_cast<std::size_t>(count));
  MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

// The ranks that start with a task of their own (first_task): 0 .. preassigned - 1.
std::size_t preassigned(const offline::SnapshotSchedule& schedule, int size) {
  return std::min(schedule.waves.front().size(), static_cast<std::size_t>(size));
}

// The early solve when it is the one of index i, else a solve of i now (cold: a first-wave value).
offline::SnapshotLayout solve_first(const offline::SnapshotRequest& request, std::size_t i,
                                    std::future<std::optional<EarlySolve>>& early, io::Snapshot& out) {
  if (early.valid()) {
    std::optional<EarlySolve> e = early.get();
    if (e && e->index == i) {
      out = std::move(e->snapshot);
      return std::move(e->layout);
    }
  }
  return offline::solve_snapshot(request, i, out, nullptr);
}

io::SnapshotSet run_rank0(MpiWorld& world, const offline::SnapshotRequest& request,
                          const offline::SnapshotRunOptions& options, std::future<std::optional<EarlySolve>> early) {
  const std::size_t n = request.mu.size();
  std::vector<io::Snapshot> snapshots(n);
  std::vector<offline::SnapshotLayout> layouts(n);
  offline::SnapshotProgress progress(options.progress, options.progress_stream, n);
  const offline::SnapshotSchedule schedule = offline::snapshot_schedule(request, options);
  const auto start_of = [&](std::size_t i) { return schedule.start[i] ? &snapshots[*schedule.start[i]] : nullptr; };
  std::deque<int> idle;  // ranks waiting for a task
  std::vector<char> heard(static_cast<std::size_t>(world.size()), 0);  // ranks that sent a first message
  int workers_heard = 0;
  std::vector<char> solved(n, 0);
  PollBackoff backoff(coordinator_cap(0, 0));
  double remote_seconds = 0;  // the solve times of the other ranks' results
  int remote_solves = 0;

  // Handles one message of a worker: a first "ready" (a worker without a first task) or a result.
  const auto handle = [&](const MPI_Status& status) {
    const std::vector<char> bytes = receive(status);
    char& first = heard[static_cast<std::size_t>(status.MPI_SOURCE)];
    if (first == 0) {
      first = 1;
      ++workers_heard;
    }
    if (status.MPI_TAG == kResult) {
      std::uint64_t i = 0;
      io::Snapshot s;
      offline::SnapshotLayout layout;
      offline::unpack_solved(bytes, i, s, layout);
      require(i < n && solved[i] == 0, "internal: rank " + std::to_string(status.MPI_SOURCE) +
                                           " returned value " + std::to_string(i) + ", which it was not given");
      solved[i] = 1;
      snapshots[i] = std::move(s);
      layouts[i] = std::move(layout);
      remote_seconds += snapshots[i].time_s;
      backoff.set_cap(coordinator_cap(remote_seconds, ++remote_solves));
      progress.finished(snapshots[i]);
    } else if (status.MPI_TAG != kReady) {
      throw Error("internal: unexpected MPI message tag " + std::to_string(status.MPI_TAG));
    }
    idle.push_back(status.MPI_SOURCE);
  };

  for (std::size_t w = 0; w < schedule.waves.size(); ++w) {
    const std::vector<std::size_t>& wave = schedule.waves[w];
    // The first wave's first values are the ranks' own first tasks (rank r: the r-th).
    const std::size_t own = w == 0 ? preassigned(schedule, world.size()) : 0;
    std::atomic<std::size_t> next{own};
    std::atomic<bool> local_done{false};
    std::exception_ptr local_error;
    // Rank 0's own solver thread: its first task, then indices from the same counter as the
    // other ranks.
    std::thread local([&] {
      try {
        if (own > 0) {
          const std::size_t i = wave[0];
          layouts[i] = solve_first(request, i, early, snapshots[i]);
          solved[i] = 1;
          progress.finished(snapshots[i]);
        }
        for (std::size_t k = next.fetch_add(1); k < wave.size(); k = next.fetch_add(1)) {
          const std::size_t i = wave[k];
          layouts[i] = offline::solve_snapshot(request, i, snapshots[i], start_of(i));
          solved[i] = 1;
          progress.finished(snapshots[i]);
        }
      } catch (...) {
        local_error = std::current_exception();
      }
      local_done = true;
    });
    std::size_t outstanding = own > 0 ? own - 1 : 0;  // tasks of other ranks not returned
    for (;;) {
      while (!idle.empty()) {
        const std::size_t k = next.fetch_add(1);
        if (k >= wave.size()) break;
        const std::size_t i = wave[k];
        send(offline::pack_task(i, start_of(i)), idle.front(), kTask);
        idle.pop_front();
        ++outstanding;
      }
      if (local_done && outstanding == 0) break;
      MPI_Status status;
      // Blocking when only the other ranks are still at work.
      if (probe(MPI_ANY_SOURCE, local_done.load(), status, backoff)) {
        const bool result = status.MPI_TAG == kResult;
        handle(status);
        if (result) --outstanding;
      } else {
        backoff.sleep();
      }
    }
    local.join();
    if (local_error) std::rethrow_exception(local_error);
  }
  // Every worker is idle once it has sent its first message: then stop them all.
  while (workers_heard < world.size() - 1) {
    MPI_Status status;
    probe(MPI_ANY_SOURCE, true, status, backoff);
    handle(status);
  }
  for (int r = 1; r < world.size(); ++r) send({}, r, kStop);
  return offline::assemble_snapshot_set(request, std::move(snapshots), layouts);
}

void run_worker(const MpiWorld& world, const offline::SnapshotRequest& request,
                const offline::SnapshotRunOptions& options, std::future<std::optional<EarlySolve>> early) {
  // The first message: the result of this rank's first task, or "ready" when it has none.
  if (const std::optional<std::size_t> i = first_task(offline::snapshot_schedule(request, options), world.rank())) {
    io::Snapshot s;
    const offline::SnapshotLayout layout = solve_first(request, *i, early, s);
    send(offline::pack_solved(*i, s, layout), 0, kResult);
  } else {
    send({}, 0, kReady);
  }
  PollBackoff backoff;  // the next task comes at once (at the coordinator's next poll), or kStop
  for (;;) {
    MPI_Status status;
    probe(0, true, status, backoff);
    const std::vector<char> bytes = receive(status);
    if (status.MPI_TAG == kStop) return;
    require(status.MPI_TAG == kTask, "internal: unexpected MPI message tag " + std::to_string(status.MPI_TAG));
    std::uint64_t i = 0;
    bool has_start = false;
    io::Snapshot start;
    offline::unpack_task(bytes, i, has_start, start);
    require(i < request.mu.size(), "internal: task index " + std::to_string(i) + " out of range");
    io::Snapshot s;
    const offline::SnapshotLayout layout = offline::solve_snapshot(request, i, s, has_start ? &start : nullptr);
    send(offline::pack_solved(i, s, layout), 0, kResult);
  }
}

}  // namespace

std::optional<io::SnapshotSet> mpi_generate_snapshots(MpiWorld& world, const offline::SnapshotRequest& request,
                                                      const offline::SnapshotRunOptions& options,
                                                      std::future<std::optional<EarlySolve>> early) {
  const bool ok = !request.mu.empty() && offline::has_problem_factory(request);
  if (!world.agree(ok)) {
    if (world.rank() == 0) throw Error("an MPI rank could not start the run (its error is above)");
    return std::nullopt;
  }
  try {
    if (world.rank() == 0) return run_rank0(world, request, options, std::move(early));
    run_worker(world, request, options, std::move(early));
    return std::nullopt;
  } catch (const std::exception& e) {
    // A rank that leaves the protocol would leave the others waiting for it: end the job.
    std::cerr << "contactrb: internal error on MPI rank " << world.rank() << ": " << printable(e.what())
              << " (ending the MPI job)\n"
              << std::flush;
    world.abort(2);
  }
}

#else

std::optional<io::SnapshotSet> mpi_generate_snapshots(MpiWorld&, const offline::SnapshotRequest&,
                                                      const offline::SnapshotRunOptions&,
                                                      std::future<std::optional<EarlySolve>>) {
  throw Error("internal: MPI snapshots in a build without MPI");
}

#endif

}  // namespace contactrb::app
