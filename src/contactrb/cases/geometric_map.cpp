#include "contactrb/cases/geometric_map.hpp"

namespace contactrb::cases {

std::array<AffineMap, 2> geometric_maps(const ParameterSpec& p, double mu) {
  std::array<AffineMap, 2> maps;
  if (p.kind == ParameterKind::BodyScaling && mu != p.reference) {
    const double s = p.scale(mu);
    AffineMap& h = maps[static_cast<std::size_t>(p.body)];
    h.M = s * Eigen::Matrix2d::Identity();
    h.b = (1.0 - s) * p.center;
  }
  return maps;
}

}  // namespace contactrb::cases
