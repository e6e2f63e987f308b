#pragma once
// Symmetric quadrature rules on a triangle, in barycentric coordinates. Weights sum to 1:
// int_T f ~= area(T) * sum_q weight_q f(x_q).
#include <Eigen/Core>
#include <vector>

namespace contactrb::fem {

struct TriangleQuadrature {
  int degree = 0;  // polynomials of this total degree are integrated exactly
  std::vector<Eigen::Vector3d> barycentric;
  std::vector<double> weights;
};

// The cheapest stored rule exact for `degree`: 1 (centroid), 2 (3 points), 4 (6 points,
// Dunavant), 5 (7 points, Dunavant). Throws contactrb::Error for degree < 0 or > 5.
const TriangleQuadrature& triangle_quadrature(int degree);

}  // namespace contactrb::fem
