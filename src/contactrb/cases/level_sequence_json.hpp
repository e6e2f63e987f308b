#pragma once
// Grid sequencing as JSON: the keys "sequence" and "sequence_time_s" of solution.json
// (docs/user-guide.md, "solve").
#include <nlohmann/json.hpp>

#include "contactrb/cases/level_sequence.hpp"

namespace contactrb::cases {

// {level, n_dofs, iterations, converged, time_s (mesh, solve and transfer)}
nlohmann::json to_json(const SequenceStage& stage);

// {"sequence": [stage, ...], "sequence_time_s": ...}: the coarse solves that chose the fine
// solve's starting point (their iterations and time are not the fine solve's).
nlohmann::json to_json(const SequenceStart& start);

}  // namespace contactrb::cases
