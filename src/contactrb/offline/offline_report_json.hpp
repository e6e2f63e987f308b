#pragma once
// The offline stage as JSON: offline.json of `contactrb offline` (docs/user-guide.md,
// "offline") and Model.report in Python, from one function.
#include <nlohmann/json.hpp>

#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/offline/offline_builder.hpp"

namespace contactrb::offline {

// The snapshot set a model is built from: case, case_kind, level, constraint, parameters (and
// parameter when there is one), training {set, values, count}, snapshot_kacanov.
nlohmann::json snapshot_set_json(const io::SnapshotSet& set);

// The settings as given: eps_pod, eps_pod_relative, n (null: --eps-pod decides), inner_product,
// dual, eps_du, eps_du_relative, r (null: --eps-du decides), eps_eim_k(_relative),
// eps_eim_g(_relative), compression, supremizers.
nlohmann::json to_json(const OfflineSettings& settings);

// Each step's outcome under `settings`: thresholds (the absolute values the tolerances came to;
// pod null for a fixed N), pod, supremizers, compression, dual, eim_kappa, eim_gamma, and
// times_s of the build's steps (assembly, pod, dual, eim_kappa, eim_gamma, reduction, build).
nlohmann::json to_json(const OfflineReport& report, const OfflineSettings& settings);

// offline.json but for what only the command knows (the file paths, its reading or computing
// of the snapshots, its writing of the model): the set, settings, report, the model's sizes and
// model_doubles.
nlohmann::json offline_json(const io::SnapshotSet& set, const OfflineSettings& settings, const OfflineResult& result);

}  // namespace contactrb::offline
