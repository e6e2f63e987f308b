// The tangential rows and the slip measure of friction (contact/tangential_rows.hpp).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
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

// ---- 3D: the rows on the master triangles (stacked blocks, non-matching meshes) ----

namespace {
struct Pair3 {
  mesh::Mesh3 mesh;
  contact::ContactPair3 pair;
  contact::ContactQuadrature quadrature;
};
Pair3 blocks3(double gap) {
  Pair3 s{mesh::stacked_blocks(0, gap), {}, {}};
  s.pair = contact::make_contact_pair(s.mesh);
  s.quadrature = contact::make_quadrature(s.mesh, s.pair, contact::Discretization::Collocation);
  return s;
}
Eigen::VectorXd translation3(const mesh::Mesh3& m, int body, const Eigen::Vector3d& d) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (std::size_t c = 0; c < m.tetrahedra.size(); ++c) {
    if (m.body[c] != body) continue;
    for (int v : m.tetrahedra[c]) w.segment<3>(3 * v) = d;
  }
  return w;
}
Eigen::VectorXd random_vector(Eigen::Index n, double scale, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = scale * uni(gen);
  return v;
}
}  // namespace

// The pair is orthonormal and orthogonal to n, right-handed with n; on n = +-e_z it is
// (e_x, +-e_y); it is continuous in n (a small turn of n turns it by as little).
TEST(TangentialRows3D, TangentPairIsOrthonormalAndContinuous) {
  EXPECT_EQ(contact::tangent_basis<3>(Eigen::Vector3d(0, 0, 1)).col(0), Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(contact::tangent_basis<3>(Eigen::Vector3d(0, 0, 1)).col(1), Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(contact::tangent_basis<3>(Eigen::Vector3d(0, 0, -1)).col(1), Eigen::Vector3d(0, -1, 0));
  std::mt19937 gen(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d n = Eigen::Vector3d(normal(gen), normal(gen), normal(gen)).normalized();
    const Eigen::Matrix<double, 3, 2> t = contact::tangent_basis<3>(n);
    EXPECT_NEAR((t.transpose() * t - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-15);
    EXPECT_NEAR((t.transpose() * n).norm(), 0.0, 1e-15);
    EXPECT_NEAR(t.col(0).cross(t.col(1)).dot(n), 1.0, 1e-15);
    // Continuity where the largest component of n is unique by a margin.
    Eigen::Vector3d a = n.cwiseAbs();
    std::sort(a.data(), a.data() + 3);
    if (a(2) - a(1) < 0.05) continue;
    const Eigen::Vector3d m = (n + 1e-6 * Eigen::Vector3d(normal(gen), normal(gen), normal(gen))).normalized();
    EXPECT_LT((contact::tangent_basis<3>(m) - t).norm(), 1e-4 * (m - n).norm() / 1e-6);
  }
}

// On the flat master below the slave the rows read the relative motion along x and y (master
// minus slave), and both bodies moving together give 0; with a random motion the normal and the
// two tangential rows split |sum_i phi_i v_{t_i} - v_s|.
TEST(TangentialRows3D, RowsSplitTheRelativeMotion) {
  const Pair3 s = blocks3(0.0);
  const Eigen::VectorXd w0 = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const contact::PointwiseContact3 pw = contact::project_slave_nodes(s.mesh, s.pair, w0);
  const auto T = contact::tangential_rows<3>(s.mesh, s.pair, s.quadrature, pw);
  const auto R = s.quadrature.weight.size();
  ASSERT_EQ(T.rows(), 2 * R);
  const Eigen::VectorXd slave = translation3(s.mesh, mesh::kSlaveBody, Eigen::Vector3d(0.01, -0.02, -0.03));
  const Eigen::VectorXd both = slave + translation3(s.mesh, mesh::kMasterBody, Eigen::Vector3d(0.01, -0.02, -0.03));
  const Eigen::VectorXd Ts = T * slave, Tb = T * both;
  for (Eigen::Index r = 0; r < R; ++r) {
    EXPECT_NEAR(Ts(2 * r), -0.01 * s.quadrature.weight(r), 1e-15) << r;
    EXPECT_NEAR(Ts(2 * r + 1), 0.02 * s.quadrature.weight(r), 1e-15) << r;
    EXPECT_NEAR(Tb.segment<2>(2 * r).norm(), 0.0, 1e-15) << r;
  }
  const Eigen::VectorXd v = random_vector(s.mesh.num_dofs(), 0.01, 7);
  const contact::ConstraintRows rows = contact::constraint_rows(s.mesh, s.pair, s.quadrature, pw, w0);
  const Eigen::VectorXd Tv = T * v, Kv = rows.K * v;
  for (std::size_t q = 0; q < s.pair.slave.size(); ++q) {
    const contact::SlaveProjection3& p = pw.projection[q];
    ASSERT_TRUE(p.candidate) << q;
    const std::array<int, 3>& f = s.pair.master_faces[static_cast<std::size_t>(p.facet)];
    Eigen::Vector3d rel = -v.segment<3>(3 * s.pair.slave[q]);
    for (int i = 0; i < 3; ++i) rel += p.phi(i) * v.segment<3>(3 * s.pair.master[static_cast<std::size_t>(f[static_cast<std::size_t>(i)])]);
    const auto r = static_cast<Eigen::Index>(q);
    EXPECT_NEAR(std::sqrt(Kv(r) * Kv(r) + Tv.segment<2>(2 * r).squaredNorm()), s.quadrature.weight(r) * rel.norm(), 1e-15);
  }
}

// The slip is material: the slave sliding by (dx, dy) over the master reads (dx, dy), both
// bodies moving together read 0 (the slave nodes cross master triangles on the way).
TEST(TangentialRows3D, SlipIsTheMotionOverTheMastersMaterialPoints) {
  const Pair3 s = blocks3(0.05);
  const Eigen::VectorXd w0 = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const contact::PointwiseContact3 before = contact::project_slave_nodes(s.mesh, s.pair, w0);
  const auto rho0 = contact::material_points<3>(s.mesh, s.pair, before, w0);
  const Eigen::Vector3d d(0.13, -0.07, -0.05);
  const Eigen::VectorXd slave = translation3(s.mesh, mesh::kSlaveBody, d);
  const Eigen::VectorXd both = slave + translation3(s.mesh, mesh::kMasterBody, d);
  for (const auto& [w, moves] : {std::pair{slave, true}, std::pair{both, false}}) {
    const contact::PointwiseContact3 now = contact::project_slave_nodes(s.mesh, s.pair, w);
    const Eigen::VectorXd slip = contact::tangential_slip<3>(now, contact::material_points<3>(s.mesh, s.pair, now, w), rho0);
    int checked = 0;
    for (std::size_t q = 0; q < now.projection.size(); ++q) {
      if (!now.projection[q].candidate) continue;
      ++checked;
      const Eigen::Vector2d expected = moves ? Eigen::Vector2d(d.x(), d.y()) : Eigen::Vector2d::Zero();
      EXPECT_NEAR((slip.segment<2>(2 * static_cast<Eigen::Index>(q)) - expected).norm(), 0.0, 1e-14) << q;
    }
    EXPECT_GE(checked, 20);
  }
}

// slip_rows is the derivative of -|I_r| slip_r (tangents held), at a randomly deformed state (the
// master triangles tilted and stretched): central differences of the material points.
TEST(TangentialRows3D, SlipRowsAreTheDerivativeOfTheWeightedSlip) {
  const Pair3 s = blocks3(0.01);
  const Eigen::VectorXd w = random_vector(s.mesh.num_dofs(), 0.005, 11), v = random_vector(s.mesh.num_dofs(), 1.0, 12);
  const contact::PointwiseContact3 pw = contact::project_slave_nodes(s.mesh, s.pair, w);
  const Eigen::VectorXd Dv = contact::slip_rows<3>(s.mesh, s.pair, s.quadrature, pw, w) * v;
  const double h = 1e-6;
  const auto plus = contact::material_points<3>(s.mesh, s.pair, pw, w + h * v);
  const auto minus = contact::material_points<3>(s.mesh, s.pair, pw, w - h * v);
  int checked = 0;
  for (std::size_t q = 0; q < pw.projection.size(); ++q) {
    if (!pw.projection[q].candidate) continue;
    const Eigen::Vector2d dslip =
        contact::tangent_basis<3>(pw.projection[q].normal).transpose() * (plus[q] - minus[q]) / (2.0 * h);
    const auto r = static_cast<Eigen::Index>(q);
    EXPECT_NEAR((Dv.segment<2>(2 * r) + s.quadrature.weight(r) * dslip).norm(), 0.0, 1e-8 * s.quadrature.weight(r)) << q;
    EXPECT_GT(dslip.norm(), 0.1);
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// tangential_stiffness is the derivative of T(w)' lambda_t when the tangents do not turn: the
// flat master moving rigidly, the slave nodes freely (central differences).
TEST(TangentialRows3D, TangentialStiffnessIsTheDerivativeOfTheForces) {
  const Pair3 s = blocks3(0.01);
  Eigen::VectorXd w = translation3(s.mesh, mesh::kSlaveBody, Eigen::Vector3d(0.03, -0.02, -0.01));
  Eigen::VectorXd v = translation3(s.mesh, mesh::kMasterBody, Eigen::Vector3d(0.3, -0.2, 0.1));
  const Eigen::VectorXd rw = random_vector(s.mesh.num_dofs(), 0.01, 5), rv = random_vector(s.mesh.num_dofs(), 1.0, 6);
  for (int node : s.pair.slave) {
    w.segment<3>(3 * node) += rw.segment<3>(3 * node);
    v.segment<3>(3 * node) += rv.segment<3>(3 * node);
  }
  const Eigen::VectorXd lambda_t = random_vector(2 * s.quadrature.weight.size(), 1.0, 9);
  const contact::PointwiseContact3 pw = contact::project_slave_nodes(s.mesh, s.pair, w);
  const Eigen::VectorXd Hv = contact::tangential_stiffness<3>(s.mesh, s.pair, s.quadrature, pw, w, lambda_t) * v;
  const double h = 1e-6;
  auto forces = [&](double t) {
    const contact::PointwiseContact3 p = contact::project_slave_nodes(s.mesh, s.pair, w + t * v);
    return Eigen::VectorXd(contact::tangential_rows<3>(s.mesh, s.pair, s.quadrature, p).transpose() * lambda_t);
  };
  const Eigen::VectorXd fd = (forces(h) - forces(-h)) / (2.0 * h);
  EXPECT_GT(Hv.norm(), 1e-3);
  EXPECT_LT((Hv - fd).cwiseAbs().maxCoeff(), 1e-7 * Hv.cwiseAbs().maxCoeff());
}
