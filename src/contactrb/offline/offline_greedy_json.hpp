#pragma once
// The weak greedy as JSON: greedy.json of `contactrb offline --greedy` (docs/user-guide.md,
// "offline") and model.greedy in Python, from one function. A point is its value for p = 1, an
// object {name: value} otherwise, null when absent.
#include <nlohmann/json.hpp>

#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace contactrb::offline {

// One step: step, snapshots, hf_solves, N, R, Mk, Mg, max_estimate (over the points answered;
// null when none is), argmax_mu, online_failures, chosen_mu, hf_status, true_error, true_e_press,
// batch_mu (the step's HF points, the chosen one first), batch_failures, times_s {build, sweep,
// hf, step}. `request` gives the training points and the parameters' names.
nlohmann::json to_json(const GreedyStep& step, const SnapshotRequest& request);

// The greedy over request.mu under `settings`: case, level, training {set, count}, tolerance,
// max_hf, batch, status, hf_solves, start, selected, excluded, sizes and model {step, snapshots,
// max_estimate, online_failures} (of the model returned, GreedyOfflineResult::offline), steps,
// times_s {start_hf, greedy}.
nlohmann::json greedy_json(const GreedyOfflineResult& result, const SnapshotRequest& request,
                           const GreedyOfflineSettings& settings);

}  // namespace contactrb::offline
