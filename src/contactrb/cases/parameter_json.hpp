#pragma once
// A parameter point as JSON (docs/user-guide.md: solution.json, online answers, offline.json,
// greedy.json, evaluation.json).
#include <nlohmann/json.hpp>
#include <vector>

#include "contactrb/cases/parameter.hpp"

namespace contactrb::cases {

// A number for p = 1, an object {"name": value, ...} in the order of `parameters` otherwise
// (a value beyond `parameters` is named by its index).
nlohmann::json mu_json(const std::vector<ParameterSpec>& parameters, const Mu& mu);

}  // namespace contactrb::cases
