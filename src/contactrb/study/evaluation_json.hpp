#pragma once
// The evaluation as JSON: evaluation.json of `contactrb evaluate` (docs/user-guide.md,
// "evaluate") and the dict of contactrb.evaluate in Python, from one function; a row as JSON
// (the columns of evaluation.csv). Non-finite numbers (an undefined effectivity) are null.
#include <nlohmann/json.hpp>
#include <vector>

#include "contactrb/study/evaluation.hpp"

namespace contactrb::study {

// count, hf_failures, rb_failures, e_ener .. e_peak {max, mean}, e_press_cone {max},
// median_hf_time_s, median_online_time_s, median_speedup, effectivity {count, min, median, max}.
nlohmann::json to_json(const EvaluationSummary& summary);

// One row, keyed as the columns of evaluation.csv: mu (a number for p = 1, else {name: value}),
// hf_converged, hf_status, hf_iterations, hf_time_s, rb_converged, rb_status, rb_iterations,
// online_time_s, speedup, the errors, forces, peaks, energies, e_energy_norm, estimate,
// effectivity.
nlohmann::json to_json(const EvaluationRow& row, const std::vector<cases::ParameterSpec>& parameters);

// evaluation.json but for what only the command knows (the model's path, the set's name, the
// multiplier files): case, level, values, parameters (names), sizes, max_sizes, kacanov,
// online_repeats, jobs, summary.
nlohmann::json evaluation_json(const Evaluation& evaluation, const contactrb::model::ReducedModel& model,
                               const std::vector<cases::Mu>& mus, const EvaluationOptions& options);

}  // namespace contactrb::study
