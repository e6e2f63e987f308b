#include "contactrb/cases/parameter_json.hpp"

#include <string>

namespace contactrb::cases {

nlohmann::json mu_json(const std::vector<ParameterSpec>& parameters, const Mu& mu) {
  if (mu.size() == 1) return mu(0);
  nlohmann::json j = nlohmann::json::object();
  for (Eigen::Index k = 0; k < mu.size(); ++k) {
    j[k < static_cast<Eigen::Index>(parameters.size()) ? parameters[static_cast<std::size_t>(k)].name
                                                       : std::to_string(k)] = mu(k);
  }
  return j;
}

}  // namespace contactrb::cases
