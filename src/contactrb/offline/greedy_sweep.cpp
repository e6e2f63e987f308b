#include "contactrb/offline/greedy_sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <numeric>

#include "contactrb/common/error.hpp"
#include "contactrb/common/run_threads.hpp"
#include "contactrb/offline/offline_greedy.hpp"

namespace contactrb::offline {

using online::OnlineSolution;
using online::OnlineSolver;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Points solved per chunk of a lazy sweep: enough to keep two threads busy, few enough that a
// chunk rarely goes far past the cut. Fixed, not per thread: the points a lazy sweep solves, and
// so the greedy's picks, do not depend on the thread or process count.
constexpr std::size_t kChunk = 16;

// The criterion at some points (online solves only), `jobs` threads with one OnlineSolver each;
// every point writes its own slot, so the result does not depend on jobs. Only [begin, end) is
// solved (one process's block); the others keep +inf / not failed.
struct Sweep {
  std::vector<double> criterion;
  std::vector<double> failed;  // 1: the online solve at that point did not converge
};

using SolverPool = std::vector<std::unique_ptr<OnlineSolver>>;

Sweep sweep_block(const model::ReducedModel& model, const std::vector<cases::Mu>& mus,
                  const online::OnlineSettings& online, int jobs, std::size_t begin, std::size_t end,
                  SolverPool* pool) {
  Sweep out;
  out.criterion.assign(mus.size(), kInf);
  out.failed.assign(mus.size(), 0.0);
  std::vector<std::exception_ptr> errors(mus.size());
  std::atomic<std::size_t> next{begin};
  std::atomic<bool> stop{false};
  const auto work = [&](std::size_t t, std::exception_ptr& own_setup_error) {
    try {
      std::unique_ptr<OnlineSolver> own;
      std::unique_ptr<OnlineSolver>& slot = pool ? (*pool)[t] : own;
      if (!slot) slot = std::make_unique<OnlineSolver>(model);
      OnlineSolver& solver = *slot;
      for (std::size_t i = next.fetch_add(1); i < end && !stop; i = next.fetch_add(1)) {
        try {
          const OnlineSolution s = solver.solve(mus[i], online);
          out.failed[i] = s.converged() ? 0.0 : 1.0;
          out.criterion[i] = relative_estimate(model, mus[i], s);
        } catch (...) {  // nothing may escape a worker thread
          errors[i] = std::current_exception();
          stop = true;
        }
      }
    } catch (...) {
      own_setup_error = std::current_exception();
      stop = true;
    }
  };
  const std::size_t threads_count = std::max<std::size_t>(1, std::min(end - begin, static_cast<std::size_t>(jobs)));
  std::vector<std::exception_ptr> setup_errors(threads_count);
  if (pool && pool->size() < threads_count) pool->resize(threads_count);
  run_threads(threads_count, [&](std::size_t t) { work(t, setup_errors[t]); });
  for (const std::exception_ptr& e : setup_errors) {
    if (e) std::rethrow_exception(e);
  }
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return out;
}

// The sweep over `mus`: on this process alone, or its block on each process of a distributed
// run, then gathered (every process gets the same criterion and failures).
Sweep sweep_points(const model::ReducedModel& model, const std::vector<cases::Mu>& mus,
                   const online::OnlineSettings& online, int jobs, const GreedyDistribution& dist, SolverPool* pool) {
  if (!dist.active()) return sweep_block(model, mus, online, jobs, 0, mus.size(), pool);
  const auto [begin, end] = dist.block(mus.size());
  Sweep out;
  std::exception_ptr error;
  try {
    out = sweep_block(model, mus, online, jobs, begin, end, pool);
  } catch (...) {  // the other processes wait in the gather: tell them first
    error = std::current_exception();
    out.criterion.assign(mus.size(), kInf);
    out.failed.assign(mus.size(), 0.0);
  }
  const bool all_ok = dist.gather(out.criterion, !error);
  if (error) std::rethrow_exception(error);
  require(all_ok, "greedy: the estimate sweep failed on another MPI rank (its error is printed there)");
  dist.gather(out.failed, true);
  return out;
}

// Solves the training points `indices` with the current model and records them.
void solve_indices(const SweepContext& c, const std::vector<std::size_t>& indices, GreedyEstimates& e) {
  std::vector<cases::Mu> mus;
  mus.reserve(indices.size());
  for (std::size_t i : indices) mus.push_back(c.mus[i]);
  const Sweep s = sweep_points(c.model, mus, c.online, c.jobs, c.distribution, c.solvers);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const std::size_t i = indices[k];
    e.value[i] = s.failed[k] != 0.0 ? kInf : s.criterion[k];
    e.failed[i] = s.failed[k] != 0.0 ? 1 : 0;
    e.fresh[i] = 1;
  }
  e.solves += static_cast<int>(indices.size());
}

// The `wanted`-th largest fresh estimate among the eligible points (-inf when fewer are fresh).
double wanted_fresh_value(const GreedyEstimates& e, const std::vector<char>& eligible, std::size_t wanted) {
  std::vector<double> values;
  for (std::size_t i = 0; i < e.value.size(); ++i) {
    if (e.fresh[i] && eligible[i]) values.push_back(e.value[i]);
  }
  if (values.size() < wanted || wanted == 0) return -kInf;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(wanted - 1), values.end(),
                   std::greater<>());
  return values[wanted - 1];
}

}  // namespace

GreedyEstimates::GreedyEstimates(std::size_t points)
    : value(points, std::numeric_limits<double>::infinity()), failed(points, 0), fresh(points, 0) {}

void sweep_every_point(const SweepContext& c, GreedyEstimates& e) {
  std::fill(e.fresh.begin(), e.fresh.end(), 0);
  e.solves = 0;
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < c.mus.size(); ++i) {
    if (!c.skip[i]) indices.push_back(i);
  }
  solve_indices(c, indices, e);
}

void sweep_largest(const SweepContext& c, const std::vector<char>& eligible, std::size_t wanted, double saturation,
                   GreedyEstimates& e) {
  require(saturation >= 1.0, "greedy: the saturation constant must be >= 1");
  if (std::isinf(saturation)) return sweep_every_point(c, e);
  std::fill(e.fresh.begin(), e.fresh.end(), 0);
  e.solves = 0;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < c.mus.size(); ++i) {
    if (!c.skip[i]) order.push_back(i);
  }
  // Largest last estimate first (never solved and failed points: +inf); ties to the smaller index.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return e.value[a] > e.value[b]; });
  const std::size_t chunk = kChunk;
  std::size_t next = 0;
  while (next < order.size()) {
    // A point left is solved only while its bound may still exceed the wanted-th fresh value.
    if (saturation * e.value[order[next]] <= wanted_fresh_value(e, eligible, wanted)) break;
    const std::size_t end = std::min(order.size(), next + chunk);
    solve_indices(c, std::vector<std::size_t>(order.begin() + static_cast<std::ptrdiff_t>(next),
                                              order.begin() + static_cast<std::ptrdiff_t>(end)),
                  e);
    next = end;
  }
}

}  // namespace contactrb::offline
