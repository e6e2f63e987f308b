// The consistent linearization of the contact maps (contact_linearization.hpp): the analytic
// derivatives D = d'(u) and H = (K(u)' lambda)' against plain central differences of the maps
// (one DOF at a time, independent of the coloured differences of the library), on random
// deformed configurations of a curved open master, a flat master with overhanging slave nodes
// (non-candidates) and a closed master, for the three constraint discretizations; and at slave
// nodes placed just before and just after a master vertex (xi near 1, the clamped wedge).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "contact/contact_fixtures.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"

using namespace contactrb;
using namespace contactrb::contact;
using contact_test::flat_blocks;
using contact_test::half_annulus;
using contact_test::join;
using mesh::Mesh;

namespace {

struct Difference {
  double d_error = 0.0, h_error = 0.0;  // largest entry error
  double d_max = 0.0, h_max = 0.0;      // largest reference entry
  double h_off_movable = 0.0;           // largest |H| entry on a fixed row or column
};

// Central differences of d(u) and K(u)' lambda, one movable DOF at a time, against the analytic
// linearization at u.
Difference compare(const Mesh& m, const ContactPair& pair, const ContactQuadrature& q, const Eigen::VectorXd& u,
                   const Eigen::VectorXd& lambda, const std::vector<char>& movable) {
  const ContactLinearization lin = linearize_contact(m, pair, q, u, lambda, movable);
  const Eigen::MatrixXd D(lin.D), H(lin.H);
  const double h = 1e-6;
  Difference out;
  for (int j = 0; j < m.num_dofs(); ++j) {
    if (!movable[static_cast<std::size_t>(j)]) {
      out.h_off_movable = std::max({out.h_off_movable, H.col(j).cwiseAbs().maxCoeff(), H.row(j).cwiseAbs().maxCoeff()});
      EXPECT_EQ(D.col(j).cwiseAbs().maxCoeff(), 0.0) << "fixed DOF " << j;
      continue;
    }
    Eigen::VectorXd up = u, um = u;
    up(j) += h;
    um(j) -= h;
    const ContactMaps plus = evaluate_contact_maps(m, pair, q, up), minus = evaluate_contact_maps(m, pair, q, um);
    const Eigen::VectorXd dd = (plus.d - minus.d) / (2.0 * h);
    Eigen::VectorXd df = (plus.rows.K.transpose() * lambda - minus.rows.K.transpose() * lambda) / (2.0 * h);
    for (int i = 0; i < m.num_dofs(); ++i) {
      if (!movable[static_cast<std::size_t>(i)]) df(i) = 0.0;  // H lives on the movable rows
    }
    out.d_error = std::max(out.d_error, (D.col(j) - dd).cwiseAbs().maxCoeff());
    out.h_error = std::max(out.h_error, (H.col(j) - df).cwiseAbs().maxCoeff());
    out.d_max = std::max(out.d_max, dd.cwiseAbs().maxCoeff());
    out.h_max = std::max(out.h_max, df.cwiseAbs().maxCoeff());
  }
  return out;
}

Eigen::VectorXd random_vector(int n, std::mt19937& gen, double lo, double hi) {
  std::uniform_real_distribution<double> dist(lo, hi);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = dist(gen);
  return v;
}

// Random multipliers in [0, 2], about a third of them zero (rows that add nothing to H).
Eigen::VectorXd random_lambda(int R, std::mt19937& gen) {
  Eigen::VectorXd l = random_vector(R, gen, -1.0, 2.0);
  return l.cwiseMax(0.0);
}

// Every DOF movable except those of the nodes of the given groups.
std::vector<char> movable_except(const Mesh& m, std::initializer_list<const char*> groups) {
  std::vector<char> movable(static_cast<std::size_t>(m.num_dofs()), 1);
  for (const char* g : groups) {
    for (int v : mesh::boundary_nodes(m, g)) movable[static_cast<std::size_t>(2 * v)] = movable[static_cast<std::size_t>(2 * v + 1)] = 0;
  }
  return movable;
}

void expect_matches(const Mesh& m, const std::string& label, double amplitude, unsigned seed,
                    std::initializer_list<const char*> fixed) {
  const ContactPair pair = make_contact_pair(m);
  const std::vector<char> movable = movable_except(m, fixed);
  std::mt19937 gen(seed);
  for (auto d : {Discretization::Collocation, Discretization::LAC, Discretization::LACSimpson}) {
    const ContactQuadrature q = make_quadrature(m, pair, d);
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::VectorXd u = random_vector(m.num_dofs(), gen, -amplitude, amplitude);
      const Eigen::VectorXd lambda = random_lambda(static_cast<int>(q.W.rows()), gen);
      const Difference e = compare(m, pair, q, u, lambda, movable);
      const std::string where = label + " " + to_string(d) + " trial " + std::to_string(trial);
      // Central differences with h = 1e-6 on a geometry of size 1: truncation ~1e-12, round-off ~1e-10.
      EXPECT_LT(e.d_error, 1e-7 * std::max(1.0, e.d_max)) << where;
      EXPECT_LT(e.h_error, 1e-7 * std::max(1.0, e.h_max)) << where;
      EXPECT_EQ(e.h_off_movable, 0.0) << where;
      // Not a vacuous comparison: the maps move with u (entries ~ |I_r| = 0.1) and the loaded rows bend.
      EXPECT_GT(e.d_max, 0.05) << where;
      EXPECT_GT(e.h_max, 1e-3) << where;
    }
  }
}

}  // namespace

TEST(ContactLinearization, AnalyticEqualsCentralDifferencesOnACurvedMaster) {
  // Slave block bottom at y = 1.02 over the outer arc (radius 1, 16 segments) of a half annulus.
  const Mesh m = join(mesh::rectangle(-0.45, 1.02, 0.45, 1.3, 9, 2, mesh::kSlaveBody), half_annulus(0.5, 1.0, 16, 2));
  expect_matches(m, "curved master", 0.02, 1u, {"m_bottom"});
}

TEST(ContactLinearization, AnalyticEqualsCentralDifferencesWithOverhangingSlaveNodes) {
  // Slave [-0.3, 1.3] over master [0, 1]: the outer slave nodes are non-candidates.
  const Mesh m = flat_blocks(-0.3, 1.3, 0.02, 8, 0.0, 1.0, 5);
  expect_matches(m, "overhanging slave", 0.03, 2u, {"m_bottom", "s_top"});
}

TEST(ContactLinearization, AnalyticEqualsCentralDifferencesOnAClosedMaster) {
  // Master: the whole boundary of [0, 1] x [-1, 0] (a closed chain with corners); the slave
  // overhangs both top corners, so projections fall on the sides and wrap past the chain start.
  Mesh m = flat_blocks(-0.2, 1.2, 0.05, 7, 0.0, 1.0, 4);
  auto& edges = m.boundaries["master"];
  for (const char* g : {"m_left", "m_bottom", "m_right"}) edges.insert(edges.end(), m.boundaries[g].begin(), m.boundaries[g].end());
  expect_matches(m, "closed master", 0.03, 3u, {"s_top"});
}

TEST(ContactLinearization, AnalyticEqualsCentralDifferencesNearAMasterVertex) {
  // Curved master (convex, seen from outside): slave nodes placed 1e-4 of a segment before
  // master vertex 8 (xi = 1 - 1e-4, interior branch), on the vertex's outward normal (the
  // clamped wedge, xi = 1), and 1e-4 past it on the next segment (xi = 1e-4), at distance
  // 1e-3 off the master; the differences (h = 1e-6) stay on one branch.
  const int nseg = 16;
  const Mesh m = join(mesh::rectangle(-0.3, 1.01, 0.3, 1.2, 6, 1, mesh::kSlaveBody), half_annulus(0.5, 1.0, nseg, 2));
  const ContactPair pair = make_contact_pair(m);
  const auto X = [&](int node) { return m.nodes[static_cast<std::size_t>(node)]; };
  const int j = nseg / 2;
  const auto out = [](const Eigen::Vector2d& e) { return Eigen::Vector2d(e.y(), -e.x()).normalized(); };
  std::mt19937 gen(4u);
  const std::vector<char> movable = movable_except(m, {"m_bottom"});
  for (auto d : {Discretization::Collocation, Discretization::LAC}) {
    const ContactQuadrature q = make_quadrature(m, pair, d);
    for (int t = 0; t < 3; ++t) {
      Eigen::VectorXd u = random_vector(m.num_dofs(), gen, -1e-3, 1e-3);
      // Targets on the deformed master.
      const auto y = [&](int k) {
        const int node = pair.master[static_cast<std::size_t>(k)];
        return Eigen::Vector2d(X(node) + u.segment<2>(2 * node));
      };
      const Eigen::Vector2d before = y(j) - y(j - 1), after = y(j + 1) - y(j);
      const Eigen::Vector2d target = t == 0   ? Eigen::Vector2d(y(j) - 1e-4 * before + 1e-3 * out(before))
                                     : t == 1 ? Eigen::Vector2d(y(j) + 1e-3 * (out(before) + out(after)).normalized())
                                              : Eigen::Vector2d(y(j) + 1e-4 * after + 1e-3 * out(after));
      // Slave node 3 at the target, its neighbours 2 and 4 along the master.
      for (int s = 2; s <= 4; ++s) {
        const int node = pair.slave[static_cast<std::size_t>(s)];
        u.segment<2>(2 * node) = target + (s - 3) * 0.07 * after.normalized() - X(node);
      }
      const ContactMaps maps = evaluate_contact_maps(m, pair, q, u);
      const SlaveProjection& p = maps.pointwise.projection[3];
      ASSERT_TRUE(p.segment == j - 1 || p.segment == j) << t;
      if (t == 0) {
        EXPECT_TRUE(p.segment == j - 1 && p.xi > 0.99 && p.xi < 1.0) << p.xi;
      } else if (t == 1) {
        EXPECT_TRUE((p.segment == j - 1 && p.xi == 1.0) || (p.segment == j && p.xi == 0.0)) << p.xi;
      } else {
        EXPECT_TRUE(p.segment == j && p.xi > 0.0 && p.xi < 0.01) << p.xi;
      }
      const Difference e = compare(m, pair, q, u, random_lambda(static_cast<int>(q.W.rows()), gen), movable);
      const std::string where = std::string(to_string(d)) + " target " + std::to_string(t);
      EXPECT_LT(e.d_error, 1e-7 * std::max(1.0, e.d_max)) << where;
      EXPECT_LT(e.h_error, 1e-7 * std::max(1.0, e.h_max)) << where;
      EXPECT_GT(e.d_max, 0.05) << where;
    }
  }
}

// The coloured finite differences (kept as an option) approximate the same Jacobians.
TEST(ContactLinearization, FiniteDifferenceOptionAgreesWithTheAnalyticOne) {
  const Mesh m = join(mesh::rectangle(-0.45, 1.02, 0.45, 1.3, 9, 2, mesh::kSlaveBody), half_annulus(0.5, 1.0, 16, 2));
  const ContactPair pair = make_contact_pair(m);
  const std::vector<char> movable = movable_except(m, {"m_bottom"});
  std::mt19937 gen(5u);
  for (auto d : {Discretization::Collocation, Discretization::LAC}) {
    const ContactQuadrature q = make_quadrature(m, pair, d);
    const Eigen::VectorXd u = random_vector(m.num_dofs(), gen, -0.02, 0.02);
    const Eigen::VectorXd lambda = random_lambda(static_cast<int>(q.W.rows()), gen);
    LinearizationOptions fd;
    fd.method = LinearizationMethod::FiniteDifference;
    const ContactLinearization a = linearize_contact(m, pair, q, u, lambda, movable);
    const ContactLinearization b = linearize_contact(m, pair, q, u, lambda, movable, fd);
    EXPECT_EQ(a.evaluations, 0);
    EXPECT_GT(b.evaluations, 0);
    const Eigen::MatrixXd dD = Eigen::MatrixXd(a.D) - Eigen::MatrixXd(b.D);
    const Eigen::MatrixXd dH = Eigen::MatrixXd(a.H) - Eigen::MatrixXd(b.H);
    EXPECT_LT(dD.cwiseAbs().maxCoeff(), 1e-6 * Eigen::MatrixXd(a.D).cwiseAbs().maxCoeff()) << to_string(d);
    EXPECT_LT(dH.cwiseAbs().maxCoeff(), 1e-6 * Eigen::MatrixXd(a.H).cwiseAbs().maxCoeff()) << to_string(d);
  }
}

// Maps continued on prescribed branches (the branch passes of semi-smooth Newton): on u's own
// branches they are the maps at u; across a master vertex the continued branch is the smooth
// piece of the other side, whose first-order Taylor expansion from u predicts the maps at the
// other side to second order, where u's own linearization misses by the kink (first order).
TEST(ContactLinearization, MapsContinuedOnTheBranchesOfAnotherPoint) {
  const int nseg = 16;
  const Mesh m = join(mesh::rectangle(-0.3, 1.01, 0.3, 1.2, 6, 1, mesh::kSlaveBody), half_annulus(0.5, 1.0, nseg, 2));
  const ContactPair pair = make_contact_pair(m);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::Collocation);
  const std::vector<char> movable = movable_except(m, {"m_bottom"});
  const auto X = [&](int node) { return m.nodes[static_cast<std::size_t>(node)]; };
  const int j = nseg / 2;
  const Eigen::Vector2d yj = X(pair.master[static_cast<std::size_t>(j)]);
  const Eigen::Vector2d before = yj - X(pair.master[static_cast<std::size_t>(j - 1)]);
  const Eigen::Vector2d after = X(pair.master[static_cast<std::size_t>(j + 1)]) - yj;
  const auto out = [](const Eigen::Vector2d& e) { return Eigen::Vector2d(e.y(), -e.x()).normalized(); };
  const int node = pair.slave[3];
  // u: slave node 3 on segment j - 1 (xi = 1 - 1e-3, just inside the master); v: on segment j
  // (xi = 1e-3): the step u -> v crosses vertex j.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.num_dofs()), v = u;
  u.segment<2>(2 * node) = yj - 1e-3 * before - 1e-5 * out(before) - X(node);
  v.segment<2>(2 * node) = yj + 1e-3 * after - 1e-5 * out(after) - X(node);
  const Eigen::VectorXd lambda = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(q.W.rows()));
  const ContactMaps at_u = evaluate_contact_maps(m, pair, q, u), at_v = evaluate_contact_maps(m, pair, q, v);
  ASSERT_EQ(at_u.pointwise.projection[3].segment, j - 1);
  ASSERT_EQ(at_v.pointwise.projection[3].segment, j);
  EXPECT_FALSE(same_branch(at_u.pointwise.projection[3], at_v.pointwise.projection[3]));
  EXPECT_TRUE(same_branch(at_u.pointwise.projection[2], at_v.pointwise.projection[2]));

  // Own branches: the maps themselves (to round-off) and the same linearization.
  const ContactLinearization own = linearize_contact_on_branches(m, pair, q, u, lambda, movable, at_u.pointwise);
  EXPECT_LT((own.maps.d - at_u.d).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT(Eigen::MatrixXd(own.maps.rows.K - at_u.rows.K).cwiseAbs().maxCoeff(), 1e-15);
  const ContactLinearization plain = linearize_contact(m, pair, q, u, lambda, movable);
  EXPECT_LT(Eigen::MatrixXd(own.D - plain.D).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT(Eigen::MatrixXd(own.H - plain.H).cwiseAbs().maxCoeff(), 1e-12);

  // v's branches continued to u: the Taylor expansion reaches v to second order in |v - u|.
  const ContactLinearization cont = linearize_contact_on_branches(m, pair, q, u, lambda, movable, at_v.pointwise);
  EXPECT_LT(cont.maps.pointwise.projection[3].xi, 0.0);  // the continuation of segment j's xi
  const Eigen::VectorXd dv = v - u;
  const Eigen::VectorXd f_u = at_u.rows.K.transpose() * lambda, f_v = at_v.rows.K.transpose() * lambda;
  const Eigen::VectorXd f_cont = cont.maps.rows.K.transpose() * lambda;
  const double d_cont = (at_v.d - cont.maps.d - cont.D * dv).cwiseAbs().maxCoeff();
  const double d_own = (at_v.d - at_u.d - plain.D * dv).cwiseAbs().maxCoeff();
  const double f_cont_err = (f_v - f_cont - cont.H * dv).cwiseAbs().maxCoeff();
  const double f_own_err = (f_v - f_u - plain.H * dv).cwiseAbs().maxCoeff();
  std::cout << "[ info     ] Taylor error at v: gap own " << d_own << " continued " << d_cont << ", force own "
            << f_own_err << " continued " << f_cont_err << "\n";
  EXPECT_LT(d_cont, 1e-3 * d_own);
  EXPECT_LT(f_cont_err, 1e-3 * f_own_err);
  EXPECT_LT(f_cont_err, 1e-6);
  EXPECT_THROW(linearize_contact_on_branches(m, pair, make_quadrature(m, pair, Discretization::LAC), u,
                                             Eigen::VectorXd::Ones(3), movable, at_v.pointwise),
               Error);
}
