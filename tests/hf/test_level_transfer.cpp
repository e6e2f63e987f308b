// Grid sequencing (hf/level_transfer.hpp, cases/level_sequence.hpp; docs/solvers.md "Grid
// sequencing"): the transfer between two non-nested Gmsh levels reproduces fields linear on
// each body (and pressures linear along the arc, in 3D on the slave surface) exactly, in 2D
// (triangles) and 3D (tetrahedra), the point location agrees with a brute-force search, and a
// sequenced solve gives the cold solve's answer (u, lambda, force, energy, active set, KKT) in
// fewer fine-level iterations.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/triangle_hit.hpp"
#include "contactrb/hf/level_transfer.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;

namespace {

// u = M_b x + c_b on body b (a different affine field on each body).
Eigen::Vector2d affine(int body, const Eigen::Vector2d& x) {
  Eigen::Matrix2d M;
  Eigen::Vector2d c;
  if (body == 0) {
    M << 0.3, -1.7, 2.1, 0.4;
    c << -0.25, 1.5;
  } else {
    M << -1.1, 0.6, 0.2, 3.3;
    c << 0.75, -2.0;
  }
  return M * x + c;
}

Eigen::VectorXd affine_field(const mesh::Mesh& m) {
  Eigen::VectorXd u(m.num_dofs());
  for (int t = 0; t < m.num_triangles(); ++t) {
    for (int v : m.triangles[static_cast<std::size_t>(t)]) {
      u.segment<2>(2 * v) = affine(m.body[static_cast<std::size_t>(t)], m.nodes[static_cast<std::size_t>(v)]);
    }
  }
  return u;
}

double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

hf::HFSettings newton(double tolerance) {
  hf::HFSettings s;
  s.method = hf::HFMethod::Newton;
  s.newton.tolerance = tolerance;
  return s;
}

}  // namespace

TEST(LevelTransfer, ReproducesAFieldLinearOnEachBodyExactly) {
  // Hertz levels 0 -> 2 and ring-block 0 -> 1: separate Gmsh meshes (nodes not nested), fine
  // arc nodes outside the coarse chords (extrapolated from the nearest coarse triangle).
  for (const char* name : {"hertz-a", "ring-block"}) {
    const cases::CaseSpec spec = cases::builtin_case_spec(name);
    const mesh::Mesh coarse = cases::reference_mesh(spec, 0);
    const mesh::Mesh fine = cases::reference_mesh(spec, std::string(name) == "hertz-a" ? 2 : 1);
    ASSERT_GT(fine.num_nodes(), coarse.num_nodes());
    const Eigen::VectorXd u = hf::transfer_displacement(coarse, affine_field(coarse), fine);
    const Eigen::VectorXd truth = affine_field(fine);
    EXPECT_LT((u - truth).lpNorm<Eigen::Infinity>(), 1e-12 * truth.lpNorm<Eigen::Infinity>()) << name;
    // Not the identity by accident: a quadratic field is NOT reproduced on the curved arcs.
    Eigen::VectorXd q(coarse.num_dofs()), q_truth(fine.num_dofs());
    for (int v = 0; v < coarse.num_nodes(); ++v) q.segment<2>(2 * v) = coarse.nodes[static_cast<std::size_t>(v)].array().square();
    for (int v = 0; v < fine.num_nodes(); ++v) q_truth.segment<2>(2 * v) = fine.nodes[static_cast<std::size_t>(v)].array().square();
    EXPECT_GT((hf::transfer_displacement(coarse, q, fine) - q_truth).lpNorm<Eigen::Infinity>(), 1e-5) << name;
  }
  const mesh::Mesh m = cases::reference_mesh(cases::builtin_case_spec("hertz-a"), 0);
  EXPECT_THROW(hf::transfer_displacement(m, Eigen::VectorXd::Zero(3), m), contactrb::Error);
}

TEST(LevelTransfer, LocatorFindsTheBruteForceNearestTriangle) {
  const mesh::Mesh m = cases::reference_mesh(cases::builtin_case_spec("hertz-a"), 0);
  for (int body = 0; body < 2; ++body) {
    const hf::TriangleLocator locator(m, body);
    std::mt19937 rng(7 + static_cast<unsigned>(body));
    std::uniform_real_distribution<double> x(-1.3, 1.3), y(body == 0 ? -0.1 : -2.3, body == 0 ? 2.3 : 0.1);
    for (int k = 0; k < 400; ++k) {
      const Eigen::Vector2d p(x(rng), y(rng));
      const hf::TriangleLocator::Location loc = locator.locate(p);
      ASSERT_GE(loc.cell, 0);
      EXPECT_EQ(m.body[static_cast<std::size_t>(loc.cell)], body);
      // Brute force: inside some triangle of the body (distance 0) or the smallest distance.
      double best = std::numeric_limits<double>::infinity();
      for (int t = 0; t < m.num_triangles(); ++t) {
        if (m.body[static_cast<std::size_t>(t)] != body) continue;
        const auto& tri = m.triangles[static_cast<std::size_t>(t)];
        const Eigen::Vector2d a = m.nodes[static_cast<std::size_t>(tri[0])], b = m.nodes[static_cast<std::size_t>(tri[1])],
                              c = m.nodes[static_cast<std::size_t>(tri[2])];
        auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
        if (cross(b - a, p - a) >= 0 && cross(c - b, p - b) >= 0 && cross(a - c, p - c) >= 0) {
          best = 0.0;
          break;
        }
        auto seg = [&](const Eigen::Vector2d& s, const Eigen::Vector2d& e) {
          const double t01 = std::clamp((p - s).dot(e - s) / (e - s).squaredNorm(), 0.0, 1.0);
          return (s + t01 * (e - s) - p).norm();
        };
        best = std::min({best, seg(a, b), seg(b, c), seg(c, a)});
      }
      EXPECT_NEAR(loc.distance, best, 1e-12) << "body " << body << " point " << p.transpose();
      // The barycentric coordinates reproduce the point.
      const auto& tri = m.triangles[static_cast<std::size_t>(loc.cell)];
      Eigen::Vector2d back = Eigen::Vector2d::Zero();
      for (int i = 0; i < 3; ++i) back += loc.barycentric(i) * m.nodes[static_cast<std::size_t>(tri[static_cast<std::size_t>(i)])];
      EXPECT_LT((back - p).norm(), 1e-12);
      if (best == 0.0) {
        EXPECT_GE(loc.barycentric.minCoeff(), -1e-12);
      }
    }
  }
}

namespace {

// The block [lo, hi]^Dim of n cells a side (mesh/structured.hpp), body 0.
template <int Dim>
mesh::SimplexMesh<Dim> block(double lo, double hi, int n) {
  if constexpr (Dim == 2) {
    return mesh::rectangle(lo, lo, hi, hi, n, n);
  } else {
    return mesh::box(Eigen::Vector3d::Constant(lo), Eigen::Vector3d::Constant(hi), n, n, n);
  }
}

// Transfer from the unit block (interior nodes perturbed) to the block [-0.3, 1.3]^Dim: every
// fine boundary node and the layer beneath lie outside the coarse body, off its faces, edges
// and corners. The truth
// is independent of the locator: the nearest point of the unit block is the clamp of x to
// [0, 1]^Dim, so the distance is |x - clamp(x)| and the located cell must hold clamp(x).
template <int Dim>
void check_outside_points() {
  using Point = Eigen::Matrix<double, Dim, 1>;
  using Matrix = Eigen::Matrix<double, Dim, Dim>;
  mesh::SimplexMesh<Dim> coarse = block<Dim>(0.0, 1.0, 4);
  mesh::perturb_interior(coarse, 0.1);
  const mesh::SimplexMesh<Dim> fine = block<Dim>(-0.3, 1.3, 7);
  Matrix M = Matrix::Zero();
  for (int i = 0; i < Dim; ++i) {
    for (int j = 0; j < Dim; ++j) M(i, j) = 0.5 + i - 1.3 * j + 0.7 * i * j;
  }
  const Point c = Point::LinSpaced(-0.4, 1.1);
  const auto field = [&](const mesh::SimplexMesh<Dim>& m) {
    Eigen::VectorXd u(m.num_dofs());
    for (int v = 0; v < m.num_nodes(); ++v) u.template segment<Dim>(Dim * v) = M * m.nodes[static_cast<std::size_t>(v)] + c;
    return u;
  };
  // The transfer extrapolates from the nearest cell: a linear field is exact at every fine node.
  const Eigen::VectorXd u = hf::transfer_displacement(coarse, field(coarse), fine);
  const Eigen::VectorXd truth = field(fine);
  EXPECT_LT((u - truth).template lpNorm<Eigen::Infinity>(), 1e-12 * truth.template lpNorm<Eigen::Infinity>()) << Dim << "D";

  const hf::SimplexLocator<Dim> locator(coarse, mesh::kSlaveBody);
  int outside = 0;
  double nearest_value_error = 0.0;  // what the value at the nearest point would miss
  for (int v = 0; v < fine.num_nodes(); ++v) {
    const Point& x = fine.nodes[static_cast<std::size_t>(v)];
    const Point p = x.cwiseMax(0.0).cwiseMin(1.0);
    if (p == x) continue;
    ++outside;
    const auto loc = locator.locate(x);
    ASSERT_GE(loc.cell, 0);
    EXPECT_NEAR(loc.distance, (x - p).norm(), 1e-14) << "node " << v;
    const auto& cell = coarse.cells()[static_cast<std::size_t>(loc.cell)];
    const auto node = [&](int k) { return coarse.nodes[static_cast<std::size_t>(cell[static_cast<std::size_t>(k)])]; };
    Matrix J;
    for (int k = 0; k < Dim; ++k) J.col(k) = node(k + 1) - node(0);
    const Point l = J.partialPivLu().solve(p - node(0));
    EXPECT_GE(std::min(l.minCoeff(), 1.0 - l.sum()), -1e-12) << "node " << v << ": the cell does not hold the nearest point";
    Point back = Point::Zero();
    for (int k = 0; k <= Dim; ++k) back += loc.barycentric(k) * node(k);
    EXPECT_LT((back - x).norm(), 1e-12) << "node " << v;
    nearest_value_error = std::max(nearest_value_error, (M * (x - p)).norm());
  }
  // Two of the eight node planes per axis lie on each side of [0, 1]: 8^Dim - 4^Dim nodes outside.
  EXPECT_EQ(outside, Dim == 2 ? 64 - 16 : 512 - 64) << Dim << "D";
  EXPECT_GT(nearest_value_error, 0.3) << Dim << "D: the test would not tell extrapolation from the nearest value";
}

}  // namespace

// Fine nodes outside the coarse body: located by the nearest coarse boundary facet, the field
// extrapolated from that facet's cell (docs/solvers.md, "Grid sequencing"), in 2D and 3D.
TEST(LevelTransfer, ExtrapolatesAtFineNodesOutsideTheCoarseBody) {
  check_outside_points<2>();
  check_outside_points<3>();
}

TEST(LevelTransfer, ReproducesAPressureLinearAlongTheArcExactly) {
  // Collocation rows sit at the slave nodes, spaced uniformly in angle on the Hertz arc
  // (theta from pi to 2 pi): a pressure linear in the angle fraction is linear in arc length.
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-a");
  const mesh::Mesh coarse = cases::reference_mesh(spec, 2), fine = cases::reference_mesh(spec, 3);
  const contact::ContactPair cp = contact::make_contact_pair(coarse), fp = contact::make_contact_pair(fine);
  const auto cq = contact::make_quadrature(coarse, cp, contact::Discretization::Collocation);
  const auto fq = contact::make_quadrature(fine, fp, contact::Discretization::Collocation);
  // The angle fraction from the chain's first node (the chain may run either way).
  auto angle_fraction = [](const mesh::Mesh& m, const contact::ContactPair& pair, const contact::ContactQuadrature& q,
                           int r) {
    auto theta = [&](int node) {
      const Eigen::Vector2d x = m.nodes[static_cast<std::size_t>(node)];
      const Eigen::Vector2d centre(0.0, 0.05 + 1.0);  // HertzGeometry defaults: gap 0.1, R1 = 1
      double t = std::atan2(x.y() - centre.y(), x.x() - centre.x());
      if (t < 0) t += 2.0 * std::numbers::pi;
      return t;
    };
    return std::abs(theta(q.center_node[static_cast<std::size_t>(r)]) - theta(pair.slave.front())) / std::numbers::pi;
  };
  Eigen::VectorXd lc(cq.weight.size());
  for (int r = 0; r < lc.size(); ++r) lc(r) = 3.0 - 2.5 * angle_fraction(coarse, cp, cq, r);
  const Eigen::VectorXd lf = hf::transfer_pressure(coarse, cp, cq, lc, fine, fp, fq);
  ASSERT_EQ(lf.size(), fq.weight.size());
  double worst = 0.0;
  for (int r = 0; r < lf.size(); ++r) worst = std::max(worst, std::abs(lf(r) - (3.0 - 2.5 * angle_fraction(fine, fp, fq, r))));
  EXPECT_LT(worst, 1e-9);
  EXPECT_THROW(hf::transfer_pressure(coarse, cp, cq, Eigen::VectorXd::Zero(2), fine, fp, fq), contactrb::Error);
}

TEST(LevelSequence, LevelsOfASequence) {
  EXPECT_EQ(cases::sequence_levels(7, 2), (std::vector<int>{3, 5}));
  EXPECT_EQ(cases::sequence_levels(3, 3), (std::vector<int>{1}));
  EXPECT_EQ(cases::sequence_levels(3, 2, 1), (std::vector<int>{1, 2}));
  EXPECT_TRUE(cases::sequence_levels(5, 0).empty());
  EXPECT_THROW(cases::sequence_levels(5, -1), contactrb::Error);
  EXPECT_THROW(cases::sequence_levels(5, 1, 0), contactrb::Error);
}

TEST(LevelSequence, SequencedSolveIsTheColdSolveInFewerFineIterations) {
  struct Case {
    const char* name;
    double mu;
    int level;
    std::vector<int> coarse;
  };
  for (const Case& c : {Case{"hertz-a", 0.45, 3, {1}}, Case{"hertz-a", 0.3, 4, {0, 2}}, Case{"ring-block", 1.05, 1, {0}}}) {
    const cases::CaseSpec spec = cases::builtin_case_spec(c.name);
    const hf::HFSolver solver(cases::make_problem(spec, c.mu, c.level));
    // Both to 1e-12 (lambda carries the residual times the stiffness; see the warm-start test).
    const hf::HFSolution cold = solver.solve(newton(1e-12));
    const cases::SequenceStart start = cases::sequence_start(spec, Eigen::VectorXd::Constant(1, c.mu), c.coarse,
                                                             std::nullopt, newton(1e-12), solver);
    ASSERT_EQ(start.stages.size(), c.coarse.size());
    for (const cases::SequenceStage& st : start.stages) EXPECT_TRUE(st.converged) << c.name << " level " << st.level;
    const hf::HFSolution warm = solver.solve(newton(1e-12), start.guess);
    ASSERT_TRUE(cold.converged && warm.converged) << cold.message << warm.message;
    EXPECT_LT(warm.iterations, cold.iterations) << c.name;
    EXPECT_LE(warm.kkt.max(), 1e-12) << c.name;
    // Pointwise (LAC allows a pointwise violation between its integrated rows: the cold one's).
    EXPECT_NEAR(warm.gap_violation, cold.gap_violation, 1e-12) << c.name;
    EXPECT_LT(relative(warm.u, cold.u), 1e-10) << c.name;
    EXPECT_LT(relative(warm.lambda, cold.lambda), 1e-10) << c.name;
    EXPECT_NEAR(warm.contact_force, cold.contact_force, 1e-10 * std::abs(cold.contact_force)) << c.name;
    EXPECT_NEAR(warm.energy, cold.energy, 1e-10 * std::abs(cold.energy)) << c.name;
    EXPECT_EQ(warm.active_constraints, cold.active_constraints) << c.name;
    for (int r = 0; r < cold.lambda.size(); ++r) EXPECT_EQ(warm.lambda(r) > 0.0, cold.lambda(r) > 0.0) << c.name << " row " << r;
    std::cout << c.name << " mu " << c.mu << " level " << c.level << ": cold " << cold.iterations << ", sequenced "
              << warm.iterations << " (coarse";
    for (const auto& st : start.stages) std::cout << " " << st.level << ":" << st.iterations;
    std::cout << ")\n";
  }
}

TEST(LevelSequence, ACoarseStageThatFailsEndsTheChainWithoutAGuess) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-a");
  const hf::HFSolver solver(cases::make_problem(spec, 0.3, 2));
  hf::HFSettings s = newton(1e-10);
  s.newton.max_iterations = 1;
  const cases::SequenceStart start = cases::sequence_start(spec, Eigen::VectorXd::Constant(1, 0.3), {0, 1}, std::nullopt, s, solver);
  ASSERT_EQ(start.stages.size(), 1u);  // level 1 never ran
  EXPECT_FALSE(start.stages[0].converged);
  EXPECT_EQ(start.guess.u.size(), 0);
  EXPECT_EQ(start.guess.lambda.size(), 0);
  // A coarse level that is not coarser is refused.
  EXPECT_THROW(cases::sequence_start(spec, Eigen::VectorXd::Constant(1, 0.3), {2}, std::nullopt, newton(1e-10), solver),
               contactrb::Error);
}

namespace {

// u = M_b x + c_b on body b of a 3D mesh (a different affine field on each body).
Eigen::VectorXd affine_field3(const mesh::Mesh3& m) {
  Eigen::Matrix3d M[2];
  Eigen::Vector3d c[2];
  M[0] << 0.3, -1.7, 2.1, 0.4, 1.2, -0.5, 0.9, 0.1, -2.2;
  M[1] << -1.1, 0.6, 0.2, 3.3, -0.4, 1.5, 0.7, -0.8, 0.05;
  c[0] << -0.25, 1.5, 0.5;
  c[1] << 0.75, -2.0, 1.25;
  Eigen::VectorXd u(m.num_dofs());
  for (int t = 0; t < m.num_tetrahedra(); ++t) {
    const int b = m.body[static_cast<std::size_t>(t)];
    for (int v : m.tetrahedra[static_cast<std::size_t>(t)]) {
      u.segment<3>(3 * v) = M[b] * m.nodes[static_cast<std::size_t>(v)] + c[b];
    }
  }
  return u;
}

}  // namespace

// hertz-3d levels 0 -> 1 (separate Gmsh meshes): a field linear on each body is reproduced to
// round-off, also at the fine nodes on the sphere outside the coarse facets (extrapolated from
// the nearest coarse tetrahedron); the located tetrahedron agrees with a brute-force search.
TEST(LevelTransfer3d, ReproducesAFieldLinearOnEachBodyExactly) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3d");
  const mesh::Mesh3 coarse = cases::reference_mesh3(spec, 0);
  const mesh::Mesh3 fine = cases::reference_mesh3(spec, 1);
  ASSERT_GT(fine.num_nodes(), coarse.num_nodes());
  const Eigen::VectorXd u = hf::transfer_displacement(coarse, affine_field3(coarse), fine);
  const Eigen::VectorXd truth = affine_field3(fine);
  EXPECT_LT((u - truth).lpNorm<Eigen::Infinity>(), 1e-12 * truth.lpNorm<Eigen::Infinity>());
  // Not the identity by accident: a quadratic field is not reproduced.
  Eigen::VectorXd q(coarse.num_dofs()), q_truth(fine.num_dofs());
  for (int v = 0; v < coarse.num_nodes(); ++v) q.segment<3>(3 * v) = coarse.nodes[static_cast<std::size_t>(v)].array().square();
  for (int v = 0; v < fine.num_nodes(); ++v) q_truth.segment<3>(3 * v) = fine.nodes[static_cast<std::size_t>(v)].array().square();
  EXPECT_GT((hf::transfer_displacement(coarse, q, fine) - q_truth).lpNorm<Eigen::Infinity>(), 1e-5);

  // The locator against all tetrahedra of the slave body: inside one of them (distance 0)
  // exactly when the brute force finds one containing the node, else at the brute force's
  // nearest distance; some fine nodes of the sphere lie outside the coarse facets.
  std::vector<int> fine_body(static_cast<std::size_t>(fine.num_nodes()), -1);
  for (int t = 0; t < fine.num_tetrahedra(); ++t) {
    for (int v : fine.tetrahedra[static_cast<std::size_t>(t)]) fine_body[static_cast<std::size_t>(v)] = fine.body[static_cast<std::size_t>(t)];
  }
  const hf::TetrahedronLocator locator(coarse, mesh::kSlaveBody);
  int outside = 0, checked = 0;
  for (int v = 0; v < fine.num_nodes(); v += 5) {
    if (fine_body[static_cast<std::size_t>(v)] != mesh::kSlaveBody) continue;
    const Eigen::Vector3d& x = fine.nodes[static_cast<std::size_t>(v)];
    const hf::TetrahedronLocator::Location loc = locator.locate(x);
    bool contained = false;
    double nearest = std::numeric_limits<double>::infinity();
    for (int t = 0; t < coarse.num_tetrahedra(); ++t) {
      if (coarse.body[static_cast<std::size_t>(t)] != mesh::kSlaveBody) continue;
      const auto& c = coarse.tetrahedra[static_cast<std::size_t>(t)];
      const auto p = [&](int k) { return coarse.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])]; };
      Eigen::Matrix3d J;
      J << p(1) - p(0), p(2) - p(0), p(3) - p(0);
      const Eigen::Vector3d l = J.partialPivLu().solve(x - p(0));
      contained = contained || (l.minCoeff() >= -1e-12 && 1.0 - l.sum() >= -1e-12);
      for (const auto& f : mesh::kCellFacets<3>) {
        nearest = std::min(nearest, std::sqrt(contact::closest_on_triangle(p(f[0]), p(f[1]), p(f[2]), 0, x).d2));
      }
    }
    ++checked;
    if (contained) {
      EXPECT_EQ(loc.distance, 0.0) << "node " << v;
    } else {
      ++outside;
      EXPECT_NEAR(loc.distance, nearest, 1e-14) << "node " << v;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(outside, 0);
}

// The 3D pressure transfer on patch-3d (a flat interface, levels 0 -> 1): a pressure linear on
// the coarse slave surface reaches the fine rows exactly.
TEST(LevelTransfer3d, ReproducesAPressureLinearOnTheSlaveSurface) {
  const cases::CaseSpec spec = cases::builtin_case_spec("patch-3d");
  const mesh::Mesh3 coarse = cases::reference_mesh3(spec, 0);
  const mesh::Mesh3 fine = cases::reference_mesh3(spec, 1);
  const contact::ContactPair3 cp = contact::make_contact_pair(coarse), fp = contact::make_contact_pair(fine);
  const contact::ContactQuadrature cq = contact::make_quadrature(coarse, cp, contact::Discretization::Collocation);
  const contact::ContactQuadrature fq = contact::make_quadrature(fine, fp, contact::Discretization::Collocation);
  const auto linear = [](const Eigen::Vector3d& x) { return 0.5 + 0.3 * x.x() - 0.7 * x.y(); };
  Eigen::VectorXd lc(static_cast<Eigen::Index>(cq.center_node.size()));
  for (std::size_t r = 0; r < cq.center_node.size(); ++r) lc(static_cast<Eigen::Index>(r)) = linear(coarse.nodes[static_cast<std::size_t>(cq.center_node[r])]);
  const Eigen::VectorXd lf = hf::transfer_pressure(coarse, cp, cq, lc, fine, fp, fq);
  ASSERT_EQ(lf.size(), static_cast<Eigen::Index>(fq.center_node.size()));
  ASSERT_GT(lf.size(), lc.size());
  for (std::size_t r = 0; r < fq.center_node.size(); ++r) {
    EXPECT_NEAR(lf(static_cast<Eigen::Index>(r)), linear(fine.nodes[static_cast<std::size_t>(fq.center_node[r])]), 1e-14) << "row " << r;
  }
  EXPECT_THROW(hf::transfer_pressure(coarse, cp, cq, Eigen::VectorXd::Zero(2), fine, fp, fq), contactrb::Error);
}

// hertz-3d at level 2 (collocation, Newton): sequenced from level 0, the fine solve converges
// to the cold solve's answer in fewer iterations (docs/solvers.md, "Grid sequencing").
TEST(LevelSequence3d, SequencedHertz3dSolveIsTheColdSolveInFewerIterations) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3d");
  const cases::Mu mu = Eigen::VectorXd::Constant(1, 0.02);
  const hf::HFSolver3 solver(cases::make_problem(spec, cases::reference_mesh3(spec, 2), mu));
  const hf::HFSolution3 cold = solver.solve(newton(1e-10));
  const cases::SequenceStart start = cases::sequence_start(spec, mu, {0}, std::nullopt, newton(1e-10), solver);
  ASSERT_EQ(start.stages.size(), 1u);
  EXPECT_TRUE(start.stages[0].converged);
  const hf::HFSolution3 warm = solver.solve(newton(1e-10), start.guess);
  ASSERT_TRUE(cold.converged && warm.converged) << cold.message << warm.message;
  EXPECT_LT(warm.iterations, cold.iterations);
  EXPECT_LE(warm.kkt.max(), 1e-10);
  EXPECT_LT(relative(warm.u, cold.u), 1e-8);
  EXPECT_LT(relative(warm.lambda, cold.lambda), 1e-6);
  EXPECT_NEAR(warm.contact_force, cold.contact_force, 1e-8 * cold.contact_force);
  EXPECT_EQ(warm.active_constraints, cold.active_constraints);
  std::cout << "hertz-3d mu 0.02 level 2: cold " << cold.iterations << ", sequenced " << warm.iterations
            << " (coarse 0:" << start.stages[0].iterations << ")\n";
}
