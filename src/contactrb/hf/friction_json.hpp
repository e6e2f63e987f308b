#pragma once
// A frictional solve as JSON (docs/solvers.md, "Friction"): the keys a frictional solution.json
// takes from the solver; a command adds the run's own (case, mesh, settings).
#include <nlohmann/json.hpp>

#include "contactrb/hf/friction.hpp"

namespace contactrb::hf {

// {law, friction_coefficient (Coulomb) or slip_threshold (Tresca)}
nlohmann::json to_json(const FrictionSettings& settings);

// {status, message (when there is one), iterations, residuals, stick_nodes, slip_nodes,
// open_nodes, contact_force, tangential_force, time_s}
nlohmann::json to_json(const FrictionStepReport& step);

// converged, status, message (when there is one), steps (one object per load step), contact_force,
// tangential_force (2D: the signed force on the slave along tau; 3D: the array [F_1, F_2] of
// F_j = sum_r lambda_t,r,j |I_r|, along each row's tangents tau_j (contact::tangent_basis: on a
// master of normal near +z, close to x and y)),
// stick_nodes, slip_nodes, kkt {stationarity, primal, dual, complementarity, friction}, time_s.
template <int Dim>
nlohmann::json to_json(const BasicFrictionalSolution<Dim>& solution);

extern template nlohmann::json to_json(const BasicFrictionalSolution<2>&);
extern template nlohmann::json to_json(const BasicFrictionalSolution<3>&);

}  // namespace contactrb::hf
