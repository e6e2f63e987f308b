#pragma once
// Parameter points in coordinates scaled to [0, 1] per parameter over its domain, so that
// parameters of different units weigh alike in a distance: x = (mu - offset) .* scale. A
// parameter of zero range (frozen) gets scale 0 and does not count.
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/parameter.hpp"

namespace contactrb::cases {

struct UnitBox {
  Eigen::VectorXd offset;  // p: each parameter's min
  Eigen::VectorXd scale;   // p: 1 / (max - min), or 0
  // The columns of `points` (p x P) scaled.
  Eigen::MatrixXd operator()(const Eigen::MatrixXd& points) const {
    return (points.colwise() - offset).array().colwise() * scale.array();
  }
};

inline UnitBox unit_box(const std::vector<ParameterSpec>& parameters) {
  const Eigen::Index p = static_cast<Eigen::Index>(parameters.size());
  UnitBox box{Eigen::VectorXd(p), Eigen::VectorXd(p)};
  for (Eigen::Index k = 0; k < p; ++k) {
    const ParameterSpec& q = parameters[static_cast<std::size_t>(k)];
    box.offset(k) = q.min;
    box.scale(k) = q.max > q.min ? 1.0 / (q.max - q.min) : 0.0;
  }
  return box;
}

}  // namespace contactrb::cases
