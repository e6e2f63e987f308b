#include <gtest/gtest.h>

#include <cmath>

#include "contactrb/common/error.hpp"
#include "contactrb/fem/p1_element.hpp"
#include "contactrb/fem/quadrature.hpp"

using namespace contactrb::fem;

namespace {
const Eigen::Vector2d p0(0.3, -0.2), p1(1.4, 0.1), p2(0.6, 0.9);
}

TEST(P1Element, GradientsReproduceLinearFunctions) {
  const P1Triangle t = p1_triangle(p0, p1, p2);
  EXPECT_NEAR(t.area, 0.5 * ((p1 - p0).x() * (p2 - p0).y() - (p2 - p0).x() * (p1 - p0).y()), 1e-15);
  // f(x) = 2 + 3x - 5y interpolated at the vertices has gradient (3, -5).
  auto f = [](const Eigen::Vector2d& x) { return 2.0 + 3.0 * x.x() - 5.0 * x.y(); };
  const Eigen::Vector2d g = t.grad.transpose() * Eigen::Vector3d(f(p0), f(p1), f(p2));
  EXPECT_NEAR(g.x(), 3.0, 1e-13);
  EXPECT_NEAR(g.y(), -5.0, 1e-13);
  EXPECT_NEAR(t.grad.colwise().sum().norm(), 0.0, 1e-14);  // partition of unity
  EXPECT_THROW(p1_triangle(p0, p2, p1), contactrb::Error);  // clockwise
}

TEST(P1Element, KernelsSymmetricAndConsistent) {
  const P1Triangle t = p1_triangle(p0, p1, p2);
  for (const ElementMatrix& M : {element_divergence(t), element_symmetric_gradient(t), element_laplacian(t),
                                 element_mass(t)}) {
    EXPECT_NEAR((M - M.transpose()).norm(), 0.0, 1e-14);
  }
  // Mass: the x-components of all entries sum to the area.
  double total = 0.0;
  const ElementMatrix M = element_mass(t);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) total += M(2 * i, 2 * j);
  EXPECT_NEAR(total, t.area, 1e-15);
  // Translations are in the kernel of the three derivative operators.
  Eigen::Matrix<double, 6, 1> tx, ty;
  tx << 1, 0, 1, 0, 1, 0;
  ty << 0, 1, 0, 1, 0, 1;
  for (const ElementMatrix& K : {element_divergence(t), element_symmetric_gradient(t), element_laplacian(t)}) {
    EXPECT_NEAR((K * tx).norm(), 0.0, 1e-13);
    EXPECT_NEAR((K * ty).norm(), 0.0, 1e-13);
  }
  // Strain of an affine field v = B x: (B00, B11, B01 + B10).
  Eigen::Matrix2d B;
  B << 0.3, -0.7, 1.1, 0.2;
  Eigen::Matrix<double, 6, 1> v;
  v << B * p0, B * p1, B * p2;
  const Eigen::Vector3d strain = strain_operator(t) * v;
  EXPECT_NEAR((strain - Eigen::Vector3d(0.3, 0.2, 0.4)).norm(), 0.0, 1e-13);
  // The symmetric-gradient energy of a rotation vanishes; the Laplacian one does not.
  Eigen::Matrix<double, 6, 1> rot;
  rot << -p0.y(), p0.x(), -p1.y(), p1.x(), -p2.y(), p2.x();
  EXPECT_NEAR(rot.dot(element_symmetric_gradient(t) * rot), 0.0, 1e-13);
  EXPECT_NEAR(rot.dot(element_laplacian(t) * rot), 2.0 * t.area, 1e-13);
}

TEST(Quadrature, ExactForItsDegree) {
  // Reference triangle (0,0), (1,0), (0,1): int x^a y^b = a! b! / (a + b + 2)!.
  auto exact = [](int a, int b) { return std::tgamma(a + 1) * std::tgamma(b + 1) / std::tgamma(a + b + 3); };
  for (int degree : {1, 2, 4, 5}) {
    const TriangleQuadrature& rule = triangle_quadrature(degree);
    EXPECT_GE(rule.degree, degree);
    double wsum = 0.0;
    for (double w : rule.weights) wsum += w;
    EXPECT_NEAR(wsum, 1.0, 1e-14);
    for (int a = 0; a <= rule.degree; ++a) {
      for (int b = 0; a + b <= rule.degree; ++b) {
        double q = 0.0;
        for (std::size_t k = 0; k < rule.weights.size(); ++k) {
          const double x = rule.barycentric[k](1), y = rule.barycentric[k](2);
          q += 0.5 * rule.weights[k] * std::pow(x, a) * std::pow(y, b);
        }
        EXPECT_NEAR(q, exact(a, b), 1e-14) << "degree " << degree << " monomial x^" << a << " y^" << b;
      }
    }
  }
  EXPECT_THROW(triangle_quadrature(6), contactrb::Error);
  EXPECT_THROW(triangle_quadrature(-1), contactrb::Error);
}
