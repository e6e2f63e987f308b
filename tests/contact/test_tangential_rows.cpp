// The tangential rows and the slip measure of friction (contact/tangential_rows.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "contact_fixtures.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/tangential_rows.hpp"

using namespace contactrb;

namespace {
struct Pair {
  mesh::Mesh mesh;
  contact::ContactPair pair;
  contact::ContactQuadrature quadrature;
};
Pair make_pair_of(mesh::Mesh m) {
  Pair s{std::move(m), {}, {}};
  s.pair = contact::make_contact_pair(s.mesh);
  s.quadrature = contact::make_quadrature(s.mesh, s.pair, contact::Discretization::Collocation);
  return s;
}
// Slave block [0.2, 0.8] x [0.05, 1.05] over master block [0, 1] x [-1, 0], non-matching.
Pair flat() { return make_pair_of(contact_test::flat_blocks(0.2, 0.8, 0.05, 6, 0.0, 1.0, 7)); }
// Moves body `body` by `d`.
Eigen::VectorXd translation(const mesh::Mesh& m, int body, const Eigen::Vector2d& d) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (int t = 0; t < m.num_triangles(); ++t) {
    if (m.body[static_cast<std::size_t>(t)] != body) continue;
    for (int v : m.triangles[static_cast<std::size_t>(t)]) w.segment<2>(2 * v) = d;
  }
  return w;
}
}  // namespace

// On a flat master below the slave, n2 = (0, 1) and tau = (1, 0): row r of T applied to a
// slave motion dx along x is -|I_r| dx (master minus slave); the two bodies moving together
// give 0.
TEST(TangentialRows, FlatMasterRowsReadTheRelativeMotionAlongX) {
  const Pair s = flat();
  const Eigen::VectorXd w0 = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const contact::PointwiseContact pw = contact::project_slave_nodes(s.mesh, s.pair, w0);
  const auto T = contact::tangential_rows<2>(s.mesh, s.pair, s.quadrature, pw);
  ASSERT_EQ(T.rows(), s.quadrature.weight.size());
  const Eigen::VectorXd slave = translation(s.mesh, mesh::kSlaveBody, Eigen::Vector2d(0.01, -0.02));
  const Eigen::VectorXd both = slave + translation(s.mesh, mesh::kMasterBody, Eigen::Vector2d(0.01, -0.02));
  const Eigen::VectorXd Ts = T * slave, Tb = T * both;
  for (int r = 0; r < T.rows(); ++r) {
    EXPECT_NEAR(Ts(r), -0.01 * s.quadrature.weight(r), 1e-15) << "row " << r;
    EXPECT_NEAR(Tb(r), 0.0, 1e-15) << "row " << r;
  }
  EXPECT_EQ(contact::tangent_basis<2>(Eigen::Vector2d(0.0, 1.0)), Eigen::Vector2d(1.0, 0.0));
}

// On a curved master (a half annulus) the normal and tangential rows are the two components of
// the same relative motion: (K_r v)^2 + (T_r v)^2 = |I_r|^2 |(1 - xi) v_a + xi v_b - v_s|^2.
TEST(TangentialRows, NormalAndTangentialRowsSplitTheRelativeMotion) {
  const Pair s = make_pair_of(contact_test::join(mesh::rectangle(-0.5, 1.02, 0.5, 1.5, 10, 3, mesh::kSlaveBody),
                                           contact_test::half_annulus(0.5, 1.0, 24, 3)));
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> uni(-0.01, 0.01);
  Eigen::VectorXd v(s.mesh.num_dofs());
  for (Eigen::Index i = 0; i < v.size(); ++i) v(i) = uni(gen);
  const contact::PointwiseContact pw = contact::project_slave_nodes(s.mesh, s.pair, Eigen::VectorXd::Zero(v.size()));
  const auto T = contact::tangential_rows<2>(s.mesh, s.pair, s.quadrature, pw);
  const contact::ConstraintRows rows = contact::constraint_rows(s.mesh, s.pair, s.quadrature, pw, Eigen::VectorXd::Zero(v.size()));
  const Eigen::VectorXd Tv = T * v, Kv = rows.K * v;
  int candidates = 0;
  for (std::size_t q = 0; q < s.pair.slave.size(); ++q) {
    const contact::SlaveProjection& p = pw.projection[q];
    if (!p.candidate) {
      EXPECT_EQ(Tv(static_cast<Eigen::Index>(q)), 0.0);
      continue;
    }
    ++candidates;
    const int a = s.pair.master[static_cast<std::size_t>(p.segment)];
    const int b = s.pair.master[static_cast<std::size_t>(p.segment + 1)];
    const Eigen::Vector2d rel = (1.0 - p.xi) * v.segment<2>(2 * a) + p.xi * v.segment<2>(2 * b) - v.segment<2>(2 * s.pair.slave[q]);
    const double w = s.quadrature.weight(static_cast<Eigen::Index>(q));
    EXPECT_NEAR(std::hypot(Kv(static_cast<Eigen::Index>(q)), Tv(static_cast<Eigen::Index>(q))), w * rel.norm(), 1e-14);
  }
  EXPECT_GE(candidates, 5);
}

// The slip is material: zero when both bodies move together, dx when the slave alone moves by dx
// along the flat master.
TEST(TangentialRows, SlipIsTheMotionOverTheMastersMaterialPoints) {
  const Pair s = flat();
  const Eigen::VectorXd w0 = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const contact::PointwiseContact before = contact::project_slave_nodes(s.mesh, s.pair, w0);
  const auto rho0 = contact::material_points<2>(s.mesh, s.pair, before, w0);
  for (const double dx : {0.05, 0.19}) {
    const Eigen::VectorXd slave = translation(s.mesh, mesh::kSlaveBody, Eigen::Vector2d(dx, -0.05));
    const Eigen::VectorXd both = slave + translation(s.mesh, mesh::kMasterBody, Eigen::Vector2d(dx, -0.05));
    for (const auto& [w, expected] : {std::pair{slave, dx}, std::pair{both, 0.0}}) {
      const contact::PointwiseContact now = contact::project_slave_nodes(s.mesh, s.pair, w);
      const Eigen::VectorXd slip = contact::tangential_slip<2>(now, contact::material_points<2>(s.mesh, s.pair, now, w), rho0);
      for (std::size_t q = 0; q < now.projection.size(); ++q) {
        ASSERT_TRUE(now.projection[q].candidate) << q;
        EXPECT_NEAR(slip(static_cast<Eigen::Index>(q)), expected, 1e-14) << q;
      }
    }
  }
}

TEST(TangentialRows, FrictionNeedsCollocationRows) {
  Pair s = flat();
  s.quadrature = contact::make_quadrature(s.mesh, s.pair, contact::Discretization::LAC);
  const contact::PointwiseContact pw = contact::project_slave_nodes(s.mesh, s.pair, Eigen::VectorXd::Zero(s.mesh.num_dofs()));
  EXPECT_THROW(contact::tangential_rows<2>(s.mesh, s.pair, s.quadrature, pw), Error);
}

// slip_rows is the derivative of -|I_r| slip_r (tangents held): central differences of the
// material points along a random direction, on the curved master, at a deformed state.
TEST(TangentialRows, SlipRowsAreTheDerivativeOfTheWeightedSlip) {
  const Pair s = make_pair_of(contact_test::join(mesh::rectangle(-0.5, 1.02, 0.5, 1.5, 10, 3, mesh::kSlaveBody),
                                                 contact_test::half_annulus(0.5, 1.0, 24, 3)));
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::VectorXd w(s.mesh.num_dofs()), v(s.mesh.num_dofs());
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    w(i) = 0.005 * uni(gen);
    v(i) = uni(gen);
  }
  const contact::PointwiseContact pw = contact::project_slave_nodes(s.mesh, s.pair, w);
  const Eigen::VectorXd Dv = contact::slip_rows<2>(s.mesh, s.pair, s.quadrature, pw, w) * v;
  const double h = 1e-6;
  auto rho_along = [&](double t) { return contact::material_points<2>(s.mesh, s.pair, pw, w + t * v); };
  const auto plus = rho_along(h), minus = rho_along(-h);
  int checked = 0;
  for (std::size_t q = 0; q < pw.projection.size(); ++q) {
    if (!pw.projection[q].candidate) continue;
    const Eigen::Vector2d tau = contact::tangent_basis<2>(pw.projection[q].normal);
    const double dslip = tau.dot(plus[q] - minus[q]) / (2.0 * h);
    EXPECT_NEAR(Dv(static_cast<Eigen::Index>(q)), -s.quadrature.weight(static_cast<Eigen::Index>(q)) * dslip, 1e-8) << q;
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

// tangential_stiffness is the derivative of T(w)' lambda_t when the tangents do not turn: a flat
// master that moves rigidly, the slave nodes moving freely (central differences).
TEST(TangentialRows, TangentialStiffnessIsTheDerivativeOfTheForces) {
  const Pair s = flat();
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::VectorXd w = translation(s.mesh, mesh::kSlaveBody, Eigen::Vector2d(0.03, -0.05));
  Eigen::VectorXd v = translation(s.mesh, mesh::kMasterBody, Eigen::Vector2d(0.3, -0.2));
  for (int node : s.pair.slave) {
    w.segment<2>(2 * node) += 0.01 * Eigen::Vector2d(uni(gen), uni(gen));
    v.segment<2>(2 * node) += Eigen::Vector2d(uni(gen), uni(gen));
  }
  Eigen::VectorXd lambda_t(s.quadrature.weight.size());
  for (Eigen::Index r = 0; r < lambda_t.size(); ++r) lambda_t(r) = uni(gen);
  const contact::PointwiseContact pw = contact::project_slave_nodes(s.mesh, s.pair, w);
  const Eigen::VectorXd Hv = contact::tangential_stiffness<2>(s.mesh, s.pair, s.quadrature, pw, w, lambda_t) * v;
  const double h = 1e-6;
  auto forces = [&](double t) {
    const contact::PointwiseContact p = contact::project_slave_nodes(s.mesh, s.pair, w + t * v);
    return Eigen::VectorXd(contact::tangential_rows<2>(s.mesh, s.pair, s.quadrature, p).transpose() * lambda_t);
  };
  const Eigen::VectorXd fd = (forces(h) - forces(-h)) / (2.0 * h);
  EXPECT_GT(Hv.norm(), 1e-3);
  EXPECT_LT((Hv - fd).cwiseAbs().maxCoeff(), 1e-7 * Hv.cwiseAbs().maxCoeff());
}
