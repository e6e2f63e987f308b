#include "contactrb/offline/offline_greedy_json.hpp"

#include <cmath>
#include <vector>

#include "contactrb/online/online_solution_json.hpp"

namespace contactrb::offline {

using online::sizes_json;

namespace {

nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json point_json(const SnapshotRequest& request, const cases::Mu& mu) {
  if (mu.size() == 0) return nullptr;
  if (mu.size() == 1) return mu(0);
  nlohmann::json o = nlohmann::json::object();
  for (std::size_t k = 0; k < request.parameters.size(); ++k) o[request.parameters[k].name] = mu(static_cast<Eigen::Index>(k));
  return o;
}

// The training points of `indices`, in their order.
nlohmann::json points_json(const SnapshotRequest& request, const std::vector<int>& indices) {
  nlohmann::json a = nlohmann::json::array();
  for (int i : indices) a.push_back(point_json(request, request.mu[static_cast<std::size_t>(i)]));
  return a;
}

}  // namespace

nlohmann::json to_json(const GreedyStep& r, const SnapshotRequest& request) {
  return {{"step", r.step},
          {"snapshots", r.snapshots},
          {"hf_solves", r.hf_solves},
          {"N", r.N},
          {"R", r.R},
          {"Mk", r.Mk},
          {"Mg", r.Mg},
          {"max_estimate", finite_or_null(r.max_estimate)},
          {"argmax_mu", point_json(request, r.argmax_mu)},
          {"online_failures", r.online_failures},
          {"chosen_mu", point_json(request, r.chosen_mu)},
          {"hf_status", r.hf_status},
          {"true_error", finite_or_null(r.true_error)},
          {"true_e_press", finite_or_null(r.true_e_press)},
          {"batch_mu", points_json(request, r.batch_points)},
          {"batch_failures", r.batch_failures},
          {"sweep_solves", r.sweep_solves},
          {"sweep_iterations", r.sweep_iterations},
          {"times_s", {{"build", r.build_s}, {"sweep", r.sweep_s}, {"hf", r.hf_s}, {"step", r.step_s}}}};
}

nlohmann::json greedy_json(const GreedyOfflineResult& g, const SnapshotRequest& request,
                           const GreedyOfflineSettings& settings) {
  nlohmann::json j;
  j["case"] = request.case_name;
  j["level"] = request.level;
  j["training"] = {{"set", request.set_name}, {"count", request.mu.size()}};
  j["tolerance"] = settings.tolerance;
  j["max_hf"] = settings.max_hf;
  j["batch"] = settings.batch;
  j["saturation"] = finite_or_null(settings.saturation);
  j["status"] = to_string(g.status);
  j["hf_solves"] = g.hf_solves;
  j["start"] = point_json(request, request.mu[static_cast<std::size_t>(g.start)]);
  j["selected"] = points_json(request, g.selected);
  j["excluded"] = points_json(request, g.excluded);
  j["sizes"] = sizes_json(g.offline.model);
  const GreedyStep& model = g.steps[static_cast<std::size_t>(g.model_step - 1)];
  j["model"] = {{"step", model.step}, {"snapshots", model.snapshots}, {"max_estimate", finite_or_null(model.max_estimate)},
                {"online_failures", model.online_failures}};
  nlohmann::json steps = nlohmann::json::array();
  for (const GreedyStep& step : g.steps) steps.push_back(to_json(step, request));
  j["steps"] = steps;
  j["times_s"] = {{"start_hf", g.start_hf_s}, {"greedy", g.total_s}};
  return j;
}

}  // namespace contactrb::offline
