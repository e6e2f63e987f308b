// The Hertz sphere problem in 3D (docs/solvers.md, "Three dimensions"; docs/cases.md, "hertz-3d"):
// the quarter model of a sphere R = 1 on a block, LAC rows, Kacanov. From the measured contact
// force F (four times the model's), Hertz's half-space solution gives a = (3 F R / (4 E*))^(1/3)
// and p0 = 3 F / (2 pi a^2) with E* = E / (2 (1 - nu^2)); the discrete pressure fitted as
// p^2 = p0^2 (1 - r^2 / a^2) over the inner active rows must give both within 5 %, and closer on
// the finer mesh (level 2: 16 slave nodes across the contact radius along each symmetry axis).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/hf/hf_solver.hpp"

namespace {

namespace cases = contactrb::cases;
namespace hf = contactrb::hf;

struct HertzFit {
  double a_hertz = 0.0, p0_hertz = 0.0;  // from the force
  double a_fit = 0.0, p0_fit = 0.0;      // from the pressure profile
  int active = 0;
};

HertzFit hertz_fit(int level) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3d");
  const cases::Mu mu = cases::Mu::Constant(1, 0.02);
  const hf::HFSolver3 solver(cases::make_problem(spec, cases::reference_mesh3(spec, level), mu,
                                                 contactrb::contact::Discretization::LAC));
  hf::HFSettings settings;  // Kacanov, eps_KA 1e-3
  const hf::HFSolution3 s = solver.solve(settings);
  EXPECT_TRUE(s.converged) << s.message;
  const auto& mesh = solver.problem().mesh;
  const auto& q = solver.quadrature();
  const double E = 15.0, nu = 0.3, R = 1.0;
  const double E_star = E / (2.0 * (1.0 - nu * nu));
  HertzFit f;
  const double F = 4.0 * s.contact_force;
  f.a_hertz = std::cbrt(3.0 * F * R / (4.0 * E_star));
  f.p0_hertz = 3.0 * F / (2.0 * M_PI * f.a_hertz * f.a_hertz);
  std::vector<double> r2, p2;
  double r_max = 0.0;
  for (Eigen::Index r = 0; r < s.lambda.size(); ++r) {
    if (!(s.lambda(r) > 0.0)) continue;
    const auto& x = mesh.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])];
    r_max = std::max(r_max, std::hypot(x.x(), x.y()));
    ++f.active;
  }
  for (Eigen::Index r = 0; r < s.lambda.size(); ++r) {
    const auto& x = mesh.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])];
    const double rr = std::hypot(x.x(), x.y());
    if (!(s.lambda(r) > 0.0) || rr >= 0.8 * r_max) continue;  // the inner rows: away from the edge
    r2.push_back(rr * rr);
    p2.push_back(s.lambda(r) * s.lambda(r));
  }
  // Least squares p^2 = c0 + c1 r^2: p0 = sqrt(c0), a = sqrt(-c0 / c1).
  const double n = static_cast<double>(r2.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < r2.size(); ++i) {
    sx += r2[i];
    sy += p2[i];
    sxx += r2[i] * r2[i];
    sxy += r2[i] * p2[i];
  }
  const double c1 = (n * sxy - sx * sy) / (n * sxx - sx * sx), c0 = (sy - c1 * sx) / n;
  f.p0_fit = std::sqrt(c0);
  f.a_fit = std::sqrt(-c0 / c1);
  std::printf("[ hertz-3d level %d ] %d active rows: a %.4f (Hertz %.4f, %+.2f %%), p0 %.4f (Hertz %.4f, %+.2f %%)\n",
              level, f.active, f.a_fit, f.a_hertz, 100.0 * (f.a_fit / f.a_hertz - 1.0), f.p0_fit, f.p0_hertz,
              100.0 * (f.p0_fit / f.p0_hertz - 1.0));
  return f;
}

}  // namespace

TEST(Hertz3d, ContactRadiusAndPeakPressureWithinFivePercent) {
  const HertzFit coarse = hertz_fit(1);
  EXPECT_NEAR(coarse.a_fit / coarse.a_hertz, 1.0, 0.05);
  EXPECT_NEAR(coarse.p0_fit / coarse.p0_hertz, 1.0, 0.05);
  const HertzFit fine = hertz_fit(2);
  EXPECT_NEAR(fine.a_fit / fine.a_hertz, 1.0, 0.05);
  EXPECT_NEAR(fine.p0_fit / fine.p0_hertz, 1.0, 0.05);
  // Closer on the finer mesh.
  EXPECT_LT(std::abs(fine.a_fit / fine.a_hertz - 1.0), std::abs(coarse.a_fit / coarse.a_hertz - 1.0));
  EXPECT_LT(std::abs(fine.p0_fit / fine.p0_hertz - 1.0), std::abs(coarse.p0_fit / coarse.p0_hertz - 1.0));
  EXPECT_GT(fine.active, 3 * coarse.active);
}

// Collocation on the quarter model: the slave nodes on the symmetry planes lie above the master's
// rim edges there; with ProjectionOptions::rim_angle_tolerance they stay candidates as the
// master triangles tilt, and both solvers converge (without it Kacanov and the Newton cycle).
TEST(Hertz3d, CollocationConvergesOnTheQuarterModel) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3d");
  for (int level : {0, 1}) {
    const hf::HFSolver3 solver(cases::make_problem(spec, cases::reference_mesh3(spec, level), cases::Mu::Constant(1, 0.03)));
    const hf::HFSolution3 k = solver.solve(hf::HFSettings{});
    hf::HFSettings newton;
    newton.method = hf::HFMethod::Newton;
    const hf::HFSolution3 n = solver.solve(newton);
    ASSERT_TRUE(k.converged) << "level " << level << ": " << k.message;
    ASSERT_TRUE(n.converged) << "level " << level << ": " << n.message;
    EXPECT_LE(n.iterations, 10) << "level " << level;
    EXPECT_EQ(n.active_constraints, k.active_constraints) << "level " << level;
    EXPECT_NEAR(n.contact_force, k.contact_force, 1e-3 * k.contact_force) << "level " << level;
    std::printf("[ hertz-3d level %d, collocation ] Kacanov %d, Newton %d iterations, force %.6e\n", level,
                k.iterations, n.iterations, n.contact_force);
  }
}

namespace {

hf::HFSolver3 hertz_lac_solver(int level) {
  const cases::CaseSpec spec = cases::builtin_case_spec("hertz-3d");
  return hf::HFSolver3(cases::make_problem(spec, cases::reference_mesh3(spec, level), cases::Mu::Constant(1, 0.02),
                                           contactrb::contact::Discretization::LAC));
}

hf::HFSettings tight_kacanov() {
  hf::HFSettings s;
  s.kacanov.tolerance = 1e-10;
  s.kacanov.max_iterations = 2000;
  return s;
}

}  // namespace

// The linearization of the 3D LAC rows (coloured central differences, contact_linearization.hpp)
// at the Kacanov solution on the sphere, against plain central differences of the maps one DOF at
// a time over every free DOF of the contact surfaces' nodes (the maps read no other node), with
// the solution's pressures as lambda. A missing row input would leave an entry of the order of the
// largest one out; truncation and round-off of the two steps are below 1e-8 relative here.
TEST(Hertz3d, LacLinearizationEqualsPlainDifferences) {
  namespace contact = contactrb::contact;
  const hf::HFSolver3 solver = hertz_lac_solver(0);
  const hf::HFSolution3 k = solver.solve(tight_kacanov());
  ASSERT_TRUE(k.converged) << k.message;
  const auto& mesh = solver.problem().mesh;
  const auto& pair = solver.pair();
  const auto& q = solver.quadrature();
  // The free DOFs, as in the Newton: the symmetry planes fix the normal components of the nodes on
  // them, where the quarter model's master rim makes the maps one-sided.
  std::vector<char> movable(static_cast<std::size_t>(mesh.num_dofs()), 0);
  for (int g : solver.dofs().free_dofs()) movable[static_cast<std::size_t>(g)] = 1;
  const Eigen::VectorXd movable_rows = Eigen::Map<const Eigen::Matrix<char, Eigen::Dynamic, 1>>(
      movable.data(), static_cast<Eigen::Index>(movable.size())).cast<double>();
  const contact::ContactLinearization3 lin = contact::linearize_contact(mesh, pair, q, k.u, k.lambda, movable);
  EXPECT_GT(lin.colours, 0);
  std::vector<int> surface(pair.slave.begin(), pair.slave.end());
  surface.insert(surface.end(), pair.master.begin(), pair.master.end());
  std::vector<char> checked(static_cast<std::size_t>(mesh.num_dofs()), 0);
  const Eigen::MatrixXd D(lin.D), H(lin.H);
  double h_step = 0.0;  // 4e-6 of the mean slave edge, four times the step of the coloured differences
  for (const auto& f : pair.slave_faces) {
    const auto v = f.vertices();
    for (int i = 0; i < 3; ++i) h_step += (mesh.nodes[static_cast<std::size_t>(v[static_cast<std::size_t>((i + 1) % 3)])] -
                                          mesh.nodes[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])]).norm();
  }
  h_step *= 4e-6 / (3.0 * static_cast<double>(pair.slave_faces.size()));
  double d_error = 0.0, h_error = 0.0, d_max = 0.0, h_max = 0.0;
  Eigen::VectorXd up = k.u, um = k.u;
  for (int node : surface) {
    for (int c = 0; c < 3; ++c) {
      const int j = 3 * node + c;
      if (!movable[static_cast<std::size_t>(j)]) continue;
      checked[static_cast<std::size_t>(j)] = 1;
      up(j) = k.u(j) + h_step;
      um(j) = k.u(j) - h_step;
      const contact::ContactMaps3 plus = contact::evaluate_contact_maps(mesh, pair, q, up);
      const contact::ContactMaps3 minus = contact::evaluate_contact_maps(mesh, pair, q, um);
      up(j) = um(j) = k.u(j);
      const Eigen::VectorXd dd = (plus.d - minus.d) / (2.0 * h_step);
      const Eigen::VectorXd df = (plus.rows.K.transpose() * k.lambda - minus.rows.K.transpose() * k.lambda)
                                     .cwiseProduct(movable_rows) / (2.0 * h_step);
      d_error = std::max(d_error, (D.col(j) - dd).cwiseAbs().maxCoeff());
      h_error = std::max(h_error, (H.col(j) - df).cwiseAbs().maxCoeff());
      d_max = std::max(d_max, dd.cwiseAbs().maxCoeff());
      h_max = std::max(h_max, df.cwiseAbs().maxCoeff());
    }
  }
  for (int j = 0; j < mesh.num_dofs(); ++j) {  // no entry in a fixed column or off the contact surfaces
    if (checked[static_cast<std::size_t>(j)]) continue;
    EXPECT_EQ(D.col(j).cwiseAbs().maxCoeff(), 0.0) << "D column " << j;
    EXPECT_EQ(H.col(j).cwiseAbs().maxCoeff(), 0.0) << "H column " << j;
  }
  std::printf("[ hertz-3d level 0, LAC ] %d colours, D error %.2e of %.2e, H error %.2e of %.2e\n", lin.colours,
              d_error, d_max, h_error, h_max);
  EXPECT_GT(d_max, 0.0);
  EXPECT_GT(h_max, 0.0);
  EXPECT_LT(d_error, 1e-6 * d_max);
  EXPECT_LT(h_error, 1e-6 * h_max);
}

// The semi-smooth Newton on the 3D LAC rows converges to the answer of Kacanov run to 1e-10 (the
// same displacement, pressures and force to the solvers' tolerances), with its KKT residual at
// the returned geometry, in a few iterations.
TEST(Hertz3d, NewtonOnLacRowsMatchesKacanov) {
  const hf::HFSolver3 solver = hertz_lac_solver(0);
  const hf::HFSolution3 k = solver.solve(tight_kacanov());
  hf::HFSettings newton;
  newton.method = hf::HFMethod::Newton;
  const hf::HFSolution3 n = solver.solve(newton);
  ASSERT_TRUE(k.converged) << k.message;
  ASSERT_TRUE(n.converged) << n.message;
  std::printf("[ hertz-3d level 0, LAC ] Kacanov %d, Newton %d iterations, force %.10e vs %.10e, KKT %.2e\n",
              k.iterations, n.iterations, n.contact_force, k.contact_force, n.kkt.max());
  EXPECT_LE(n.iterations, 10);
  EXPECT_LT(n.kkt.max(), 1e-10);
  EXPECT_EQ(n.active_constraints, k.active_constraints);
  EXPECT_NEAR(n.contact_force, k.contact_force, 1e-8 * k.contact_force);
  EXPECT_LT((n.lambda - k.lambda).norm(), 1e-7 * k.lambda.norm());
  EXPECT_LT((n.u - k.u).norm(), 1e-8 * k.u.norm());
  int colours = 0;
  for (const hf::NewtonIteration& it : n.newton_history) colours = std::max(colours, it.colours);
  EXPECT_GT(colours, 0) << "no Newton-phase step";
}
