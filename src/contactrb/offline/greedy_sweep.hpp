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
#include <cstddef>
#include <memory>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/model/reduced_model.hpp"
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
};

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
};

// Every point not skipped, with the current model.
void sweep_every_point(const SweepContext& context, GreedyEstimates& estimates);

// The points that may hold the `wanted` largest estimates among those with `eligible` set (and
// every point whose bound exceeds them, eligible or not): see the header comment. saturation >= 1;
// +inf is a full sweep.
void sweep_largest(const SweepContext& context, const std::vector<char>& eligible, std::size_t wanted,
                   double saturation, GreedyEstimates& estimates);

}  // namespace contactrb::offline
