#include "contactrb/offline/greedy_sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>

#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"
#include "contactrb/common/run_threads.hpp"
#include "contactrb/offline/offline_greedy.hpp"

namespace contactrb::offline {

using online::OnlineSettings;
using online::OnlineSolution;
using online::OnlineSolver;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Points solved per chunk of a lazy sweep: enough to keep two threads busy, few enough that a
// chunk rarely goes far past the cut. Fixed, not per thread: the points a lazy sweep solves, and
// so the greedy's picks, do not depend on the thread or process count.
constexpr std::size_t kChunk = 16;

// The sweep's answer at each of its points, one record of `width` numbers a point (so that a
// distributed sweep gathers it in one piece): the criterion, 1 when the online solve did not
// converge, its iterations, and its [u_hat; lambda_hat] (zero when it did not converge).
struct Sweep {
  Sweep(std::size_t points, const model::ReducedModel& model)
      : width(3 + sz(model.N_max) + sz(model.online_R_max())), records(points * width, 0.0) {
    for (std::size_t i = 0; i < points; ++i) records[i * width] = kInf;
  }
  double criterion(std::size_t i) const { return records[i * width]; }
  bool failed(std::size_t i) const { return records[i * width + 1] != 0.0; }
  long long iterations(std::size_t i) const { return static_cast<long long>(records[i * width + 2]); }
  Eigen::Map<const Eigen::VectorXd> solution(std::size_t i) const {
    return {records.data() + i * width + 3, static_cast<Eigen::Index>(width - 3)};
  }
  void set(std::size_t i, double criterion, const OnlineSolution& s) {
    double* r = records.data() + i * width;
    r[0] = criterion;
    r[1] = s.converged() ? 0.0 : 1.0;
    r[2] = s.iterations;
    if (!s.converged()) return;
    Eigen::Map<Eigen::VectorXd> x(r + 3, static_cast<Eigen::Index>(width - 3));
    x << s.u_hat, s.lambda_hat;
  }
  std::size_t width;
  std::vector<double> records;
};

using SolverPool = std::vector<std::unique_ptr<OnlineSolver>>;

// How each point is solved (SweepContext::online and ::fallback).
struct SweepSolve {
  const OnlineSettings& online;
  const OnlineSettings* fallback;
};

// The solve at mu from `start` when there is one; where that does not converge, again from the
// solver's own start, so that a warm start never turns an answered point into a failure (the
// iterations of both are counted).
OnlineSolution solve_from(OnlineSolver& solver, const cases::Mu& mu, OnlineSettings& settings,
                          const Eigen::VectorXd* start) {
  if (start == nullptr || start->size() == 0) {
    settings.start.reset();
    return solver.solve(mu, settings);
  }
  settings.start = *start;
  OnlineSolution warm = solver.solve(mu, settings);
  if (warm.converged()) return warm;
  settings.start.reset();
  OnlineSolution cold = solver.solve(mu, settings);
  cold.iterations += warm.iterations;
  return cold;
}

// The criterion at some points (online solves only), `jobs` threads with one OnlineSolver each;
// every point writes its own record, so the result does not depend on jobs. Only [begin, end) is
// solved (one process's block); the others keep +inf / not failed. starts: one per point (empty:
// none), or nullptr.
void sweep_block(const model::ReducedModel& model, const std::vector<cases::Mu>& mus,
                 const std::vector<const Eigen::VectorXd*>& starts, const SweepSolve& how, int jobs,
                 std::size_t begin, std::size_t end, SolverPool* pool, Sweep& out) {
  std::vector<std::exception_ptr> errors(mus.size());
  std::atomic<std::size_t> next{begin};
  std::atomic<bool> stop{false};
  const auto work = [&](std::size_t t, std::exception_ptr& own_setup_error) {
    try {
      std::unique_ptr<OnlineSolver> own;
      std::unique_ptr<OnlineSolver>& slot = pool ? (*pool)[t] : own;
      if (!slot) slot = std::make_unique<OnlineSolver>(model);
      OnlineSolver& solver = *slot;
      OnlineSettings settings = how.online;
      std::optional<OnlineSettings> fallback;
      if (how.fallback) fallback = *how.fallback;
      for (std::size_t i = next.fetch_add(1); i < end && !stop; i = next.fetch_add(1)) {
        try {
          const OnlineSolution s = solve_point(solver, mus[i], settings, fallback ? &*fallback : nullptr, starts[i]);
          out.set(i, relative_estimate(model, mus[i], s), s);
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
}

// The sweep over `mus`: on this process alone, or its block on each process of a distributed
// run, then gathered (every process gets the same records).
Sweep sweep_points(const model::ReducedModel& model, const std::vector<cases::Mu>& mus,
                   const std::vector<const Eigen::VectorXd*>& starts, const SweepSolve& how, int jobs,
                   const GreedyDistribution& dist, SolverPool* pool) {
  Sweep out(mus.size(), model);
  if (!dist.active()) {
    sweep_block(model, mus, starts, how, jobs, 0, mus.size(), pool, out);
    return out;
  }
  const auto [begin, end] = dist.block(mus.size());
  std::exception_ptr error;
  try {
    sweep_block(model, mus, starts, how, jobs, begin, end, pool, out);
  } catch (...) {  // the other processes wait in the gather: tell them first
    error = std::current_exception();
  }
  const bool all_ok = dist.gather(out.records, out.width, !error);
  if (error) std::rethrow_exception(error);
  require(all_ok, "greedy: the estimate sweep failed on another MPI rank (its error is printed there)");
  return out;
}

// Solves the training points `indices` with the current model and records them.
void solve_indices(const SweepContext& c, const std::vector<std::size_t>& indices, GreedyEstimates& e) {
  std::vector<cases::Mu> mus;
  std::vector<const Eigen::VectorXd*> starts;
  mus.reserve(indices.size());
  if (e.start.size() != c.mus.size()) e.start.assign(c.mus.size(), Eigen::VectorXd());
  for (std::size_t i : indices) {
    mus.push_back(c.mus[i]);
    starts.push_back(c.warm_start ? &e.start[i] : nullptr);
  }
  const Sweep s = sweep_points(c.model, mus, starts, {c.online, c.fallback}, c.jobs, c.distribution, c.solvers);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const std::size_t i = indices[k];
    e.value[i] = s.failed(k) ? kInf : s.criterion(k);
    e.failed[i] = s.failed(k) ? 1 : 0;
    e.fresh[i] = 1;
    e.iterations += s.iterations(k);
    if (s.failed(k)) {
      e.start[i].resize(0);
    } else {
      e.start[i] = s.solution(k);
    }
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

// For each column of `before`, the column of `after` equal to it bit for bit, or nullopt when
// one has none.
std::optional<std::vector<int>> column_map(const Eigen::MatrixXd& before, const Eigen::MatrixXd& after) {
  if (before.rows() != after.rows()) return std::nullopt;
  std::vector<int> map;
  for (Eigen::Index j = 0; j < before.cols(); ++j) {
    Eigen::Index k = 0;
    while (k < after.cols() && !(after.col(k).array() == before.col(j).array()).all()) ++k;
    if (k == after.cols()) return std::nullopt;
    map.push_back(static_cast<int>(k));
  }
  return map;
}

// The cone's generators as columns over every constraint row (Xi on the kept rows, zero elsewhere).
Eigen::MatrixXd generators_on_all_rows(const model::ReducedReconstruction& r) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(r.num_constraints, r.Xi.cols());
  for (std::size_t i = 0; i < r.kept_rows.size(); ++i) G.row(r.kept_rows[i]) = r.Xi.row(ix(i));
  return G;
}

}  // namespace

OnlineSolution solve_point(OnlineSolver& solver, const cases::Mu& mu, OnlineSettings& settings,
                           OnlineSettings* fallback, const Eigen::VectorXd* start) {
  OnlineSolution first = solve_from(solver, mu, settings, start);
  if (first.converged() || fallback == nullptr) return first;
  OnlineSolution second = solve_from(solver, mu, *fallback, start);
  second.iterations += first.iterations;
  return second;
}

std::optional<CoordinateMap> coordinate_map(const OfflineResult& before, const OfflineResult& after) {
  const model::ReducedReconstruction &a = before.reconstruction, &b = after.reconstruction;
  // A registered cone's generators depend on mu (Xi(mu)): no fixed map.
  if (a.Theta.cols() == 0 || !a.registration.empty() || !b.registration.empty()) return std::nullopt;
  if (a.num_constraints != b.num_constraints) return std::nullopt;
  std::optional<std::vector<int>> primal = column_map(a.Theta, b.Theta);
  if (!primal) return std::nullopt;
  std::optional<std::vector<int>> dual = column_map(generators_on_all_rows(a), generators_on_all_rows(b));
  if (!dual) return std::nullopt;
  return CoordinateMap{std::move(*primal), std::move(*dual), after.model.N_max, after.model.online_R_max()};
}

void carry_starts(const std::optional<CoordinateMap>& map, GreedyEstimates& e) {
  for (Eigen::VectorXd& x : e.start) {
    const auto N = static_cast<Eigen::Index>(map ? map->primal.size() : 0);
    const auto R = static_cast<Eigen::Index>(map ? map->dual.size() : 0);
    if (!map || x.size() != N + R) {
      x.resize(0);
      continue;
    }
    Eigen::VectorXd y = Eigen::VectorXd::Zero(map->N + map->R);
    for (Eigen::Index n = 0; n < N; ++n) y(map->primal[sz(n)]) = x(n);
    for (Eigen::Index r = 0; r < R; ++r) y(map->N + map->dual[sz(r)]) = x(N + r);
    x = std::move(y);
  }
}

GreedyEstimates::GreedyEstimates(std::size_t points)
    : value(points, std::numeric_limits<double>::infinity()), failed(points, 0), fresh(points, 0) {}

void sweep_every_point(const SweepContext& c, GreedyEstimates& e) {
  std::fill(e.fresh.begin(), e.fresh.end(), 0);
  e.solves = 0;
  e.iterations = 0;
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < c.mus.size(); ++i) {
    if (!c.skip[i]) indices.push_back(i);
  }
  solve_indices(c, indices, e);
}

void sweep_stale(const SweepContext& c, GreedyEstimates& e) {
  e.solves = 0;
  e.iterations = 0;
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < c.mus.size(); ++i) {
    if (!c.skip[i] && !e.fresh[i]) indices.push_back(i);
  }
  solve_indices(c, indices, e);
}

void sweep_largest(const SweepContext& c, const std::vector<char>& eligible, std::size_t wanted, double saturation,
                   GreedyEstimates& e) {
  require(saturation >= 1.0, "greedy: the saturation constant must be >= 1");
  if (std::isinf(saturation)) return sweep_every_point(c, e);
  std::fill(e.fresh.begin(), e.fresh.end(), 0);
  e.solves = 0;
  e.iterations = 0;
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
