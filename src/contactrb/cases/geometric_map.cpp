#include "contactrb/cases/geometric_map.hpp"

namespace contactrb::cases {

std::array<AffineMap, 2> geometric_maps(const std::vector<ParameterSpec>& parameters, const Mu& mu) {
  std::array<AffineMap, 2> maps;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const ParameterSpec& p = parameters[k];
    const double value = mu(static_cast<Eigen::Index>(k));
    if (p.kind != ParameterKind::BodyScaling || value == p.reference) continue;
    const double s = p.scale(value);
    AffineMap& h = maps[static_cast<std::size_t>(p.body)];
    h.M = s * Eigen::Matrix2d::Identity();
    h.b = (1.0 - s) * p.center;
  }
  return maps;
}

bool is_geometric(const std::vector<ParameterSpec>& parameters) {
  for (const ParameterSpec& p : parameters) {
    if (p.kind == ParameterKind::BodyScaling) return true;
  }
  return false;
}

}  // namespace contactrb::cases
