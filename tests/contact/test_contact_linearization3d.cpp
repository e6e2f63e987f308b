// The 3D linearization of the contact maps (contact_linearization.hpp), analytic and by coloured
// central differences: D = d'(u) and H = (K(u)' lambda)' against plain central differences of
// the maps, one DOF at a time (no colouring, no sparsity pattern assumed), on a randomly deformed
// pair of stacked blocks; D = -K on an undeformed flat master. The 3D LAC rows (lac3d.hpp) by
// coloured central differences, whichever method is asked, against the same plain differences.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <utility>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;
using namespace contactrb::contact;

namespace {

struct StackedPair {
  mesh::Mesh3 mesh;
  ContactPair3 pair;
  ContactQuadrature quadrature;
  std::vector<char> movable;
};

StackedPair stacked(double gap, Discretization discretization = Discretization::Collocation) {
  StackedPair s;
  s.mesh = mesh::stacked_blocks(0, gap);
  s.pair = make_contact_pair(s.mesh);
  s.quadrature = make_quadrature(s.mesh, s.pair, discretization);
  s.movable.assign(static_cast<std::size_t>(s.mesh.num_dofs()), 1);
  return s;
}

LinearizationOptions finite_differences() {
  LinearizationOptions o;
  o.method = LinearizationMethod::FiniteDifference;
  return o;
}

// Plain central differences of d(u) and K(u)' lambda, one DOF at a time, against a linearization.
struct Difference {
  double d_error = 0.0, h_error = 0.0, d_max = 0.0, h_max = 0.0;
};

Difference compare(const StackedPair& s, const Eigen::VectorXd& u, const Eigen::VectorXd& lambda,
                   const ContactLinearization3& lin) {
  const Eigen::MatrixXd D(lin.D), H(lin.H);
  const double h = 1e-6 * 0.25;
  Difference out;
  Eigen::VectorXd up = u, um = u;
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    up(j) = u(j) + h;
    um(j) = u(j) - h;
    const ContactMaps3 plus = evaluate_contact_maps(s.mesh, s.pair, s.quadrature, up);
    const ContactMaps3 minus = evaluate_contact_maps(s.mesh, s.pair, s.quadrature, um);
    up(j) = um(j) = u(j);
    const Eigen::VectorXd dd = (plus.d - minus.d) / (2.0 * h);
    const Eigen::VectorXd df = (plus.rows.K.transpose() * lambda - minus.rows.K.transpose() * lambda) / (2.0 * h);
    out.d_error = std::max(out.d_error, (D.col(j) - dd).cwiseAbs().maxCoeff());
    out.h_error = std::max(out.h_error, (H.col(j) - df).cwiseAbs().maxCoeff());
    out.d_max = std::max(out.d_max, dd.cwiseAbs().maxCoeff());
    out.h_max = std::max(out.h_max, df.cwiseAbs().maxCoeff());
  }
  return out;
}

// A random deformed configuration (displacements up to 0.01, master normals tilted by ~0.05) and
// multipliers in [0.5, 1.5].
std::pair<Eigen::VectorXd, Eigen::VectorXd> random_state(const StackedPair& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unif(-1.0, 1.0);
  Eigen::VectorXd u(s.mesh.num_dofs());
  for (Eigen::Index i = 0; i < u.size(); ++i) u(i) = 0.01 * unif(rng);
  Eigen::VectorXd lambda(static_cast<Eigen::Index>(s.quadrature.weight.size()));
  for (Eigen::Index r = 0; r < lambda.size(); ++r) lambda(r) = 1.0 + 0.5 * unif(rng);
  return {u, lambda};
}

}  // namespace

// Both methods against plain differences on a random deformed configuration (master normals
// tilted by ~0.05). The difference quotients carry truncation and round-off (~1e-9 relative
// here); a missing or wrong entry would be of the order of the largest one.
TEST(ContactLinearization3D, BothMethodsEqualPlainDifferences) {
  const StackedPair s = stacked(0.01);
  const auto [u, lambda] = random_state(s, 7);
  const ContactLinearization3 coloured =
      linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable, finite_differences());
  EXPECT_GT(coloured.colours, 0);
  EXPECT_EQ(coloured.evaluations, 2 * coloured.colours);
  const ContactLinearization3 analytic = linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable);
  EXPECT_EQ(analytic.evaluations, 0);
  for (const ContactLinearization3* lin : {&coloured, &analytic}) {
    const Difference e = compare(s, u, lambda, *lin);
    const std::string label = lin == &analytic ? "analytic" : "finite-difference";
    EXPECT_GT(e.d_max, 0.01);
    EXPECT_GT(e.h_max, 0.01);
    EXPECT_LT(e.d_error, 1e-6 * e.d_max) << label << ": max |D| " << e.d_max;
    EXPECT_LT(e.h_error, 1e-6 * e.h_max) << label << ": max |H| " << e.h_max;
  }
}

// On the undeformed flat master across a gap, d_s = |I_s| (z_s - z of the master plane under s):
// D = -K (the slave's z with weight |I_s|, the master vertices' z with -|I_s| phi_i; nothing
// lateral moves a flat plane or its normals to first order). The analytic derivative gives it to
// round-off. Slave nodes on the rim (no candidates once moved outward: d becomes their distance to
// the rim edge, sqrt(gap^2 + t^2)) or above a master edge (the closest triangle switches) sit on
// kinks of the maps, where the central difference is a generalized derivative up to
// O(step / gap): 2e-6 of max |K| here. A missing or wrong entry would be of the order of max |K|.
TEST(ContactLinearization3D, FlatMasterGivesMinusK) {
  const StackedPair s = stacked(0.01);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const Eigen::VectorXd lambda = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.quadrature.weight.size()));
  const ContactLinearization3 analytic = linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable);
  const ContactLinearization3 coloured =
      linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable, finite_differences());
  const Eigen::MatrixXd K(analytic.maps.rows.K);
  const double kmax = K.cwiseAbs().maxCoeff();
  EXPECT_LT((Eigen::MatrixXd(analytic.D) + K).cwiseAbs().maxCoeff(), 1e-14 * kmax);
  EXPECT_LT((Eigen::MatrixXd(coloured.D) + K).cwiseAbs().maxCoeff(), 1e-5 * kmax);
  EXPECT_EQ(analytic.H.nonZeros(), 0);  // lambda = 0
  EXPECT_EQ(coloured.H.nonZeros(), 0);
}

// The LAC rows move with the clipping of the slave cells by the deformed master triangles; a
// missing row input (a master vertex whose normal enters, a slave node whose projection makes a
// direction d_T) would leave an entry of the order of the largest one out of the coloured
// differences, which perturb many columns at once. The analytic method asked for gives the same
// coloured differences (the clipped rows have no analytic linearization).
TEST(ContactLinearization3D, LacRowsEqualPlainDifferences) {
  const StackedPair s = stacked(0.01, Discretization::LAC);
  const auto [u, lambda] = random_state(s, 11);
  const ContactLinearization3 coloured =
      linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable, finite_differences());
  EXPECT_GT(coloured.colours, 0);
  EXPECT_EQ(coloured.evaluations, 2 * coloured.colours);
  const ContactLinearization3 asked_analytic = linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable);
  EXPECT_EQ(asked_analytic.colours, coloured.colours);
  EXPECT_EQ((Eigen::MatrixXd(asked_analytic.D) - Eigen::MatrixXd(coloured.D)).cwiseAbs().maxCoeff(), 0.0);
  const Difference e = compare(s, u, lambda, coloured);
  std::printf("[ LAC stacked_blocks ] %d colours, D error %.2e of %.2e, H error %.2e of %.2e\n", coloured.colours,
              e.d_error, e.d_max, e.h_error, e.h_max);
  EXPECT_GT(e.d_max, 0.01);
  EXPECT_GT(e.h_max, 0.01);
  EXPECT_LT(e.d_error, 1e-6 * e.d_max);
  EXPECT_LT(e.h_error, 1e-6 * e.h_max);
}

TEST(ContactLinearization3D, SizeErrors) {
  const StackedPair s = stacked(0.0);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  EXPECT_THROW(linearize_contact(s.mesh, s.pair, s.quadrature, u, Eigen::VectorXd::Zero(3), s.movable), Error);
  EXPECT_THROW(linearize_contact(s.mesh, s.pair, s.quadrature, Eigen::VectorXd::Zero(5),
                                 Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.quadrature.weight.size())), s.movable),
               Error);
}
