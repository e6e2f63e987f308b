#pragma once
// Element kernels of the P1 vector Lagrange simplex: the triangle (Dim = 2, plane strain) and
// the tetrahedron (Dim = 3). Local DOF Dim*i + c is component c (0 = x, 1 = y, 2 = z) of
// vertex i, matching the global numbering Dim*node + c (mesh.hpp).
// Strains and stresses are Voigt vectors: the Dim normal components, then the shear ones,
// (xy) in 2D and (xy, yz, xz) in 3D (the order of ParaView's symmetric tensors); a strain
// carries the engineering shears 2 eps_ab, a stress sigma_ab.
#include <Eigen/Core>
#include <array>

namespace contactrb::fem {

template <int Dim>
inline constexpr int kVoigtSize = Dim * (Dim + 1) / 2;
template <int Dim>
using SimplexElementMatrix = Eigen::Matrix<double, Dim*(Dim + 1), Dim*(Dim + 1)>;
template <int Dim>
using SimplexStrainOperator = Eigen::Matrix<double, kVoigtSize<Dim>, Dim*(Dim + 1)>;
template <int Dim>
using VoigtVector = Eigen::Matrix<double, kVoigtSize<Dim>, 1>;

using ElementMatrix = SimplexElementMatrix<2>;
using StrainOperator = SimplexStrainOperator<2>;  // rows: eps_xx, eps_yy, 2 eps_xy

// The element's measure under the dimension's own name (area, volume); measure() for
// dimension-independent code.
template <int Dim>
struct SimplexMeasure;
template <>
struct SimplexMeasure<2> {
  double area = 0.0;
  double measure() const { return area; }
};
template <>
struct SimplexMeasure<3> {
  double volume = 0.0;
  double measure() const { return volume; }
};

// The measure and the constant gradients of the Dim + 1 barycentric shape functions (row i =
// grad phi_i).
template <int Dim>
struct P1Simplex : SimplexMeasure<Dim> {
  Eigen::Matrix<double, Dim + 1, Dim> grad;
};
using P1Triangle = P1Simplex<2>;
using P1Tetrahedron = P1Simplex<3>;

// Throws contactrb::Error when the triangle is not counter-clockwise.
P1Triangle p1_triangle(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2);
// Throws contactrb::Error when det(p1 - p0, p2 - p0, p3 - p0) <= 0 (mesh.hpp).
P1Tetrahedron p1_tetrahedron(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                             const Eigen::Vector3d& p3);
// The element of Dim + 1 vertices (p1_triangle or p1_tetrahedron).
template <int Dim>
P1Simplex<Dim> p1_simplex(const std::array<Eigen::Matrix<double, Dim, 1>, Dim + 1>& p);

// Engineering strain (Voigt, above) = B v_e.
template <int Dim>
SimplexStrainOperator<Dim> strain_operator(const P1Simplex<Dim>& element);
// int div v div w (the lambda_L part of the stiffness).
template <int Dim>
SimplexElementMatrix<Dim> element_divergence(const P1Simplex<Dim>& element);
// int eps(v) : eps(w) (the 2 mu_L part of the stiffness).
template <int Dim>
SimplexElementMatrix<Dim> element_symmetric_gradient(const P1Simplex<Dim>& element);
// int grad v : grad w.
template <int Dim>
SimplexElementMatrix<Dim> element_laplacian(const P1Simplex<Dim>& element);
// int v . w (exact for P1).
template <int Dim>
SimplexElementMatrix<Dim> element_mass(const P1Simplex<Dim>& element);

// Isotropic Hooke's law sigma = lambda_L tr(eps) I + 2 mu_L eps on Voigt vectors (above); in
// 2D the plane-strain stress (sxx, syy, sxy).
template <int Dim>
VoigtVector<Dim> hooke_stress(const VoigtVector<Dim>& strain, double lame_lambda, double lame_mu);
// The 2D name of hooke_stress.
Eigen::Vector3d plane_strain_stress(const Eigen::Vector3d& strain, double lame_lambda, double lame_mu);

}  // namespace contactrb::fem
