#pragma once
// Element kernels of the P1 vector Lagrange triangle. Local DOF 2*i + c is component c
// (0 = x, 1 = y) of vertex i, matching the global numbering 2*node + c (mesh.hpp).
#include <Eigen/Core>

namespace contactrb::fem {

using ElementMatrix = Eigen::Matrix<double, 6, 6>;
using StrainOperator = Eigen::Matrix<double, 3, 6>;  // rows: eps_xx, eps_yy, 2 eps_xy

// Area and the constant gradients of the three barycentric shape functions (row i =
// grad phi_i). Throws contactrb::Error when the triangle is not counter-clockwise.
struct P1Triangle {
  double area = 0.0;
  Eigen::Matrix<double, 3, 2> grad;
};
P1Triangle p1_triangle(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2);

// Engineering strain (eps_xx, eps_yy, 2 eps_xy) = B v_e.
StrainOperator strain_operator(const P1Triangle& element);
// int div v div w (the lambda_L part of the stiffness).
ElementMatrix element_divergence(const P1Triangle& element);
// int eps(v) : eps(w) (the 2 mu_L part of the stiffness).
ElementMatrix element_symmetric_gradient(const P1Triangle& element);
// int grad v : grad w.
ElementMatrix element_laplacian(const P1Triangle& element);
// int v . w (exact for P1).
ElementMatrix element_mass(const P1Triangle& element);

// Plane-strain stress (sxx, syy, sxy) from the engineering strain (eps_xx, eps_yy, 2 eps_xy).
Eigen::Vector3d plane_strain_stress(const Eigen::Vector3d& strain, double lame_lambda, double lame_mu);

}  // namespace contactrb::fem
