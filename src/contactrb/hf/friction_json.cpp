#include "contactrb/hf/friction_json.hpp"

#include "contactrb/hf/hf_solution_json.hpp"

namespace contactrb::hf {

namespace {
// One number in 2D, an array of the Dim - 1 tangential components otherwise.
nlohmann::json tangential(const Eigen::VectorXd& force) {
  if (force.size() == 1) return force(0);
  return std::vector<double>(force.data(), force.data() + force.size());
}
}  // namespace

nlohmann::json to_json(const FrictionSettings& s) {
  nlohmann::json j{{"law", to_string(s.law)}};
  if (s.law == FrictionLaw::Coulomb) {
    j["friction_coefficient"] = s.coefficient;
  } else {
    j["slip_threshold"] = s.threshold;
  }
  return j;
}

nlohmann::json to_json(const FrictionStepReport& r) {
  nlohmann::json j{{"status", to_string(r.status)}};
  if (!r.message.empty()) j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["residuals"] = r.residuals;
  j["stick_nodes"] = r.stick;
  j["slip_nodes"] = r.slip;
  j["open_nodes"] = r.open;
  j["contact_force"] = r.normal_force;
  j["tangential_force"] = tangential(r.tangential_force);
  j["time_s"] = r.time_s;
  return j;
}

template <int Dim>
nlohmann::json to_json(const BasicFrictionalSolution<Dim>& s) {
  nlohmann::json j;
  j["converged"] = s.converged;
  j["status"] = to_string(s.status);
  if (!s.message.empty()) j["message"] = s.message;
  nlohmann::json steps = nlohmann::json::array();
  for (const FrictionStepReport& r : s.steps) steps.push_back(to_json(r));
  j["steps"] = steps;
  j["contact_force"] = s.contact_force;
  j["tangential_force"] = tangential(s.tangential_force);
  j["stick_nodes"] = s.stick_nodes;
  j["slip_nodes"] = s.slip_nodes;
  nlohmann::json kkt = to_json(s.kkt.normal);
  kkt["friction"] = s.kkt.friction;
  j["kkt"] = kkt;
  j["time_s"] = s.time_s;
  return j;
}

template nlohmann::json to_json(const BasicFrictionalSolution<2>&);
template nlohmann::json to_json(const BasicFrictionalSolution<3>&);

}  // namespace contactrb::hf
