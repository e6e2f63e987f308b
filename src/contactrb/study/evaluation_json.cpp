#include "contactrb/study/evaluation_json.hpp"

#include <cmath>

#include "contactrb/cases/parameter_json.hpp"
#include "contactrb/online/online_solution_json.hpp"

namespace contactrb::study {

using model::ReducedModel;
using online::sizes_json;

namespace {

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json to_json(const EvaluationSummary& s) {
  return {{"count", s.count},
          {"hf_failures", s.hf_failures},
          {"rb_failures", s.rb_failures},
          {"e_ener", {{"max", s.max_e_ener}, {"mean", s.mean_e_ener}}},
          {"e_displ", {{"max", s.max_e_displ}, {"mean", s.mean_e_displ}}},
          {"e_inter", {{"max", s.max_e_inter}, {"mean", s.mean_e_inter}}},
          {"e_press", {{"max", s.max_e_press}, {"mean", s.mean_e_press}}},
          {"e_force", {{"max", s.max_e_force}, {"mean", s.mean_e_force}}},
          {"e_peak", {{"max", s.max_e_peak}, {"mean", s.mean_e_peak}}},
          {"e_press_cone", {{"max", s.max_e_press_cone}}},
          {"median_hf_time_s", s.median_hf_time_s},
          {"median_online_time_s", s.median_online_time_s},
          {"median_speedup", s.median_speedup},
          {"effectivity",
           {{"count", s.effectivity_count},
            {"min", finite_or_null(s.min_effectivity)},
            {"median", finite_or_null(s.median_effectivity)},
            {"max", finite_or_null(s.max_effectivity)}}}};
}

nlohmann::json to_json(const EvaluationRow& r, const std::vector<cases::ParameterSpec>& parameters) {
  return {{"mu", cases::mu_json(parameters, r.mu)},
          {"hf_converged", r.hf_converged},
          {"hf_status", r.hf_status},
          {"hf_iterations", r.hf_iterations},
          {"hf_time_s", r.hf_time_s},
          {"rb_converged", r.rb_converged},
          {"rb_status", r.rb_status},
          {"rb_iterations", r.rb_iterations},
          {"online_time_s", r.online_time_s},
          {"speedup", finite_or_null(r.speedup)},
          {"e_ener", finite_or_null(r.e_ener)},
          {"e_displ", finite_or_null(r.e_displ)},
          {"e_inter", finite_or_null(r.e_inter)},
          {"e_press", finite_or_null(r.e_press)},
          {"e_force", finite_or_null(r.e_force)},
          {"e_peak", finite_or_null(r.e_peak)},
          {"e_press_cone", finite_or_null(r.e_press_cone)},
          {"force_hf", r.force_hf},
          {"force_rb", r.force_rb},
          {"peak_hf", r.peak_hf},
          {"peak_rb", r.peak_rb},
          {"energy_hf", r.energy_hf},
          {"energy_rb", r.energy_rb},
          {"e_energy_norm", finite_or_null(r.e_energy_norm)},
          {"estimate", finite_or_null(r.estimate)},
          {"effectivity", finite_or_null(r.effectivity)}};
}

nlohmann::json evaluation_json(const Evaluation& e, const ReducedModel& model, const std::vector<cases::Mu>& mus,
                               const EvaluationOptions& options) {
  nlohmann::json j;
  j["case"] = model.case_name;
  j["level"] = model.level;
  nlohmann::json values = nlohmann::json::array();
  for (const cases::Mu& mu : mus) values.push_back(cases::mu_json(model.parameters, mu));
  j["values"] = values;
  nlohmann::json names = nlohmann::json::array();
  for (const cases::ParameterSpec& p : model.parameters) names.push_back(p.name);
  j["parameters"] = names;
  j["sizes"] = {{"N", e.N}, {"R", e.R}, {"Mk", e.Mk}, {"Mg", e.Mg}};
  j["max_sizes"] = sizes_json(model);
  j["kacanov"] = {{"alpha", model.kacanov_alpha},
                  {"tolerance", model.kacanov_tolerance},
                  {"max_iterations", model.kacanov_max_iterations}};
  j["iteration"] = online::to_string(options.online.iteration);
  j["online_repeats"] = options.online_repeats;
  j["jobs"] = options.jobs;
  j["hf_solver"] = hf::to_string(options.hf_method);
  j["hf_sequence"] = e.hf_sequence;
  j["summary"] = to_json(e.summary);
  return j;
}

}  // namespace contactrb::study
