#include "contactrb/cases/level_sequence_json.hpp"

namespace contactrb::cases {

nlohmann::json to_json(const SequenceStage& stage) {
  return {{"level", stage.level},
          {"n_dofs", stage.dofs},
          {"iterations", stage.iterations},
          {"converged", stage.converged},
          {"time_s", stage.mesh_s + stage.solve_s + stage.transfer_s}};
}

nlohmann::json to_json(const SequenceStart& start) {
  nlohmann::json stages = nlohmann::json::array();
  for (const SequenceStage& stage : start.stages) stages.push_back(to_json(stage));
  return {{"sequence", stages}, {"sequence_time_s", start.time_s}};
}

}  // namespace contactrb::cases
