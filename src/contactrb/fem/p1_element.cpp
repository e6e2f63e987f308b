#include "contactrb/fem/p1_element.hpp"

#include <Eigen/Geometry>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::fem {
namespace {

// Copies the lower triangle onto the upper one, so that element matrices, hence the
// assembled ones, are symmetric to the last bit (Eigen's products need not be).
template <int Dim>
SimplexElementMatrix<Dim> mirrored_lower(SimplexElementMatrix<Dim> M) {
  for (int j = 0; j < M.cols(); ++j)
    for (int i = 0; i < j; ++i) M(i, j) = M(j, i);
  return M;
}

// The components (a, b) of the shear rows of a Voigt vector (p1_element.hpp).
template <int Dim>
inline constexpr std::array<std::array<int, 2>, kVoigtSize<Dim> - Dim> kShearPairs{};
template <>
inline constexpr std::array<std::array<int, 2>, 1> kShearPairs<2>{{{0, 1}}};
template <>
inline constexpr std::array<std::array<int, 2>, 3> kShearPairs<3>{{{0, 1}, {1, 2}, {0, 2}}};

}  // namespace

P1Triangle p1_triangle(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2) {
  const Eigen::Vector2d e1 = p1 - p0, e2 = p2 - p0;
  const double twice_area = e1.x() * e2.y() - e2.x() * e1.y();
  if (!(twice_area > 0.0)) {  // message built only on failure (hot path)
    throw Error("p1_triangle: triangle is not counter-clockwise (signed area " + number_text(0.5 * twice_area) +
                ")");
  }
  P1Triangle t;
  t.area = 0.5 * twice_area;
  // grad phi_i = rot(opposite edge) / (2 area), with the edge taken counter-clockwise.
  t.grad << p1.y() - p2.y(), p2.x() - p1.x(),  //
      p2.y() - p0.y(), p0.x() - p2.x(),        //
      p0.y() - p1.y(), p1.x() - p0.x();
  t.grad /= twice_area;
  return t;
}

P1Tetrahedron p1_tetrahedron(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                             const Eigen::Vector3d& p3) {
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0, e3 = p3 - p0;
  // Rows of the inverse Jacobian [e1 e2 e3]^-1: the cofactors e_j x e_k over the determinant.
  const Eigen::Vector3d c1 = e2.cross(e3), c2 = e3.cross(e1), c3 = e1.cross(e2);
  const double det = e1.dot(c1);
  if (!(det > 0.0)) {  // message built only on failure (hot path)
    throw Error("p1_tetrahedron: tetrahedron has no positive volume (signed volume " + number_text(det / 6.0) + ")");
  }
  P1Tetrahedron t;
  t.volume = det / 6.0;
  t.grad.row(1) = c1.transpose() / det;
  t.grad.row(2) = c2.transpose() / det;
  t.grad.row(3) = c3.transpose() / det;
  t.grad.row(0) = -(t.grad.row(1) + t.grad.row(2) + t.grad.row(3));
  return t;
}

template <int Dim>
P1Simplex<Dim> p1_simplex(const std::array<Eigen::Matrix<double, Dim, 1>, Dim + 1>& p) {
  if constexpr (Dim == 2) {
    return p1_triangle(p[0], p[1], p[2]);
  } else {
    return p1_tetrahedron(p[0], p[1], p[2], p[3]);
  }
}

template <int Dim>
SimplexStrainOperator<Dim> strain_operator(const P1Simplex<Dim>& element) {
  SimplexStrainOperator<Dim> B = SimplexStrainOperator<Dim>::Zero();
  for (int i = 0; i < Dim + 1; ++i) {
    for (int c = 0; c < Dim; ++c) B(c, Dim * i + c) = element.grad(i, c);
    for (std::size_t s = 0; s < kShearPairs<Dim>.size(); ++s) {
      const int row = Dim + static_cast<int>(s), a = kShearPairs<Dim>[s][0], b = kShearPairs<Dim>[s][1];
      B(row, Dim * i + a) = element.grad(i, b);
      B(row, Dim * i + b) = element.grad(i, a);
    }
  }
  return B;
}

template <int Dim>
SimplexElementMatrix<Dim> element_divergence(const P1Simplex<Dim>& element) {
  Eigen::Matrix<double, Dim*(Dim + 1), 1> d;
  for (int i = 0; i < Dim + 1; ++i) {
    for (int c = 0; c < Dim; ++c) d(Dim * i + c) = element.grad(i, c);
  }
  return mirrored_lower<Dim>(element.measure() * d * d.transpose());
}

template <int Dim>
SimplexElementMatrix<Dim> element_symmetric_gradient(const P1Simplex<Dim>& element) {
  // eps : eps = sum of the normal strains squared + half the engineering shears squared.
  const SimplexStrainOperator<Dim> B = strain_operator(element);
  VoigtVector<Dim> weight = VoigtVector<Dim>::Constant(0.5);
  weight.template head<Dim>().setOnes();
  return mirrored_lower<Dim>(element.measure() * B.transpose() * weight.asDiagonal() * B);
}

template <int Dim>
SimplexElementMatrix<Dim> element_laplacian(const P1Simplex<Dim>& element) {
  Eigen::Matrix<double, Dim + 1, Dim + 1> G = element.measure() * element.grad * element.grad.transpose();
  for (int j = 0; j < Dim + 1; ++j)
    for (int i = 0; i < j; ++i) G(i, j) = G(j, i);
  SimplexElementMatrix<Dim> L = SimplexElementMatrix<Dim>::Zero();
  for (int i = 0; i < Dim + 1; ++i) {
    for (int j = 0; j < Dim + 1; ++j) {
      for (int c = 0; c < Dim; ++c) L(Dim * i + c, Dim * j + c) = G(i, j);
    }
  }
  return L;
}

template <int Dim>
SimplexElementMatrix<Dim> element_mass(const P1Simplex<Dim>& element) {
  // int phi_i phi_j = measure (1 + delta_ij) / ((Dim + 1)(Dim + 2)).
  constexpr double denominator = (Dim + 1) * (Dim + 2);
  SimplexElementMatrix<Dim> M = SimplexElementMatrix<Dim>::Zero();
  for (int i = 0; i < Dim + 1; ++i) {
    for (int j = 0; j < Dim + 1; ++j) {
      const double m = element.measure() * (i == j ? 2.0 : 1.0) / denominator;
      for (int c = 0; c < Dim; ++c) M(Dim * i + c, Dim * j + c) = m;
    }
  }
  return M;
}

template <int Dim>
VoigtVector<Dim> hooke_stress(const VoigtVector<Dim>& strain, double lame_lambda, double lame_mu) {
  double trace = strain(0);
  for (int c = 1; c < Dim; ++c) trace += strain(c);
  VoigtVector<Dim> stress;
  for (int c = 0; c < Dim; ++c) stress(c) = lame_lambda * trace + 2.0 * lame_mu * strain(c);
  for (int s = Dim; s < kVoigtSize<Dim>; ++s) stress(s) = lame_mu * strain(s);
  return stress;
}

Eigen::Vector3d plane_strain_stress(const Eigen::Vector3d& strain, double lame_lambda, double lame_mu) {
  return hooke_stress<2>(strain, lame_lambda, lame_mu);
}

#define CONTACTRB_P1_INSTANTIATE(D)                                                                       \
  template P1Simplex<D> p1_simplex<D>(const std::array<Eigen::Matrix<double, D, 1>, D + 1>&);             \
  template SimplexStrainOperator<D> strain_operator<D>(const P1Simplex<D>&);                              \
  template SimplexElementMatrix<D> element_divergence<D>(const P1Simplex<D>&);                            \
  template SimplexElementMatrix<D> element_symmetric_gradient<D>(const P1Simplex<D>&);                    \
  template SimplexElementMatrix<D> element_laplacian<D>(const P1Simplex<D>&);                             \
  template SimplexElementMatrix<D> element_mass<D>(const P1Simplex<D>&);                                  \
  template VoigtVector<D> hooke_stress<D>(const VoigtVector<D>&, double, double);
CONTACTRB_P1_INSTANTIATE(2)
CONTACTRB_P1_INSTANTIATE(3)
#undef CONTACTRB_P1_INSTANTIATE

}  // namespace contactrb::fem
