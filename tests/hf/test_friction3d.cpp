// Frictional contact in 3D (docs/solvers.md, "Friction"): the isotropic Coulomb cone, the
// frictionless and tied limits, mirror symmetry (block-on-block-3d), Cattaneo-Mindlin (cattaneo-3d).
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SparseLU>
#include <cmath>
#include <cstdio>
#include <map>

#include "contactrb/cases/frictional_cases.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/tangential_rows.hpp"
#include "contactrb/hf/friction.hpp"
#include "support/tied_interface.hpp"

using namespace contactrb;

namespace {

void print_steps(const char* what, const hf::FrictionalSolution3& s) {
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    const hf::FrictionStepReport& r = s.steps[i];
    std::printf("[ report ] %s step %zu: %s, %d iterations, P %.6g, Q (%.4g, %.4g), stick %d slip %d open %d, %.3f s\n",
                what, i + 1, hf::to_string(r.status), r.iterations, r.normal_force, r.tangential_force(0),
                r.tangential_force(1), r.stick, r.slip, r.open, r.time_s);
  }
}

// The components of row r's tangential traction along its pair.
Eigen::Vector2d traction(const hf::FrictionalSolution3& s, int r) { return s.lambda_t.segment<2>(2 * r); }

// The level-0 case with a slip zone along the slave's rim and a stick zone inside.
cases::FrictionalCase3 shear_case() { return cases::block_on_block_3d_case(0, {0.004, {0.0006, 0.0003}, 0.3, 2}); }
const hf::FrictionalSolution3& shear_run() {
  static const hf::FrictionalSolution3 s = [] {
    const cases::FrictionalCase3 c = shear_case();
    return hf::solve_load_path(c.problem, c.path, c.friction);
  }();
  return s;
}

// The tangential traction of each row as a vector, sum_j lambda_t,rj tau_j, with the pair tau at
// the normal of the state u (rows are the slave nodes: collocation).
std::vector<Eigen::Vector3d> traction_vectors(const hf::ContactProblem3& p, const hf::FrictionalSolution3& s) {
  const hf::HFSolver3 solver(p);
  const contact::PointwiseContact3 pw = contact::project_slave_nodes(p.mesh, solver.pair(), s.u);
  std::vector<Eigen::Vector3d> t(pw.projection.size());
  for (std::size_t q = 0; q < t.size(); ++q) {
    t[q] = contact::tangent_basis<3>(pw.projection[q].normal) * s.lambda_t.segment<2>(2 * static_cast<Eigen::Index>(q));
  }
  return t;
}

// The frictionless Newton answer with the last load step's Dirichlet data of a case's path.
hf::HFSolution3 frictionless_at_path_end(const cases::FrictionalCase3& c) {
  hf::ContactProblem3 last = c.problem;
  last.dirichlet = c.path.back().dirichlet;
  hf::HFSettings newton;
  newton.method = hf::HFMethod::Newton;
  return hf::HFSolver3(last).solve(newton);
}

}  // namespace

// Coulomb's isotropic cone at every node: |t| <= f p to round-off; on the slip nodes |t| = f p and
// t opposes the slip of the last step: t = -f p g / |g| (the traction on the slave, g the slave's
// slip in the step, the total slip of the path minus that of the path without its last step).
TEST(Friction3D, CoulombConeHoldsAndSlipNodesOpposeTheirSlip) {
  const hf::FrictionalSolution3& s = shear_run();
  cases::FrictionalCase3 c = shear_case();
  c.path.pop_back();
  const hf::FrictionalSolution3 before = hf::solve_load_path(c.problem, c.path, c.friction);
  ASSERT_TRUE(before.converged) << before.message;
  print_steps("shear", s);
  ASSERT_TRUE(s.converged) << s.message;
  const double kF = 0.3;
  const double round_off = 1e-9 * s.lambda.cwiseAbs().maxCoeff();
  int slip = 0;
  for (int r = 0; r < s.lambda.size(); ++r) {
    const Eigen::Vector2d t = traction(s, r);
    const double p = s.lambda(r);
    EXPECT_LE(t.norm(), kF * std::max(p, 0.0) + round_off) << "row " << r;
    if (s.state[static_cast<std::size_t>(r)] != hf::SlipState::Slip) continue;
    ++slip;
    EXPECT_NEAR(t.norm(), kF * p, round_off) << "row " << r;
    const Eigen::Vector2d g = s.slip.segment<2>(2 * r) - before.slip.segment<2>(2 * r);
    ASSERT_GT(g.norm(), 0.0) << "row " << r;
    EXPECT_LT((t + kF * p * g.normalized()).norm(), 1e-6 * kF * p) << "row " << r << ": t does not oppose the slip";
  }
  EXPECT_GE(slip, 8);
  EXPECT_GE(s.stick_nodes, 8);
  EXPECT_LE(s.kkt.max(), 1e-10);
  // The tangential force points along the imposed displacement (2, 1) / sqrt(5), on the slave
  // against it: the master holds the slave back.
  const Eigen::Vector2d Q = s.tangential_force;
  EXPECT_LT(Q.normalized().dot(Eigen::Vector2d(2.0, 1.0).normalized()), -0.99);
}

// Tresca with a zero threshold goes through the frictional iteration and gives the frictionless
// 3D answer (to the tolerances of the two solvers); Coulomb f = 0 is that answer bit for bit.
TEST(Friction3D, ZeroThresholdIsTheFrictionlessAnswer) {
  cases::FrictionalCase3 c = cases::block_on_block_3d_case(0, {0.004, {0.0006, 0.0003}, 0.0, 2});
  const hf::HFSolution3 h = frictionless_at_path_end(c);
  ASSERT_TRUE(h.converged) << h.message;
  hf::HFSettings newton;
  newton.method = hf::HFMethod::Newton;
  const hf::FrictionalSolution3 off = hf::solve_load_path(c.problem, c.path, c.friction, newton);
  EXPECT_TRUE(off.u == h.u);
  hf::FrictionSettings tresca;
  tresca.law = hf::FrictionLaw::Tresca;
  tresca.threshold = 0.0;
  const hf::FrictionalSolution3 s = hf::solve_load_path(c.problem, c.path, tresca);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_EQ(s.steps.size(), c.path.size());
  EXPECT_LT((s.lambda - h.lambda).cwiseAbs().maxCoeff() / h.lambda.maxCoeff(), 1e-8);
  EXPECT_LT((s.u - h.u).cwiseAbs().maxCoeff() / h.u.cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(s.lambda_t.cwiseAbs().maxCoeff(), 1e-10 * h.lambda.maxCoeff());
}

// A very large f: every node sticks where it touched at rest, the answer of the tied interface
// u_s = sum_i phi_i u_{t_i} (each slave node glued to the master point below it, the barycentric
// coordinates phi of the undeformed projection), solved here as an equality-constrained system.
TEST(Friction3D, LargeCoefficientGivesTheTiedAnswer) {
  const cases::FrictionalCase3 c = cases::block_on_block_3d_case(0, {0.004, {0.0006, 0.0003}, 1e6, 1});
  const std::vector<hf::LoadStep3> path{c.path.back()};
  hf::ContactProblem3 p = c.problem;
  p.dirichlet = path.back().dirichlet;
  const hf::FrictionalSolution3 s = hf::solve_load_path(p, path, c.friction);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_EQ(s.stick_nodes, static_cast<int>(s.lambda.size()));
  const hf::HFSolver3 solver(p);
  const contact::PointwiseContact3 rest =
      contact::project_slave_nodes(p.mesh, solver.pair(), Eigen::VectorXd::Zero(p.mesh.num_dofs()));
  std::vector<test_support::Tie> ties;
  for (std::size_t q = 0; q < solver.pair().slave.size(); ++q) {
    const contact::SlaveProjection3& pr = rest.projection[q];
    ASSERT_TRUE(pr.candidate);
    ASSERT_LT(pr.distance, 1e-12);
    const std::array<int, 3>& f = solver.pair().master_faces[static_cast<std::size_t>(pr.facet)];
    for (int comp = 0; comp < 3; ++comp) {
      test_support::Tie tie{{3 * solver.pair().slave[q] + comp, 1.0}};
      for (int i = 0; i < 3; ++i) {
        tie.emplace_back(3 * solver.pair().master[static_cast<std::size_t>(f[static_cast<std::size_t>(i)])] + comp, -pr.phi(i));
      }
      ties.push_back(tie);
    }
  }
  const Eigen::VectorXd tied = test_support::tied_displacement(solver, ties);
  ASSERT_EQ(tied.size(), s.u.size());
  const double diff = (s.u - tied).cwiseAbs().maxCoeff() / tied.cwiseAbs().maxCoeff();
  std::printf("[ report ] f = 1e6 against the tied interface: max |u - u_tied| / max |u| = %.2e\n", diff);
  EXPECT_LT(diff, 1e-8);
}

// A load symmetric about the plane x = y (the tangential displacement along (1, 1), both meshes
// symmetric about that plane): the pressures are symmetric and the tangential tractions mirror
// each other, t(y, x) = (t_y, t_x, t_z)(x, y) as vectors (the components along the pairs are not
// mirror images: the pair follows the axes), row by row.
TEST(Friction3D, LoadSymmetricAboutAPlaneGivesMirrorTractions) {
  const cases::FrictionalCase3 c = cases::block_on_block_3d_case(0, {0.004, {0.0005, 0.0005}, 0.3, 1});
  const hf::FrictionalSolution3 s = hf::solve_load_path(c.problem, c.path, c.friction);
  print_steps("symmetric", s);
  ASSERT_TRUE(s.converged) << s.message;
  const hf::HFSolver3 solver(c.problem);
  const auto& q = solver.quadrature();
  const std::vector<Eigen::Vector3d> t = traction_vectors(c.problem, s);
  std::map<std::pair<long, long>, int> row_at;
  auto key = [](const Eigen::Vector3d& x) { return std::pair{std::lround(x.x() * 1e9), std::lround(x.y() * 1e9)}; };
  for (int r = 0; r < s.lambda.size(); ++r) row_at[key(c.problem.mesh.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])])] = r;
  const double scale = s.lambda.cwiseAbs().maxCoeff();
  int slip = 0;
  for (int r = 0; r < s.lambda.size(); ++r) {
    const Eigen::Vector3d x = c.problem.mesh.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])];
    const auto it = row_at.find(key(Eigen::Vector3d(x.y(), x.x(), x.z())));
    ASSERT_NE(it, row_at.end()) << "no mirror node of row " << r;
    const int m = it->second;
    EXPECT_NEAR(s.lambda(r), s.lambda(m), 1e-8 * scale) << r;
    const Eigen::Vector3d mirrored(t[static_cast<std::size_t>(m)].y(), t[static_cast<std::size_t>(m)].x(),
                                   t[static_cast<std::size_t>(m)].z());
    EXPECT_LT((t[static_cast<std::size_t>(r)] - mirrored).norm(), 1e-8 * scale) << r;
    EXPECT_EQ(s.state[static_cast<std::size_t>(r)], s.state[static_cast<std::size_t>(m)]) << r;
    slip += s.state[static_cast<std::size_t>(r)] == hf::SlipState::Slip;
  }
  EXPECT_GE(slip, 4);
  EXPECT_GT(s.tangential_force.norm(), 1e-3 * s.contact_force);
}

TEST(Friction3D, CaseRefusesBadData) {
  EXPECT_THROW(cases::block_on_block_3d_case(3), Error);
  EXPECT_THROW(cases::block_on_block_3d_case(0, {0.0, {0.0, 0.0}, 0.3, 1}), Error);
  EXPECT_THROW(cases::block_on_block_3d_case(0, {0.004, {NAN, 0.0}, 0.3, 1}), Error);
  EXPECT_THROW(cases::block_on_block_3d_case(0, {0.004, {0.0, 0.0}, -0.1, 1}), Error);
  EXPECT_THROW(cases::block_on_block_3d_case(0, {0.004, {0.0, 0.0}, 0.3, 0}), Error);
  EXPECT_THROW(cases::cattaneo_3d_case(3), Error);
  EXPECT_THROW(cases::cattaneo_3d_case(0, {0.2, 0.002, 0.3, 1}), Error);
  EXPECT_THROW(cases::cattaneo_3d_case(0, {0.02, INFINITY, 0.3, 1}), Error);
  EXPECT_THROW(cases::cattaneo_3d_case(0, {0.02, 0.002, -1.0, 1}), Error);
  EXPECT_THROW(cases::cattaneo_3d_case(0, {0.02, 0.002, 0.3, 0}), Error);
}

// Level 1 (about 7000 nodes): every load step converges in at most 15 Newton iterations (the
// figures of docs/solvers.md, "Friction": the step times against the frictionless Newton solve of
// the last step's data on the same mesh).
TEST(Friction3D, Level1StepsConvergeInFewIterations) {
  const cases::FrictionalCase3 c = cases::block_on_block_3d_case(1, {0.004, {0.0006, 0.0003}, 0.3, 2});
  const hf::FrictionalSolution3 s = hf::solve_load_path(c.problem, c.path, c.friction);
  print_steps("level 1", s);
  ASSERT_TRUE(s.converged) << s.message;
  for (const hf::FrictionStepReport& r : s.steps) EXPECT_LE(r.iterations, 15);
  EXPECT_GT(s.slip_nodes, 0);
  EXPECT_GT(s.stick_nodes, 0);
  const hf::HFSolution3 h = frictionless_at_path_end(c);
  ASSERT_TRUE(h.converged) << h.message;
  std::printf("[ report ] level 1: %lld rows; frictionless Newton %d iterations, %.3f s; frictional path %.3f s\n",
              static_cast<long long>(s.lambda.size()), h.iterations, h.time_s, s.time_s);
}

// Cattaneo-Mindlin for spheres of the same material (Johnson, Contact Mechanics, 7.2): under a
// tangential force Q < f P after the normal load, the stick zone is r < c with
// c / a = (1 - Q / (f P))^(1/3). In the stick zone f p - |t| = f p0 (c/a) sqrt(1 - r^2/c^2), so
// (f p - |t|)^2 is linear in r^2: c from a least-squares fit over the stick nodes, a from the
// same fit of p^2 over the nodes in contact (as tests/hf/test_hertz.cpp), r the deformed distance
// to the centre of pressure.
struct StickRadius {
  double ratio = 0.0, c_over_a = 0.0, truth = 0.0, a = 0.0;
};
StickRadius cattaneo_3d_stick_radius(int level) {
  const double f = 0.3;
  const cases::FrictionalCase3 c = cases::cattaneo_3d_case(level, {0.02, 0.0035, f, 1});
  const hf::FrictionalSolution3 s = hf::solve_load_path(c.problem, c.path, c.friction);
  print_steps("cattaneo-3d", s);
  EXPECT_TRUE(s.converged) << s.message;
  const hf::HFSolver3 solver(c.problem);
  const auto& q = solver.quadrature();
  const auto R = s.lambda.size();
  std::vector<Eigen::Vector2d> x(static_cast<std::size_t>(R));
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double P = 0.0;
  for (int r = 0; r < R; ++r) {
    const int node = q.center_node[static_cast<std::size_t>(r)];
    const Eigen::Vector3d y = c.problem.mesh.nodes[static_cast<std::size_t>(node)] + s.u.segment<3>(3 * node);
    x[static_cast<std::size_t>(r)] = y.head<2>();
    centre += s.lambda(r) * q.weight(r) * y.head<2>();
    P += s.lambda(r) * q.weight(r);
  }
  centre /= P;
  auto fit = [&](auto select, auto value) {  // least squares v = alpha + beta r^2
    Eigen::MatrixXd A(0, 2);
    Eigen::VectorXd b(0);
    for (int r = 0; r < R; ++r) {
      if (!select(r)) continue;
      A.conservativeResize(A.rows() + 1, 2);
      b.conservativeResize(b.size() + 1);
      A.row(A.rows() - 1) << 1.0, (x[static_cast<std::size_t>(r)] - centre).squaredNorm();
      b(b.size() - 1) = value(r);
    }
    const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(b);
    return std::sqrt(-ab(0) / ab(1));
  };
  const double a = fit([&](int r) { return s.lambda(r) > 0.0; }, [&](int r) { return s.lambda(r) * s.lambda(r); });
  const double cr = fit([&](int r) { return s.state[static_cast<std::size_t>(r)] == hf::SlipState::Stick && s.lambda(r) > 0.0; },
                        [&](int r) { return std::pow(f * s.lambda(r) - s.lambda_t.segment<2>(2 * r).norm(), 2); });
  const double ratio = std::abs(s.tangential_force(0)) / (f * s.contact_force);
  const double truth = std::cbrt(1.0 - ratio);
  std::printf("[ report ] cattaneo-3d level %d: Q/(fP) = %.3f, a = %.4f, c = %.4f, c/a = %.3f against %.3f (%+.1f %%), "
              "stick %d slip %d, tangential step %d iterations %.3f s\n",
              level, ratio, a, cr, cr / a, truth, 100.0 * (cr / a / truth - 1.0), s.stick_nodes, s.slip_nodes,
              s.steps.back().iterations, s.steps.back().time_s);
  return {ratio, cr / a, truth, a};
}

// Tolerances: the stick edge lies between a stick and a slip node, so one node reads c to within
// half a mesh size h near the contact, h / (2 c) = 18 % on level 0 (h = 0.04, c about 0.11) and
// 9 % on level 1; the fit over every stick node (35 on level 0, 135 on level 1) averages that
// error down, and the bounds are half of it: 10 % and the 5 % of the 2D check.
TEST(Friction3D, CattaneoMindlinStickRadiusLevel0) {
  const StickRadius m = cattaneo_3d_stick_radius(0);
  EXPECT_GT(m.ratio, 0.4);
  EXPECT_LT(m.ratio, 0.6);
  EXPECT_NEAR(m.c_over_a / m.truth, 1.0, 0.1);
}

TEST(Friction3D, CattaneoMindlinStickRadiusLevel1) {
  const StickRadius m = cattaneo_3d_stick_radius(1);
  EXPECT_NEAR(m.c_over_a / m.truth, 1.0, 0.05);
  cases::FrictionalCase3 c = cases::cattaneo_3d_case(1, {0.02, 0.0035, 0.3, 1});
  c.problem.dirichlet = c.path.back().dirichlet;
  hf::HFSettings newton;
  newton.method = hf::HFMethod::Newton;
  const hf::HFSolution3 h = hf::HFSolver3(c.problem).solve(newton);
  ASSERT_TRUE(h.converged) << h.message;
  std::printf("[ report ] cattaneo-3d level 1: frictionless Newton of the final data %d iterations, %.3f s\n", h.iterations,
              h.time_s);
}
