#pragma once
// The online answer as JSON: the object `contactrb online --mu` prints and each JSON line of
// `--batch` (docs/user-guide.md, "online"); Model.solve's estimate_parts in Python.
#include <nlohmann/json.hpp>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::online {

// The estimate of |u_hf - u_rb|_A(mu) and its parts (docs/offline-online.md): {energy, residual,
// coercivity, violation, complementarity, multiplier_norm, eim_residual, eim_slack}; null when
// not available (a failed solve, or a model without estimate data).
nlohmann::json to_json(const ErrorEstimate& estimate);

// converged, status, message (when there is one), iterations, energy, contact_force, time_s,
// estimate, u_hat, lambda_hat.
nlohmann::json to_json(const OnlineSolution& solution);

// {N, R, Mk, Mg}: the sizes a solver uses, or a model's maxima.
nlohmann::json sizes_json(const OnlineSolver& solver);
nlohmann::json sizes_json(const contactrb::model::ReducedModel& model);

// The answer at mu: the solution's keys, "mu" (a number for p = 1, else {name: value}) and
// "sizes".
nlohmann::json answer_json(const std::vector<cases::ParameterSpec>& parameters, const cases::Mu& mu,
                           const OnlineSolver& solver, const OnlineSolution& solution);

}  // namespace contactrb::online
