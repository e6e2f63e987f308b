// The HF contact solvers in 3D (hf::HFSolver3: Kacanov and semi-smooth Newton on the code path of
// 2D; docs/solvers.md, "Three dimensions") on two stacked blocks with non-matching meshes on their
// common plane (mesh::stacked_blocks): patch tests against the exact uniform-strain solution and
// force balance, rigid translation, symmetry of the pressure about a symmetry plane of mesh and
// load, the KKT conditions at the returned displacement, and the 3D errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/hf/hf_solution_json.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/mesh/structured.hpp"
#include "contactrb/solve/blas_threads.hpp"

using namespace contactrb;

namespace {

using Vec3 = Eigen::Vector3d;

hf::HFSettings kacanov() {
  hf::HFSettings s;
  s.method = hf::HFMethod::Kacanov;
  s.kacanov.alpha = 0.5;
  s.kacanov.tolerance = 1e-12;
  s.kacanov.max_iterations = 500;
  return s;
}

hf::HFSettings newton() {
  hf::HFSettings s;
  s.method = hf::HFMethod::Newton;
  s.newton.tolerance = 1e-11;
  return s;
}

fem::DirichletCondition fixed(const std::string& group, double ux, double uy, double uz) {
  return {group, ux, uy, uz};
}
fem::DirichletCondition sliding_in_z(const std::string& group) { return {group, 0.0, 0.0, std::nullopt}; }

// Confined compression of the two blocks: the master's bottom fixed, the four sides of both blocks
// sliding vertically (ux = uy = 0), the slave's top pushed down by delta (uz = -delta). The exact
// solution is the uniform strain u = (0, 0, u_z(z)) with the same sigma_zz in both bodies.
hf::ContactProblem3 confined_compression(int level, double delta, const fem::Material& slave,
                                         const fem::Material& master) {
  hf::ContactProblem3 problem;
  problem.mesh = mesh::stacked_blocks(level);
  problem.materials = {slave, master};
  problem.dirichlet = {fixed("bottom", 0.0, 0.0, 0.0), sliding_in_z("slave_sides"), sliding_in_z("master_sides"),
                       {"top", std::nullopt, std::nullopt, -delta}};
  return problem;
}

// Constrained modulus lambda + 2 mu: sigma_zz / eps_zz under lateral confinement.
double constrained_modulus(const fem::Material& m) { return m.lame_lambda() + 2.0 * m.lame_mu(); }

// The exact pressure of confined_compression: the shortening delta shared by the two blocks of
// height 1/2 in series.
double exact_pressure(double delta, const fem::Material& slave, const fem::Material& master) {
  return delta / (0.5 / constrained_modulus(slave) + 0.5 / constrained_modulus(master));
}

// The exact uniform-strain displacement of confined_compression at every node: the master block
// [-1/2, 0] and the slave block [0, 1/2] in z, bottom fixed.
Eigen::VectorXd exact_compression(const mesh::Mesh3& mesh, double delta, const fem::Material& slave,
                                  const fem::Material& master) {
  const double p = exact_pressure(delta, slave, master);
  const double eps_master = p / constrained_modulus(master), eps_slave = p / constrained_modulus(slave);
  std::vector<int> body_of(mesh.nodes.size(), -1);
  for (int c = 0; c < mesh.num_cells(); ++c) {
    for (int v : mesh.tetrahedra[static_cast<std::size_t>(c)]) body_of[static_cast<std::size_t>(v)] = mesh.body[static_cast<std::size_t>(c)];
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const double z = mesh.nodes[static_cast<std::size_t>(v)].z();
    u(3 * v + 2) = body_of[static_cast<std::size_t>(v)] == mesh::kMasterBody ? -eps_master * (z + 0.5)
                                                                              : -eps_master * 0.5 - eps_slave * z;
  }
  return u;
}

// The z reaction the imposed displacement of group "top" needs: sum over its nodes of (A u - f)_z.
double top_reaction(const hf::HFSolver3& solver, const Eigen::VectorXd& u) {
  const Eigen::VectorXd residual = solver.stiffness() * u - solver.load();
  double sum = 0.0;
  for (int v : mesh::boundary_nodes(solver.problem().mesh, "top")) sum += residual(3 * v + 2);
  return sum;
}

double max_abs(const Eigen::VectorXd& v) { return v.size() > 0 ? v.cwiseAbs().maxCoeff() : 0.0; }

// lambda >= 0, the gap d = g(u) - K(u) u >= 0 and lambda_r d_r = 0 at the returned u, with the
// geometry re-evaluated there (independent of the solver's own report).
void expect_kkt(const hf::HFSolver3& solver, const hf::HFSolution3& sol, double tol, const std::string& label) {
  const contact::PointwiseContact3 pw = contact::project_slave_nodes(solver.problem().mesh, solver.pair(), sol.u);
  const contact::ConstraintRows rows = contact::constraint_rows(solver.problem().mesh, solver.pair(),
                                                                solver.quadrature(), pw, sol.u);
  const Eigen::VectorXd d = rows.g - rows.K * sol.u;
  const double lmax = std::max(max_abs(sol.lambda), 1e-300);
  const double u_scale = std::max(max_abs(sol.u), 1e-300);
  EXPECT_GE(sol.lambda.minCoeff(), -tol * lmax) << label;
  for (Eigen::Index r = 0; r < d.size(); ++r) {
    const double w = solver.quadrature().weight(r);
    EXPECT_GE(d(r) / w, -tol * u_scale) << label << " row " << r;                                   // no penetration
    EXPECT_LE(std::abs(sol.lambda(r) * d(r) / w), tol * lmax * u_scale) << label << " row " << r;  // complementarity
  }
  EXPECT_LT(sol.kkt.max(), 1e-9) << label;
}

struct PatchFigures {
  double force_error = 0.0;      // |sum_r lambda_r |I_r| n2_z(r) + top reaction| / |top reaction|
  double normal_force_error = 0.0;  // |sum_r lambda_r |I_r| + top reaction| / |top reaction|
  double u_error = 0.0;          // |u - u_exact|_inf / |u_exact|_inf
  double pressure_spread = 0.0;  // max |lambda_r - p| / p, p the exact pressure
};

// The z equilibrium of the slave block: the imposed top displacement's reaction against the
// contact forces K' lambda, whose direction is the normal n2 of the deformed master.
PatchFigures patch_figures(const hf::HFSolver3& solver, const hf::HFSolution3& sol, double p,
                           const Eigen::VectorXd& exact) {
  PatchFigures f;
  const double reaction = top_reaction(solver, sol.u);  // < 0: the top pushes down
  double vertical = 0.0;
  for (Eigen::Index r = 0; r < sol.lambda.size(); ++r) {
    vertical += sol.lambda(r) * solver.quadrature().weight(r) * sol.pointwise.projection[static_cast<std::size_t>(r)].normal.z();
  }
  f.force_error = std::abs(vertical + reaction) / std::abs(reaction);
  f.normal_force_error = std::abs(sol.contact_force + reaction) / std::abs(reaction);
  f.u_error = max_abs(sol.u - exact) / max_abs(exact);
  f.pressure_spread = max_abs((sol.lambda.array() - p).matrix()) / p;
  return f;
}

}  // namespace

// Collocation on non-matching meshes: the contact forces balance the imposed displacement's
// reaction to round-off (the z equilibrium of the slave block, whatever the distribution; the
// forces act along the normal n2 of the deformed master, which the non-uniform interface
// displacement tilts by O(1e-4) here, so sum lambda_r |I_r| itself balances it to O(tilt^2)),
// both solvers converge to the same solution, and it is the exact uniform strain up to the
// non-matching interface's error.
TEST(HF3D, ConfinedCompressionForceBalanceBothSolvers) {
  const fem::Material slave{1.0, 0.3}, master{2.0, 0.25};
  const double delta = 0.01, p = exact_pressure(delta, slave, master);
  for (int level : {0, 1}) {
    const std::string label = "stacked_blocks level " + std::to_string(level);
    const hf::ContactProblem3 problem = confined_compression(level, delta, slave, master);
    const Eigen::VectorXd exact = exact_compression(problem.mesh, delta, slave, master);
    const hf::HFSolver3 solver(problem);
    const hf::HFSolution3 k = solver.solve(kacanov());
    const hf::HFSolution3 n = solver.solve(newton());
    ASSERT_TRUE(k.converged) << label << ": " << k.message;
    ASSERT_TRUE(n.converged) << label << ": " << n.message;
    for (const hf::HFSolution3* s : {&k, &n}) {
      const PatchFigures f = patch_figures(solver, *s, p, exact);
      EXPECT_LT(f.force_error, 1e-10) << label << " " << hf::to_string(s->method);
      EXPECT_LT(f.normal_force_error, 1e-6) << label << " " << hf::to_string(s->method);
      // Collocation on non-matching meshes is not exact (docs/contact.md): the master's nodal
      // forces are the slave weights interpolated, not the consistent ones.
      EXPECT_LT(f.u_error, 0.05) << label << " " << hf::to_string(s->method);
      EXPECT_EQ(s->active_constraints, static_cast<int>(solver.pair().slave.size())) << label;
      expect_kkt(solver, *s, 1e-8, label + " " + hf::to_string(s->method));
    }
    EXPECT_LT((n.u - k.u).norm() / k.u.norm(), 1e-8) << label;
    EXPECT_LT((n.lambda - k.lambda).norm() / k.lambda.norm(), 1e-7) << label;
    EXPECT_LE(n.iterations, 10) << label;
  }
}

// The master held fixed on its contact face, the slave block above it across a gap and pushed
// down further than the gap: collocation reproduces the exact uniform strain and the uniform
// pressure p at every slave node to round-off (the nodal areas are the consistent loads of a
// uniform pressure on P1 triangles), and the contact force balances the reaction.
TEST(HF3D, CompressionOnFixedMasterIsExact) {
  const fem::Material slave{1.0, 0.3}, master{1.0, 0.3};
  const double gap = 0.005, delta = 0.02, p = constrained_modulus(slave) * (delta - gap) / 0.5;
  for (int level : {0, 1}) {
    const std::string label = "stacked_blocks level " + std::to_string(level);
    hf::ContactProblem3 problem = confined_compression(level, delta, slave, master);
    problem.mesh = mesh::stacked_blocks(level, gap);
    problem.dirichlet.push_back(fixed(mesh::kMasterBoundary, 0.0, 0.0, 0.0));
    const hf::HFSolver3 solver(problem);
    Eigen::VectorXd exact = Eigen::VectorXd::Zero(problem.mesh.num_dofs());
    for (int v = 0; v < problem.mesh.num_nodes(); ++v) {
      const double z = problem.mesh.nodes[static_cast<std::size_t>(v)].z();
      if (z >= gap) exact(3 * v + 2) = -gap - (delta - gap) * (z - gap) / 0.5;
    }
    for (const hf::HFSettings& settings : {kacanov(), newton()}) {
      const hf::HFSolution3 s = solver.solve(settings);
      ASSERT_TRUE(s.converged) << label << ": " << s.message;
      const PatchFigures f = patch_figures(solver, s, p, exact);
      EXPECT_LT(f.force_error, 1e-12) << label;
      EXPECT_LT(f.normal_force_error, 1e-12) << label;
      EXPECT_LT(f.u_error, 1e-11) << label << " " << hf::to_string(settings.method);
      EXPECT_LT(f.pressure_spread, 1e-10) << label << " " << hf::to_string(settings.method);
      expect_kkt(solver, s, 1e-10, label + " " + hf::to_string(settings.method));
    }
  }
}

// Both blocks translated by the same imposed displacement, no load: no stress, no contact
// pressure. The multipliers are round-off, whose signs depend on the BLAS threads: the KKT
// report counts them as zero (hf/multiplier_scale.hpp), so Newton converges on one thread too.
TEST(HF3D, RigidTranslationGivesNoStressNoPressure) {
  hf::ContactProblem3 problem;
  problem.mesh = mesh::stacked_blocks(0);
  problem.materials = {fem::Material{1.0, 0.3}, fem::Material{3.0, 0.2}};
  const Vec3 t(0.013, -0.021, 0.034);
  problem.dirichlet = {fixed("bottom", t.x(), t.y(), t.z()), fixed("top", t.x(), t.y(), t.z())};
  const hf::HFSolver3 solver(problem);
  for (const int threads : {1, 2}) {
    for (const hf::HFSettings& settings : {kacanov(), newton()}) {
      const solve::ScopedBlasThreads blas(threads);
      const hf::HFSolution3 s = solver.solve(settings);
      ASSERT_TRUE(s.converged) << threads << " BLAS threads: " << s.message;
      EXPECT_EQ(s.kkt.dual, 0.0) << hf::to_string(settings.method);
      for (int v = 0; v < problem.mesh.num_nodes(); ++v) {
        EXPECT_LT((s.u.segment<3>(3 * v) - t).cwiseAbs().maxCoeff(), 1e-14) << "node " << v;
      }
      const auto stress = fem::element_stress(problem.mesh, problem.materials, s.u);
      EXPECT_LT(stress.cwiseAbs().maxCoeff(), 1e-13) << hf::to_string(settings.method);
      EXPECT_LT(max_abs(s.lambda), 1e-13) << hf::to_string(settings.method);
      EXPECT_LT(std::abs(s.contact_force), 1e-13);
    }
  }
}

// Mesh and load symmetric about the plane x = y (stacked_blocks cuts every cube along its
// (1, 1, 1) diagonal, which the swap of x and y keeps): the slave's top pushed down, its sides
// sliding, the master's sides free, so that the pressure is not uniform (the master bulges over
// its clamped bottom). The pressure at (x, y) equals that at (y, x) to solver tolerance.
TEST(HF3D, PressureSymmetricAboutSymmetryPlane) {
  hf::ContactProblem3 problem;
  problem.mesh = mesh::stacked_blocks(1);
  problem.materials = {fem::Material{1.0, 0.3}, fem::Material{1.0, 0.3}};
  problem.dirichlet = {fixed("bottom", 0.0, 0.0, 0.0), sliding_in_z("slave_sides"),
                       {"top", std::nullopt, std::nullopt, -0.01}};
  const hf::HFSolver3 solver(problem);
  const std::vector<int>& slave = solver.pair().slave;
  std::map<std::pair<long, long>, int> at;  // slave node position (in 1e-9) -> row
  const auto key = [](double x, double y) { return std::make_pair(std::lround(x * 1e9), std::lround(y * 1e9)); };
  for (std::size_t r = 0; r < slave.size(); ++r) {
    const Vec3& X = problem.mesh.nodes[static_cast<std::size_t>(slave[r])];
    at[key(X.x(), X.y())] = static_cast<int>(r);
  }
  for (const hf::HFSettings& settings : {kacanov(), newton()}) {
    const hf::HFSolution3 s = solver.solve(settings);
    ASSERT_TRUE(s.converged) << s.message;
    const Eigen::VectorXd pressure = s.lambda;
    const double pmax = max_abs(pressure), pmin = pressure.minCoeff();
    EXPECT_GT(pmax - pmin, 0.01 * pmax) << "the pressure should not be uniform";
    int pairs = 0;
    for (std::size_t r = 0; r < slave.size(); ++r) {
      const Vec3& X = problem.mesh.nodes[static_cast<std::size_t>(slave[r])];
      const auto mirror = at.find(key(X.y(), X.x()));
      ASSERT_NE(mirror, at.end()) << "slave node " << slave[r] << " has no mirror image";
      EXPECT_NEAR(pressure(static_cast<Eigen::Index>(r)), pressure(mirror->second), 1e-8 * pmax)
          << hf::to_string(settings.method) << " at (" << X.x() << ", " << X.y() << ")";
      pairs += mirror->second != static_cast<int>(r);
    }
    EXPECT_GT(pairs, 0);
    expect_kkt(solver, s, 1e-8, std::string("symmetric ") + hf::to_string(settings.method));
  }
}

// The master's top bent down away from the centre, z -= c r^2 (a convex master, the slave block
// flat above it): the contact zone is a part of the slave face whose size the solve finds, and
// the geometry is nonlinear (normals tilted by up to ~0.1). Kacanov and Newton (with either
// linearization) converge to the same solution, which satisfies the KKT conditions at its own
// geometry.
TEST(HF3D, CurvedMasterPartialContactBothSolversAgree) {
  hf::ContactProblem3 problem;
  problem.mesh = mesh::stacked_blocks(1);
  const double c = 0.1;
  std::vector<char> on_master(problem.mesh.nodes.size(), 0);
  for (int t = 0; t < problem.mesh.num_cells(); ++t) {
    if (problem.mesh.body[static_cast<std::size_t>(t)] != mesh::kMasterBody) continue;
    for (int v : problem.mesh.tetrahedra[static_cast<std::size_t>(t)]) on_master[static_cast<std::size_t>(v)] = 1;
  }
  for (std::size_t v = 0; v < problem.mesh.nodes.size(); ++v) {
    if (!on_master[v]) continue;
    Vec3& X = problem.mesh.nodes[v];
    const double r2 = (X.x() - 0.5) * (X.x() - 0.5) + (X.y() - 0.5) * (X.y() - 0.5);
    X.z() -= c * r2 * (X.z() + 0.5) / 0.5;  // the bottom stays flat
  }
  problem.materials = {fem::Material{1.0, 0.3}, fem::Material{1.0, 0.3}};
  problem.dirichlet = {fixed("bottom", 0.0, 0.0, 0.0), fixed("top", 0.0, 0.0, -0.01)};
  const hf::HFSolver3 solver(problem);
  const hf::HFSolution3 k = solver.solve(kacanov());
  ASSERT_TRUE(k.converged) << k.message;
  expect_kkt(solver, k, 1e-8, "curved kacanov");
  const int S = static_cast<int>(solver.pair().slave.size());
  for (const contact::LinearizationMethod method :
       {contact::LinearizationMethod::Analytic, contact::LinearizationMethod::FiniteDifference}) {
    hf::HFSettings settings = newton();
    settings.newton.linearization.method = method;
    const hf::HFSolution3 n = solver.solve(settings);
    const std::string label = std::string("curved newton ") + contact::to_string(method);
    ASSERT_TRUE(n.converged) << label << ": " << n.message;
    EXPECT_GT(n.active_constraints, S / 10) << label;
    EXPECT_LT(n.active_constraints, S) << label;
    EXPECT_LT((n.u - k.u).norm() / k.u.norm(), 1e-8) << label;
    EXPECT_LT((n.lambda - k.lambda).norm() / k.lambda.norm(), 1e-7) << label;
    EXPECT_LE(n.iterations, 12) << label;
    if (method == contact::LinearizationMethod::FiniteDifference) {  // colours: a Newton-phase step was taken
      int colours = 0;
      for (const hf::NewtonIteration& it : n.newton_history) colours = std::max(colours, it.colours);
      EXPECT_GT(colours, 0) << label << ": no Newton-phase step";
    }
    expect_kkt(solver, n, 1e-8, label);
  }
  // The first iteration's frozen systems on the constraint rows (the 3D default) or on the block of
  // A_00^-1 over every DOF they touch: the same iterates up to round-off.
  hf::HFSettings on_block = newton();
  on_block.newton.tuning.frozen_rows_from_dimension = 4;
  const hf::HFSolution3 g = solver.solve(on_block), r = solver.solve(newton());
  ASSERT_TRUE(g.converged && r.converged) << g.message << r.message;
  EXPECT_EQ(g.iterations, r.iterations);
  ASSERT_FALSE(r.newton_history.empty());
  EXPECT_GT(r.newton_history.front().factorizations, 1) << "the first iteration solved one frozen system only";
  EXPECT_LT((g.u - r.u).norm() / g.u.norm(), 1e-10);
  EXPECT_LT((g.lambda - r.lambda).norm() / g.lambda.norm(), 1e-9);
  EXPECT_LT((r.u - k.u).norm() / k.u.norm(), 1e-8);
}

// A gap between the blocks that the load does not close: no contact, lambda = 0, positive gap.
TEST(HF3D, OpenGapCarriesNoPressure) {
  hf::ContactProblem3 problem;
  problem.mesh = mesh::stacked_blocks(0, 0.05);
  problem.materials = {fem::Material{1.0, 0.3}, fem::Material{1.0, 0.3}};
  problem.dirichlet = {fixed("bottom", 0.0, 0.0, 0.0), fixed("top", 0.0, 0.0, -0.01)};
  const hf::HFSolver3 solver(problem);
  for (const hf::HFSettings& settings : {kacanov(), newton()}) {
    const hf::HFSolution3 s = solver.solve(settings);
    ASSERT_TRUE(s.converged) << s.message;
    EXPECT_EQ(s.active_constraints, 0);
    EXPECT_EQ(max_abs(s.lambda), 0.0);
    EXPECT_EQ(s.gap_violation, 0.0);
  }
}

// The solution record is the one of 2D: rows, pointwise projections and the JSON keys.
TEST(HF3D, SolutionRecordMatches2D) {
  const fem::Material m{1.0, 0.3};
  const hf::HFSolver3 solver(confined_compression(0, 0.01, m, m));
  const hf::HFSolution3 s = solver.solve(newton());
  ASSERT_TRUE(s.converged) << s.message;
  const int S = static_cast<int>(solver.pair().slave.size());
  EXPECT_EQ(s.rows.K.rows(), S);
  EXPECT_EQ(s.rows.K.cols(), solver.problem().mesh.num_dofs());
  ASSERT_EQ(static_cast<int>(s.pointwise.projection.size()), S);
  for (const auto& proj : s.pointwise.projection) EXPECT_TRUE(proj.candidate);
  EXPECT_NEAR(s.contact_force, s.lambda.dot(solver.quadrature().weight), 1e-15);
  EXPECT_GT(s.newton_history.size(), 0u);
  const nlohmann::json j = hf::to_json(s);
  EXPECT_EQ(j.at("converged"), true);
  EXPECT_EQ(hf::discretization_json(solver).at("n_dofs"), solver.problem().mesh.num_dofs());
}

// The contact patch test with the 3D LAC rows (contact/lac3d.hpp) on non-matching meshes: the
// Kacanov solve gives the uniform pressure p at every row and the exact uniform strain to
// round-off, where collocation misses p by about 10 % (the test above); so does the Newton.
TEST(HF3D, LacPassesThePatchTestToRoundOff) {
  const fem::Material slave{1.0, 0.3}, master{2.0, 0.25};
  const double delta = 0.01, p = exact_pressure(delta, slave, master);
  for (int level : {0, 1}) {
    const std::string label = "stacked_blocks level " + std::to_string(level);
    hf::ContactProblem3 problem = confined_compression(level, delta, slave, master);
    problem.discretization = contact::Discretization::LAC;
    const Eigen::VectorXd exact = exact_compression(problem.mesh, delta, slave, master);
    const hf::HFSolver3 solver(problem);
    const hf::HFSolution3 k = solver.solve(kacanov());
    ASSERT_TRUE(k.converged) << label << ": " << k.message;
    const PatchFigures f = patch_figures(solver, k, p, exact);
    std::printf("[ %s, LAC ] pressure spread %.2e, u error %.2e, force balance %.2e, %d iterations\n", label.c_str(),
                f.pressure_spread, f.u_error, f.force_error, k.iterations);
    EXPECT_LT(f.pressure_spread, 1e-10) << label;
    EXPECT_LT(f.u_error, 1e-10) << label;
    EXPECT_LT(f.force_error, 1e-10) << label;
    const hf::HFSolution3 n = solver.solve(newton());
    ASSERT_TRUE(n.converged) << n.message;
    const PatchFigures fn = patch_figures(solver, n, p, exact);
    std::printf("[ %s, LAC, Newton ] pressure spread %.2e, u error %.2e, force balance %.2e, %d iterations\n",
                label.c_str(), fn.pressure_spread, fn.u_error, fn.force_error, n.iterations);
    EXPECT_LT(fn.pressure_spread, 1e-10) << label;
    EXPECT_LT(fn.u_error, 1e-10) << label;
    EXPECT_LT(fn.force_error, 1e-10) << label;
  }
}

// Where the Newton needs the consistent linearization (a curved master, the contact zone a part
// of the slave face), the 3D LAC rows are linearized by coloured differences
// (contact_linearization.hpp): the Newton takes consistent steps and converges to Kacanov's
// solution, which satisfies the KKT conditions at its own geometry.
TEST(HF3D, NewtonOnLacRowsAgreesWithKacanovOnACurvedMaster) {
  hf::ContactProblem3 problem;
  problem.mesh = mesh::stacked_blocks(0);
  for (std::size_t v = 0; v < problem.mesh.nodes.size(); ++v) {
    Vec3& X = problem.mesh.nodes[v];
    if (X.z() > 1e-12) continue;  // the master block: its top face bent down away from the centre
    const double r2 = (X.x() - 0.5) * (X.x() - 0.5) + (X.y() - 0.5) * (X.y() - 0.5);
    X.z() -= 0.1 * r2 * (X.z() + 0.5) / 0.5;
  }
  problem.materials = {fem::Material{1.0, 0.3}, fem::Material{1.0, 0.3}};
  problem.dirichlet = {fixed("bottom", 0.0, 0.0, 0.0), fixed("top", 0.0, 0.0, -0.01)};
  problem.discretization = contact::Discretization::LAC;
  const hf::HFSolver3 solver(problem);
  const hf::HFSolution3 k = solver.solve(kacanov());
  ASSERT_TRUE(k.converged) << k.message;
  expect_kkt(solver, k, 1e-8, "curved LAC kacanov");
  const hf::HFSolution3 n = solver.solve(newton());
  ASSERT_TRUE(n.converged) << n.message;
  const int S = static_cast<int>(solver.pair().slave.size());
  EXPECT_GT(n.active_constraints, 0);
  EXPECT_LT(n.active_constraints, S);
  EXPECT_LT((n.u - k.u).norm() / k.u.norm(), 1e-8);
  EXPECT_LT((n.lambda - k.lambda).norm() / k.lambda.norm(), 1e-7);
  EXPECT_LE(n.iterations, 12);
  int colours = 0;
  for (const hf::NewtonIteration& it : n.newton_history) colours = std::max(colours, it.colours);
  EXPECT_GT(colours, 0) << "no Newton-phase step";
  expect_kkt(solver, n, 1e-8, "curved LAC newton");
}

TEST(HF3D, Errors) {
  const fem::Material m{1.0, 0.3};
  hf::ContactProblem3 missing = confined_compression(0, 0.01, m, m);
  missing.dirichlet.push_back(fixed("lid", 0.0, 0.0, 0.0));
  EXPECT_THROW(hf::HFSolver3{missing}, Error);
  hf::ContactProblem3 one_material = confined_compression(0, 0.01, m, m);
  one_material.materials.pop_back();
  EXPECT_THROW(hf::HFSolver3{one_material}, Error);
}
