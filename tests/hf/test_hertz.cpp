// HF solver on the Hertz geometry (paper Section 6.2, DESIGN.md): symmetry, Hertz theory,
// mesh convergence, KKT conditions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "hf_test_meshes.hpp"

using namespace contactrb;

namespace {
const fem::Material kMat{15.0, 0.35};

hf::ContactProblem hertz_a(double mu, int arc_nodes) {
  mesh::HertzGeometry g;
  g.slave_arc_nodes = arc_nodes;
  hf::ContactProblem p;
  p.mesh = mesh::generate_hertz(g);
  p.materials = {kMat, kMat};
  p.dirichlet = {{"top", 0.0, -0.5 * mu}, {"bottom", 0.0, 0.5 * mu}};
  return p;
}

hf::HFSettings tight() {
  hf::HFSettings s;
  s.kacanov.alpha = 1.0;
  s.kacanov.tolerance = 1e-10;
  return s;
}
}  // namespace

// hertz-a with matching mirrored meshes is symmetric about y = 0: each half-disk sees a
// frictionless rigid plane at half the gap. The rigid plane is a clamped block whose top
// edge is the master boundary. The discrete two-body problem is not exactly mirror
// symmetric (node-to-segment: slave and master play different roles, and at the two edges
// of the contact zone the continuous master normal carries half the kink of the deformed
// master), so the two solutions agree up to a discretization error that must vanish
// under refinement; the total force agrees much more closely than pointwise values.
namespace {
struct SymmetryGap {
  double lambda = 0.0;  // max |lambda_1 - lambda_2| / max lambda_2
  double force = 0.0;   // relative contact-force difference
  double kkt = 0.0;
};
SymmetryGap symmetric_vs_plane(int arc_nodes) {
  const double mu = 0.3;
  const hf::ContactProblem two = hertz_a(mu, arc_nodes);
  hf::ContactProblem one;
  const mesh::Mesh upper = test_meshes::extract_body(two.mesh, mesh::kSlaveBody, mesh::kSlaveBody);
  mesh::Mesh plane = mesh::rectangle(-1.5, -0.3, 1.5, 0.0, 60, 6, mesh::kMasterBody);
  mesh::rename_boundary(plane, "top", mesh::kMasterBoundary);
  one.mesh = mesh::merge(upper, plane);
  one.materials = {kMat, kMat};
  one.dirichlet = {{"top", 0.0, -0.5 * mu}, {"bottom", 0.0, 0.0}, {"left", 0.0, 0.0},
                   {"right", 0.0, 0.0}, {mesh::kMasterBoundary, 0.0, 0.0}};
  const hf::HFSolution s2 = hf::HFSolver(two).solve(tight());
  const hf::HFSolution s1 = hf::HFSolver(one).solve(tight());
  EXPECT_TRUE(s2.converged) << s2.message;
  EXPECT_TRUE(s1.converged) << s1.message;
  EXPECT_EQ(s1.lambda.size(), s2.lambda.size());
  SymmetryGap gap;
  gap.lambda = (s1.lambda - s2.lambda).cwiseAbs().maxCoeff() / s2.lambda.maxCoeff();
  gap.force = std::abs(s1.contact_force - s2.contact_force) / s2.contact_force;
  gap.kkt = std::max(s1.kkt.max(), s2.kkt.max());
  return gap;
}
}  // namespace

TEST(Hertz, SymmetricTwoBodyApproachesHalfDiskOnRigidPlane) {
  const SymmetryGap coarse = symmetric_vs_plane(51);
  const SymmetryGap fine = symmetric_vs_plane(101);
  std::printf("[ report ] two-body vs rigid plane: lambda %.2e -> %.2e, force %.2e -> %.2e\n", coarse.lambda,
              fine.lambda, coarse.force, fine.force);
  EXPECT_LT(coarse.kkt, 1e-8);
  EXPECT_LT(fine.kkt, 1e-8);
  EXPECT_LT(coarse.lambda, 1e-2);
  EXPECT_LT(fine.lambda, coarse.lambda);
  EXPECT_LT(coarse.force, 1e-4);
  EXPECT_LT(fine.force, 1e-4);
}

// Two cylinders in plane strain (Hertz): p(x) = p0 sqrt(1 - x^2/a^2) with
// a = sqrt(4 P R* / (pi E*)), p0 = 2 P / (pi a), 1/R* = 1/R1 + 1/R2, 1/E* = 2 (1 - nu^2)/E.
// At a small load (mu = 0.13: an overlap of 0.03, a/R about 0.1) the half-disks behave
// locally like cylinders. We fit p^2 = p0^2 (1 - x^2/a^2) on the active nodes (least
// squares in x^2) and compare a and p0 with the theory driven by the computed total force
// P. Tolerance 5%: the contact zone spans 2a/h = 15 elements of the 241-node arc
// (h = pi/240), so the edge of the zone is located within h/2, about 6% of a for one node,
// reduced by the fit over 15 nodes; the finite size of the half-disks (flat edges at
// distance R) changes the local solution by O((a/R)^2), about 1%. Measured: a within 2%,
// p0 within 1.5%.
TEST(Hertz, AgreesWithHertzTheoryAtSmallLoad) {
  const hf::ContactProblem p = hertz_a(0.13, 241);
  const hf::HFSolver solver(p);
  const hf::HFSolution s = solver.solve(tight());
  ASSERT_TRUE(s.converged) << s.message;
  const double P = s.contact_force;
  const double Rstar = 0.5;
  const double Estar = kMat.E / (2.0 * (1.0 - kMat.nu * kMat.nu));
  const double a_theory = std::sqrt(4.0 * P * Rstar / (std::numbers::pi * Estar));
  const double p0_theory = 2.0 * P / (std::numbers::pi * a_theory);
  // Least-squares fit of p^2 = alpha + beta x^2 over active slave nodes.
  const auto& q = solver.quadrature();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (int r = 0; r < s.lambda.size(); ++r) {
    if (s.lambda(r) <= 0.0) continue;
    const double x = p.mesh.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])].x();
    const double X = x * x, Y = s.lambda(r) * s.lambda(r);
    sx += X; sy += Y; sxx += X * X; sxy += X * Y; ++n;
  }
  ASSERT_GE(n, 12);
  const double beta = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double alpha = (sy - beta * sx) / n;
  const double p0_fit = std::sqrt(alpha), a_fit = std::sqrt(-alpha / beta);
  std::printf("[ report ] Hertz: P = %.5f, a = %.4f (theory %.4f), p0 = %.4f (theory %.4f), %d active\n", P,
              a_fit, a_theory, p0_fit, p0_theory, n);
  EXPECT_NEAR(a_fit / a_theory, 1.0, 0.05);
  EXPECT_NEAR(p0_fit / p0_theory, 1.0, 0.05);
}

TEST(Hertz, EnergyAndForceConvergeUnderRefinement) {
  std::vector<double> energy, force;
  for (int arc : {31, 61, 121}) {
    const hf::HFSolution s = hf::HFSolver(hertz_a(0.3, arc)).solve(tight());
    ASSERT_TRUE(s.converged) << s.message;
    energy.push_back(s.energy);
    force.push_back(s.contact_force);
  }
  const double de1 = std::abs(energy[1] - energy[0]), de2 = std::abs(energy[2] - energy[1]);
  const double df1 = std::abs(force[1] - force[0]), df2 = std::abs(force[2] - force[1]);
  std::printf("[ report ] energy %.6f %.6f %.6f, force %.6f %.6f %.6f\n", energy[0], energy[1], energy[2],
              force[0], force[1], force[2]);
  EXPECT_LT(de2, 0.6 * de1);
  EXPECT_LT(df2, 0.6 * df1);
}

TEST(Hertz, PaperSettingsConvergeWithSmallKkt) {
  const hf::HFSolution s = hf::HFSolver(hertz_a(0.3, 51)).solve({});
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_GT(s.iterations, 3);
  EXPECT_LT(s.iterations, 60);
  EXPECT_LT(s.kkt.max(), 1e-8);
  EXPECT_GT(s.active_constraints, 3);
  EXPECT_LT(s.gap_violation, 1e-2 * 0.1);
}

// At alpha = 1e-4 the relaxed increment of the first step passes (63) as printed, which would
// answer "converged" after one iteration with the contact force 5% off (1.398 against 1.4726)
// and a penetration of 1.4e-2. The stopping test reads the unrelaxed step (docs/theory.md,
// "Kacanov (12)"): such an iteration is not converged within its cap, and the paper's alpha = 0.3 lands on
// the undamped (alpha = 1) solution within the tolerance's reach.
TEST(Hertz, StoppingTestDoesNotDependOnTheRelaxation) {
  const hf::HFSolver solver(hertz_a(0.3, 51));
  hf::HFSettings tiny;
  tiny.kacanov.alpha = 1e-4;
  tiny.kacanov.max_iterations = 30;
  const hf::HFSolution s_tiny = solver.solve(tiny);
  EXPECT_FALSE(s_tiny.converged);
  EXPECT_EQ(s_tiny.status, solve::KacanovStatus::MaxIterations);
  EXPECT_EQ(s_tiny.iterations, 30);

  const hf::HFSolution exact = solver.solve(tight());
  ASSERT_TRUE(exact.converged) << exact.message;
  for (double alpha : {1.0, 0.3, 0.1}) {
    hf::HFSettings paper;  // eps_KA = 1e-3
    paper.kacanov.alpha = alpha;
    paper.kacanov.max_iterations = 2000;
    const hf::HFSolution s = solver.solve(paper);
    ASSERT_TRUE(s.converged) << "alpha " << alpha << ": " << s.message;
    std::printf("[ report ] alpha %.2f: %d iterations, force %.6f (exact %.6f), gap violation %.2e\n", alpha,
                s.iterations, s.contact_force, exact.contact_force, s.gap_violation);
    EXPECT_NEAR(s.contact_force / exact.contact_force, 1.0, 3e-3) << "alpha " << alpha;
    EXPECT_LT(s.gap_violation, 1e-3 * 0.1) << "alpha " << alpha;
  }
}
