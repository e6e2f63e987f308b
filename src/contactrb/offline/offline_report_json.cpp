#include "contactrb/offline/offline_report_json.hpp"

#include <vector>

#include "contactrb/online/online_solution_json.hpp"

namespace contactrb::offline {

using model::model_doubles;
using online::sizes_json;

namespace {

nlohmann::json vector_json(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

nlohmann::json size_or_null(int size) { return size >= 1 ? nlohmann::json(size) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json snapshot_set_json(const io::SnapshotSet& set) {
  nlohmann::json j;
  j["case"] = set.case_name;
  j["case_kind"] = set.case_kind;
  j["level"] = set.level;
  j["constraint"] = set.constraint;
  nlohmann::json params = nlohmann::json::array();
  for (const io::SnapshotParameter& q : set.parameters) {
    params.push_back({{"name", q.name}, {"kind", q.kind}, {"units", q.units}, {"min", q.min}, {"max", q.max}});
  }
  if (set.parameters.size() == 1) j["parameter"] = params.front();
  j["parameters"] = params;
  nlohmann::json mus = nlohmann::json::array();
  for (const io::Snapshot& s : set.snapshots) {
    if (s.mu.size() == 1) {
      mus.push_back(s.mu(0));
    } else {
      mus.push_back(std::vector<double>(s.mu.data(), s.mu.data() + s.mu.size()));
    }
  }
  j["training"] = {{"set", set.set_name}, {"values", mus}, {"count", set.snapshots.size()}};
  j["snapshot_solver"] = set.solver;
  j["snapshot_kacanov"] = {{"alpha", set.kacanov_alpha},
                           {"tolerance", set.kacanov_tolerance},
                           {"max_iterations", set.kacanov_max_iterations}};
  return j;
}

nlohmann::json to_json(const OfflineSettings& s) {
  return {{"eps_pod", s.eps_pod},
          {"eps_pod_relative", s.eps_pod_relative},
          {"n", size_or_null(s.pod_modes)},
          {"inner_product", to_string(s.inner_product)},
          {"dual", to_string(s.dual_method)},
          {"eps_du", s.eps_du},
          {"eps_du_relative", s.eps_du_relative},
          {"r", size_or_null(s.dual_size)},
          {"eps_eim_k", s.eps_eim_k},
          {"eps_eim_k_relative", s.eps_eim_k_relative},
          {"eps_eim_g", s.eps_eim_g},
          {"eps_eim_g_relative", s.eps_eim_g_relative},
          {"compression", s.compression},
          {"supremizers", s.supremizers}};
}

nlohmann::json to_json(const OfflineReport& rep, const OfflineSettings& settings) {
  nlohmann::json j;
  j["thresholds"] = {{"pod", settings.pod_modes >= 1 ? nlohmann::json(nullptr) : nlohmann::json(rep.pod_threshold)},
                     {"eim_kappa", rep.eim_kappa_threshold},
                     {"eim_gamma", rep.eim_gamma_threshold}};
  j["pod"] = {{"singular_values", vector_json(rep.singular_values)}, {"N", rep.N_pod}};
  j["supremizers"] = {{"enabled", settings.supremizers}, {"count", rep.N_supremizers}, {"time_s", rep.supremizer_s}};
  j["compression"] = {{"enabled", settings.compression},
                      {"constraints", rep.R_hf},
                      {"kept", rep.R_kept},
                      {"dropped", rep.R_hf - rep.R_kept}};
  j["dual"] = {{"method", to_string(settings.dual_method)},
               {"R", rep.R},
               {"errors", rep.dual_errors},
               {"relative_errors", rep.dual_relative_errors},
               {"status", rep.dual_status},
               {"condition_number", rep.dual_condition_number}};
  j["eim_kappa"] = {{"M", rep.Mk}, {"errors", rep.eim_kappa_errors}, {"status", rep.eim_kappa_status}};
  j["eim_gamma"] = {{"M", rep.Mg}, {"errors", rep.eim_gamma_errors}, {"status", rep.eim_gamma_status}};
  j["times_s"] = {{"assembly", rep.assembly_s}, {"pod", rep.pod_s},
                  {"dual", rep.dual_s},         {"eim_kappa", rep.eim_kappa_s},
                  {"eim_gamma", rep.eim_gamma_s}, {"reduction", rep.reduction_s},
                  {"build", rep.total_s}};
  return j;
}

nlohmann::json offline_json(const io::SnapshotSet& set, const OfflineSettings& settings, const OfflineResult& result) {
  nlohmann::json j = snapshot_set_json(set);
  j.update(to_json(result.report, settings));
  j["settings"] = to_json(settings);
  j["sizes"] = sizes_json(result.model);
  j["model_doubles"] = model_doubles(result.model);
  return j;
}

}  // namespace contactrb::offline
