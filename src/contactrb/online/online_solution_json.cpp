#include "contactrb/online/online_solution_json.hpp"

#include "contactrb/cases/parameter_json.hpp"

namespace contactrb::online {

using model::ReducedModel;

namespace {

nlohmann::json vector_json(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

}  // namespace

nlohmann::json to_json(const ErrorEstimate& e) {
  if (!e.available) return nullptr;
  return {{"energy", e.energy},
          {"residual", e.residual},
          {"coercivity", e.coercivity},
          {"violation", e.violation},
          {"complementarity", e.complementarity},
          {"multiplier_norm", e.multiplier_norm},
          {"eim_residual", e.eim_residual},
          {"eim_slack", e.eim_slack},
          {"geometric", e.geometric},
          {"correction", e.correction}};
}

nlohmann::json to_json(const OnlineSolution& s) {
  nlohmann::json j;
  j["converged"] = s.converged();
  j["status"] = solve::to_string(s.status);
  if (!s.message.empty()) j["message"] = s.message;
  j["iterations"] = s.iterations;
  j["energy"] = s.energy;
  j["contact_force"] = s.contact_force;
  j["time_s"] = s.time_s;
  j["estimate"] = to_json(s.estimate);
  j["u_hat"] = vector_json(s.u_hat);
  j["lambda_hat"] = vector_json(s.lambda_hat);
  return j;
}

nlohmann::json sizes_json(const OnlineSolver& solver) {
  return {{"N", solver.N()}, {"R", solver.R()}, {"Mk", solver.Mk()}, {"Mg", solver.Mg()}};
}

nlohmann::json sizes_json(const ReducedModel& model) {
  return {{"N", model.N_max}, {"R", model.R_max}, {"Mk", model.Mk_max}, {"Mg", model.Mg_max}};
}

nlohmann::json answer_json(const std::vector<cases::ParameterSpec>& parameters, const cases::Mu& mu,
                           const OnlineSolver& solver, const OnlineSolution& solution) {
  nlohmann::json j = to_json(solution);
  j["mu"] = cases::mu_json(parameters, mu);
  j["sizes"] = sizes_json(solver);
  return j;
}

}  // namespace contactrb::online
