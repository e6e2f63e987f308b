#include "contactrb/fem/p1_element.hpp"

#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::fem {
namespace {

// Copies the lower triangle onto the upper one, so that element matrices, hence the
// assembled ones, are symmetric to the last bit (Eigen's products need not be).
ElementMatrix mirrored_lower(ElementMatrix M) {
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < j; ++i) M(i, j) = M(j, i);
  return M;
}

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

StrainOperator strain_operator(const P1Triangle& element) {
  StrainOperator B = StrainOperator::Zero();
  for (int i = 0; i < 3; ++i) {
    const double gx = element.grad(i, 0), gy = element.grad(i, 1);
    B(0, 2 * i) = gx;
    B(1, 2 * i + 1) = gy;
    B(2, 2 * i) = gy;
    B(2, 2 * i + 1) = gx;
  }
  return B;
}

ElementMatrix element_divergence(const P1Triangle& element) {
  Eigen::Matrix<double, 6, 1> d;
  for (int i = 0; i < 3; ++i) {
    d(2 * i) = element.grad(i, 0);
    d(2 * i + 1) = element.grad(i, 1);
  }
  return mirrored_lower(element.area * d * d.transpose());
}

ElementMatrix element_symmetric_gradient(const P1Triangle& element) {
  // eps : eps = eps_xx^2 + eps_yy^2 + (2 eps_xy)^2 / 2.
  const StrainOperator B = strain_operator(element);
  const Eigen::Vector3d weight(1.0, 1.0, 0.5);
  return mirrored_lower(element.area * B.transpose() * weight.asDiagonal() * B);
}

ElementMatrix element_laplacian(const P1Triangle& element) {
  Eigen::Matrix3d G = element.area * element.grad * element.grad.transpose();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < j; ++i) G(i, j) = G(j, i);
  ElementMatrix L = ElementMatrix::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      L(2 * i, 2 * j) = G(i, j);
      L(2 * i + 1, 2 * j + 1) = G(i, j);
    }
  }
  return L;
}

ElementMatrix element_mass(const P1Triangle& element) {
  ElementMatrix M = ElementMatrix::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double m = element.area * (i == j ? 2.0 : 1.0) / 12.0;
      M(2 * i, 2 * j) = m;
      M(2 * i + 1, 2 * j + 1) = m;
    }
  }
  return M;
}

Eigen::Vector3d plane_strain_stress(const Eigen::Vector3d& strain, double lame_lambda, double lame_mu) {
  const double trace = strain(0) + strain(1);
  return {lame_lambda * trace + 2.0 * lame_mu * strain(0), lame_lambda * trace + 2.0 * lame_mu * strain(1),
          lame_mu * strain(2)};
}

}  // namespace contactrb::fem
