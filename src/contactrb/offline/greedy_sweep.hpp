#pragma once
// The estimate sweep of a greedy step (offline_greedy.hpp): the relative estimate of the current
// reduced model at the training points, online solves only.
//
// A full sweep solves every point. A lazy sweep (Hesthaven, Stamm, Zhang, M2AN 48, 2014: the
// saturation assumption) keeps each point's last estimate as a bound: if the estimate of a point
// grows by at most the factor `saturation` when the model is enriched, a point whose last estimate
// times `saturation` is below the `wanted`-th largest fresh value cannot be among the `wanted`
// largest, and is not solved. The points are solved in decreasing order of their last estimate,
// in chunks, until that holds for every point left (docs/offline-online.md, "Greedy sampling").
//
// Warm starts: each point's last reduced solution, carried into the next model's coordinates
// when that model extends the last one (every basis column and cone generator kept as it was),
// is the start of its next solve (OnlineSettings::start); a point without one, or whose warm
// solve does not converge, starts as any online solve does.
//
// Fallback: a point whose solve does not converge from either start is solved again, from both,
// with SweepContext::fallback (the row-cone greedy: the accelerated iteration first, the reduced
// Newton where it does not converge), so that the cheaper iteration never turns a point the
// other answers into a failure.
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"

namespace contactrb::offline {

struct GreedyDistribution;

// The training points' estimates across the steps of one greedy.
struct GreedyEstimates {
  explicit GreedyEstimates(std::size_t points);
  std::vector<double> value;  // last relative estimate of each point; +inf: never solved, or failed
  std::vector<char> failed;   // 1: the last online solve there did not converge
  std::vector<char> fresh;    // 1: value is the current model's
  int solves = 0;             // online solves of the last sweep
  long long iterations = 0;   // their reduced iterations (OnlineSolution::iterations, every attempt), summed
  // Per point: its last converged [u_hat; lambda_hat] in the current model's coordinates, the
  // start of its next solve; empty: none.
  std::vector<Eigen::VectorXd> start;
};

// Where one model's reduced coordinates sit in the next model's: column n of the first basis is
// column primal[n] of the next, generator r of the first cone is generator dual[r] of the next.
struct CoordinateMap {
  std::vector<int> primal, dual;
  int N = 0, R = 0;  // the next model's sizes
};

// The map from `before` to `after` when every basis column and cone generator of `before` is,
// bit for bit, one of `after`'s (an extension build, OfflineSettings::extend_basis); nullopt
// otherwise (a POD rebuild, a registered cone). Then u = Theta u_hat is the same field in both.
std::optional<CoordinateMap> coordinate_map(const OfflineResult& before, const OfflineResult& after);

// The points' starts mapped into the next model's coordinates (zero in its new directions),
// or dropped when there is no map.
void carry_starts(const std::optional<CoordinateMap>& map, GreedyEstimates& estimates);

// What a sweep solves over: the model, the training points and how.
struct SweepContext {
  const model::ReducedModel& model;
  const std::vector<cases::Mu>& mus;
  const online::OnlineSettings& online;
  int jobs = 1;
  const GreedyDistribution& distribution;
  const std::vector<char>& skip;  // 1: no longer a training point (its HF solve failed)
  // One solver of `model` per thread, built at the first chunk that needs it and kept for the
  // sweep's other chunks (its setup factors the estimate's columns: several online solves' worth).
  // nullptr: each chunk builds its own.
  std::vector<std::unique_ptr<online::OnlineSolver>>* solvers = nullptr;
  // Start each point from GreedyEstimates::start where it has one.
  bool warm_start = true;
  // Where `online` does not converge at a point (from its start, then from the solver's own):
  // the same again with these settings. nullptr: none.
  const online::OnlineSettings* fallback = nullptr;
};

// One point of a sweep: the solve at mu with `settings` from `start` (empty or nullptr: the
// solver's own start), again from the solver's own start where that does not converge, and the
// same two with `fallback` (when not nullptr) where neither converges; the iterations of every
// attempt are counted. settings.start and fallback->start are overwritten.
online::OnlineSolution solve_point(online::OnlineSolver& solver, const cases::Mu& mu, online::OnlineSettings& settings,
                                   online::OnlineSettings* fallback, const Eigen::VectorXd* start);

// Every point not skipped, with the current model.
void sweep_every_point(const SweepContext& context, GreedyEstimates& estimates);

// Every point not skipped whose estimate is not fresh (the rest of a lazy sweep): afterwards
// every estimate is the current model's.
void sweep_stale(const SweepContext& context, GreedyEstimates& estimates);

// The points that may hold the `wanted` largest estimates among those with `eligible` set (and
// every point whose bound exceeds them, eligible or not): see the header comment. saturation >= 1;
// +inf is a full sweep.
void sweep_largest(const SweepContext& context, const std::vector<char>& eligible, std::size_t wanted,
                   double saturation, GreedyEstimates& estimates);

}  // namespace contactrb::offline
