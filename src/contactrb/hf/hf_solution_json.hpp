#pragma once
// The HF solve as JSON: the keys of `contactrb solve`'s solution.json (docs/user-guide.md, "solve")
// that the solve and its solver give. The command adds the run's own (case, mu, level,
// settings, grid sequencing).
#include <nlohmann/json.hpp>

#include "contactrb/hf/hf_solver.hpp"

namespace contactrb::hf {

// {stationarity, primal, dual, complementarity}
nlohmann::json to_json(const HFKKT& kkt);

// converged, status, message (when there is one), iterations, increments {displacement,
// multipliers} (Kacanov, one per iteration), newton_residuals (Newton: the KKT residual before
// each step), energy, contact_force, active_constraints, kkt, gap_violation, time_s.
template <int Dim>
nlohmann::json to_json(const BasicHFSolution<Dim>& solution);

// The discretization the solver set up: constraint, n_dofs, n_free_dofs, n_constraints and
// setup_time_s.
template <int Dim>
nlohmann::json discretization_json(const BasicHFSolver<Dim>& solver);

extern template nlohmann::json to_json(const BasicHFSolution<2>&);
extern template nlohmann::json to_json(const BasicHFSolution<3>&);
extern template nlohmann::json discretization_json(const BasicHFSolver<2>&);
extern template nlohmann::json discretization_json(const BasicHFSolver<3>&);

}  // namespace contactrb::hf
