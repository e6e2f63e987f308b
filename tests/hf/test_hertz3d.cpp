// The Hertz sphere problem in 3D (docs/solvers.md, "Three dimensions"; docs/cases.md, "hertz-3d"):
// the quarter model of a sphere R = 1 on a block, LAC rows, Kacanov. From the measured contact
// force F (four times the model's), Hertz's half-space solution gives a = (3 F R / (4 E*))^(1/3)
// and p0 = 3 F / (2 pi a^2) with E* = E / (2 (1 - nu^2)); the discrete pressure fitted as
// p^2 = p0^2 (1 - r^2 / a^2) over the inner active rows must give both within 5 %, and closer on
// the finer mesh (level 2: 16 slave nodes across the contact radius along each symmetry axis).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/catalog.hpp"
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
