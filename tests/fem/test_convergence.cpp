// Manufactured solution: u smooth, f = -div sigma(u) computed analytically, Dirichlet data
// from the nodal values of u on the whole boundary. P1 rates: 2 in L2, 1 in the H1 seminorm.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "contactrb/fem/cholesky.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/fem/p1_element.hpp"
#include "contactrb/fem/quadrature.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;
using namespace contactrb::fem;

namespace {

constexpr double pi = std::numbers::pi;
const Material kMaterial{2.0, 0.3};

// u = (sin(pi x) sin(pi y), exp(x) cos(y)); the second component is harmonic.
Eigen::Vector2d exact_u(const Eigen::Vector2d& p) {
  return {std::sin(pi * p.x()) * std::sin(pi * p.y()), std::exp(p.x()) * std::cos(p.y())};
}
Eigen::Matrix2d exact_grad(const Eigen::Vector2d& p) {  // row i = grad u_i
  Eigen::Matrix2d G;
  G << pi * std::cos(pi * p.x()) * std::sin(pi * p.y()), pi * std::sin(pi * p.x()) * std::cos(pi * p.y()),
      std::exp(p.x()) * std::cos(p.y()), -std::exp(p.x()) * std::sin(p.y());
  return G;
}
// f = -div sigma(u) = -mu Lap u - (lambda + mu) grad div u.
Eigen::Vector2d force(const Eigen::Vector2d& p) {
  const double lambda = kMaterial.lame_lambda(), mu = kMaterial.lame_mu();
  const double s = std::sin(pi * p.x()) * std::sin(pi * p.y());
  const Eigen::Vector2d laplacian(-2.0 * pi * pi * s, 0.0);
  const Eigen::Vector2d grad_div(-pi * pi * s - std::exp(p.x()) * std::sin(p.y()),
                                 pi * pi * std::cos(pi * p.x()) * std::cos(pi * p.y()) -
                                     std::exp(p.x()) * std::cos(p.y()));
  return -mu * laplacian - (lambda + mu) * grad_div;
}

struct Errors {
  double h = 0.0;
  double l2 = 0.0;
  double h1_semi = 0.0;
};

Errors solve_and_measure(const mesh::Mesh& m) {
  const SparseMatrix K = stiffness(m, {kMaterial});
  const Eigen::VectorXd f = body_load(m, 0, force, 5);
  std::vector<DirichletCondition> boundary;
  for (const auto& [name, edges] : m.boundaries) boundary.push_back({name, 0.0, 0.0});
  const DofMap dofs(m, boundary);
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(m.num_dofs());
  for (int d : dofs.constrained_dofs()) lift(d) = exact_u(m.nodes[static_cast<std::size_t>(d / 2)])(d % 2);
  SparseCholesky chol;
  EXPECT_EQ(chol.compute(dofs.restrict_matrix(K)), FactorStatus::Success);
  const Eigen::VectorXd u = lift + dofs.extend(chol.solve(Eigen::VectorXd(dofs.restrict(f - K * lift))));

  // Errors against the exact field at the points of a degree-5 rule.
  const TriangleQuadrature& rule = triangle_quadrature(5);
  Errors e;
  double area = 0.0;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const auto& tri = m.triangles[static_cast<std::size_t>(t)];
    const Eigen::Vector2d p[3] = {m.nodes[static_cast<std::size_t>(tri[0])], m.nodes[static_cast<std::size_t>(tri[1])],
                                  m.nodes[static_cast<std::size_t>(tri[2])]};
    const P1Triangle el = p1_triangle(p[0], p[1], p[2]);
    Eigen::Matrix<double, 3, 2> nodal;  // row i = u_h at vertex i
    for (int i = 0; i < 3; ++i) nodal.row(i) = u.segment<2>(2 * tri[static_cast<std::size_t>(i)]).transpose();
    const Eigen::Matrix2d grad_h = nodal.transpose() * el.grad;  // row c = grad u_h,c
    for (std::size_t q = 0; q < rule.weights.size(); ++q) {
      const Eigen::Vector3d& l = rule.barycentric[q];
      const Eigen::Vector2d x = l(0) * p[0] + l(1) * p[1] + l(2) * p[2];
      const Eigen::Vector2d uh = nodal.transpose() * l;
      const double w = el.area * rule.weights[q];
      e.l2 += w * (exact_u(x) - uh).squaredNorm();
      e.h1_semi += w * (exact_grad(x) - grad_h).squaredNorm();
    }
    area += el.area;
  }
  e.l2 = std::sqrt(e.l2);
  e.h1_semi = std::sqrt(e.h1_semi);
  e.h = std::sqrt(2.0 * area / m.num_triangles());  // a length proportional to the mesh size
  return e;
}

void expect_rates(const std::vector<Errors>& errors) {
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double ratio = std::log(errors[k - 1].h / errors[k].h);
    const double l2_rate = std::log(errors[k - 1].l2 / errors[k].l2) / ratio;
    const double h1_rate = std::log(errors[k - 1].h1_semi / errors[k].h1_semi) / ratio;
    EXPECT_GE(l2_rate, 1.8) << "refinement " << k;
    EXPECT_LE(l2_rate, 2.2) << "refinement " << k;
    EXPECT_GE(h1_rate, 0.85) << "refinement " << k;
    EXPECT_LE(h1_rate, 1.2) << "refinement " << k;
    std::printf("  h = %.4f  L2 = %.3e (rate %.3f)  H1 semi = %.3e (rate %.3f)\n", errors[k].h, errors[k].l2,
                l2_rate, errors[k].h1_semi, h1_rate);
  }
}

// Uniform red refinement (each triangle into four); midpoints of the edges of group `arc`
// are moved radially onto the circle of radius `radius` centred at the origin.
mesh::Mesh refine(const mesh::Mesh& m, const std::string& arc, double radius) {
  mesh::Mesh r;
  r.nodes = m.nodes;
  std::map<std::pair<int, int>, int> midpoint;
  auto mid = [&](int a, int b) {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    r.nodes.push_back(0.5 * (m.nodes[static_cast<std::size_t>(a)] + m.nodes[static_cast<std::size_t>(b)]));
    return midpoint[key] = r.num_nodes() - 1;
  };
  for (int t = 0; t < m.num_triangles(); ++t) {
    const auto [a, b, c] = m.triangles[static_cast<std::size_t>(t)];
    const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    for (const std::array<int, 3>& child : {std::array<int, 3>{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}}) {
      r.triangles.push_back(child);
      r.body.push_back(m.body[static_cast<std::size_t>(t)]);
    }
  }
  for (const auto& [name, edges] : m.boundaries) {
    auto& dst = r.boundaries[name];
    for (const mesh::Edge& e : edges) {
      const int c = mid(e.a, e.b);
      if (name == arc) r.nodes[static_cast<std::size_t>(c)] *= radius / r.nodes[static_cast<std::size_t>(c)].norm();
      dst.push_back({e.a, c});
      dst.push_back({c, e.b});
    }
  }
  return r;
}

}  // namespace

TEST(Convergence, ManufacturedSolutionOnSquare) {
  std::vector<Errors> errors;
  for (int n : {8, 16, 32, 64}) {
    mesh::Mesh m = mesh::rectangle(0.0, 0.0, 1.0, 1.0, n, n);
    mesh::perturb_interior(m, 0.2, 5);
    errors.push_back(solve_and_measure(m));
  }
  expect_rates(errors);
}

TEST(Convergence, ManufacturedSolutionOnHalfDisk) {
  std::vector<Errors> errors;
  // generate_half_disk grades the size away from the arc (Hertz meshes), so a sequence of
  // arc_nodes is no uniform refinement: refine one Gmsh mesh uniformly instead.
  mesh::Mesh m = mesh::generate_half_disk(1.0, 17);
  for (int level = 0; level < 4; ++level) {
    if (level > 0) m = refine(m, "arc", 1.0);
    ASSERT_NO_THROW(mesh::validate(m));
    errors.push_back(solve_and_measure(m));
  }
  expect_rates(errors);
}
