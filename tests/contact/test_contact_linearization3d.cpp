// The 3D linearization of the contact maps (contact_linearization.hpp: coloured central
// differences): D = d'(u) and H = (K(u)' lambda)' against plain central differences of the maps,
// one DOF at a time (no colouring, no sparsity pattern assumed), on a randomly deformed pair of
// stacked blocks; D = -K on an undeformed flat master; the analytic method refused in 3D.
#include <gtest/gtest.h>

#include <random>
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

StackedPair stacked(double gap) {
  StackedPair s;
  s.mesh = mesh::stacked_blocks(0, gap);
  s.pair = make_contact_pair(s.mesh);
  s.quadrature = make_quadrature(s.mesh, s.pair, Discretization::Collocation);
  s.movable.assign(static_cast<std::size_t>(s.mesh.num_dofs()), 1);
  return s;
}

LinearizationOptions finite_differences() {
  LinearizationOptions o;
  o.method = LinearizationMethod::FiniteDifference;
  return o;
}

}  // namespace

TEST(ContactLinearization3D, ColouredDifferencesEqualPlainDifferences) {
  const StackedPair s = stacked(0.01);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unif(-1.0, 1.0);
  Eigen::VectorXd u(s.mesh.num_dofs());
  for (Eigen::Index i = 0; i < u.size(); ++i) u(i) = 0.01 * unif(rng);  // master normals tilt by ~0.05
  const int R = static_cast<int>(s.quadrature.weight.size());
  Eigen::VectorXd lambda(R);
  for (int r = 0; r < R; ++r) lambda(r) = 1.0 + 0.5 * unif(rng);
  const ContactLinearization3 lin = linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable,
                                                     finite_differences());
  EXPECT_GT(lin.colours, 0);
  EXPECT_EQ(lin.evaluations, 2 * lin.colours);
  const Eigen::MatrixXd D(lin.D), H(lin.H);
  const double h = 1e-6 * 0.25;  // the library's step: 1e-6 of the mean slave edge (~1/7 .. 1/7 sqrt 2)
  double d_error = 0.0, h_error = 0.0, d_max = 0.0, h_max = 0.0;
  Eigen::VectorXd up = u, um = u;
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    up(j) = u(j) + h;
    um(j) = u(j) - h;
    const ContactMaps3 plus = evaluate_contact_maps(s.mesh, s.pair, s.quadrature, up);
    const ContactMaps3 minus = evaluate_contact_maps(s.mesh, s.pair, s.quadrature, um);
    up(j) = um(j) = u(j);
    const Eigen::VectorXd dd = (plus.d - minus.d) / (2.0 * h);
    const Eigen::VectorXd df = (plus.rows.K.transpose() * lambda - minus.rows.K.transpose() * lambda) / (2.0 * h);
    d_error = std::max(d_error, (D.col(j) - dd).cwiseAbs().maxCoeff());
    h_error = std::max(h_error, (H.col(j) - df).cwiseAbs().maxCoeff());
    d_max = std::max(d_max, dd.cwiseAbs().maxCoeff());
    h_max = std::max(h_max, df.cwiseAbs().maxCoeff());
  }
  // Both are central differences with steps of the same size: they differ by the truncation
  // and round-off of each (docs/solvers.md, "Semi-smooth Newton"), far below a missing entry.
  EXPECT_GT(d_max, 0.01);
  EXPECT_GT(h_max, 0.01);
  EXPECT_LT(d_error, 1e-6 * d_max) << "max |D| " << d_max;
  EXPECT_LT(h_error, 1e-6 * h_max) << "max |H| " << h_max;
}

// On the undeformed flat master across a gap, d_s = |I_s| (z_s - z of the master plane under s):
// D = -K (the slave's z with weight |I_s|, the master vertices' z with -|I_s| phi_i; nothing
// lateral moves a flat plane or its normals to first order).
TEST(ContactLinearization3D, FlatMasterGivesMinusK) {
  const StackedPair s = stacked(0.01);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const Eigen::VectorXd lambda = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.quadrature.weight.size()));
  const ContactLinearization3 lin = linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable,
                                                     finite_differences());
  const Eigen::MatrixXd D(lin.D), K(lin.maps.rows.K);
  // Slave nodes on the rim (no candidates once moved outward: d becomes their distance to the rim
  // edge, sqrt(gap^2 + t^2)) or above a master edge (the closest triangle switches) sit on kinks
  // of the maps, where the central difference is a generalized derivative up to O(step / gap):
  // 2e-6 of max |K| at most here. A missing or wrong entry would be of the order of max |K|.
  EXPECT_LT((D + K).cwiseAbs().maxCoeff(), 1e-5 * K.cwiseAbs().maxCoeff());
  EXPECT_EQ(lin.H.nonZeros(), 0);  // lambda = 0
}

TEST(ContactLinearization3D, AnalyticIsRefusedInThreeDimensions) {
  const StackedPair s = stacked(0.0);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(s.mesh.num_dofs());
  const Eigen::VectorXd lambda = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.quadrature.weight.size()));
  try {
    linearize_contact(s.mesh, s.pair, s.quadrature, u, lambda, s.movable);
    FAIL() << "the analytic linearization was accepted in 3D";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not available in 3D"), std::string::npos) << e.what();
  }
  EXPECT_THROW(linearize_contact(s.mesh, s.pair, s.quadrature, u, Eigen::VectorXd::Zero(3), s.movable,
                                 finite_differences()),
               Error);
}
