#pragma once
// Quadrature rules on a simplex (triangle, tetrahedron), in barycentric coordinates. Weights
// sum to 1: int_T f ~= measure(T) * sum_q weight_q f(x_q).
#include <Eigen/Core>
#include <vector>

namespace contactrb::fem {

template <int Dim>
struct SimplexQuadrature {
  int degree = 0;  // polynomials of this total degree are integrated exactly
  std::vector<Eigen::Matrix<double, Dim + 1, 1>> barycentric;
  std::vector<double> weights;
};
using TriangleQuadrature = SimplexQuadrature<2>;
using TetrahedronQuadrature = SimplexQuadrature<3>;

// The cheapest stored rule exact for `degree`: 1 (centroid), 2 (3 points), 4 (6 points,
// Dunavant), 5 (7 points, Dunavant). Throws contactrb::Error for degree < 0 or > 5.
const TriangleQuadrature& triangle_quadrature(int degree);

// The Grundmann-Moeller rule (SIAM J. Numer. Anal. 15, 1978) of the smallest odd degree
// >= `degree`: 1 (1 point), 3 (5 points), 5 (15 points), 7 (35 points; some weights are
// negative). Throws contactrb::Error for degree < 0 or > 7.
const TetrahedronQuadrature& tetrahedron_quadrature(int degree);

// triangle_quadrature or tetrahedron_quadrature.
template <int Dim>
const SimplexQuadrature<Dim>& simplex_quadrature(int degree) {
  if constexpr (Dim == 2) {
    return triangle_quadrature(degree);
  } else {
    return tetrahedron_quadrature(degree);
  }
}

}  // namespace contactrb::fem
