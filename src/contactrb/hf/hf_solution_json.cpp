#include "contactrb/hf/hf_solution_json.hpp"

namespace contactrb::hf {

nlohmann::json to_json(const HFKKT& kkt) {
  return {{"stationarity", kkt.stationarity},
          {"primal", kkt.primal},
          {"dual", kkt.dual},
          {"complementarity", kkt.complementarity}};
}

template <int Dim>
nlohmann::json to_json(const BasicHFSolution<Dim>& s) {
  nlohmann::json j;
  j["converged"] = s.converged;
  j["status"] = solve::to_string(s.status);
  if (!s.message.empty()) j["message"] = s.message;
  j["iterations"] = s.iterations;
  nlohmann::json du = nlohmann::json::array(), dl = nlohmann::json::array();
  for (const solve::KacanovIteration& it : s.history) {
    du.push_back(it.du);
    dl.push_back(it.dlambda);
  }
  j["increments"] = {{"displacement", du}, {"multipliers", dl}};
  if (s.method == HFMethod::Newton) {
    nlohmann::json residuals = nlohmann::json::array();
    for (const NewtonIteration& it : s.newton_history) residuals.push_back(it.residual);
    j["newton_residuals"] = residuals;
  }
  j["energy"] = s.energy;
  j["contact_force"] = s.contact_force;
  j["active_constraints"] = s.active_constraints;
  j["kkt"] = to_json(s.kkt);
  j["gap_violation"] = s.gap_violation;
  j["time_s"] = s.time_s;
  return j;
}

template <int Dim>
nlohmann::json discretization_json(const BasicHFSolver<Dim>& solver) {
  return {{"constraint", contact::to_string(solver.problem().discretization)},
          {"setup_time_s", solver.setup_time_s()},
          {"n_dofs", solver.problem().mesh.num_dofs()},
          {"n_free_dofs", solver.dofs().num_free()},
          {"n_constraints", static_cast<int>(solver.quadrature().weight.size())}};
}

template nlohmann::json to_json(const BasicHFSolution<2>&);
template nlohmann::json to_json(const BasicHFSolution<3>&);
template nlohmann::json discretization_json(const BasicHFSolver<2>&);
template nlohmann::json discretization_json(const BasicHFSolver<3>&);

}  // namespace contactrb::hf
