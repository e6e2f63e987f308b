// Exactly integrated LAC rows (lac_integration.hpp), checked against independent
// computations on flat interfaces with non-matching meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "contact/contact_fixtures.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/lac_integration.hpp"
#include "contactrb/contact/projection.hpp"

using namespace contactrb;
using namespace contactrb::contact;
using contact_test::flat_blocks;
using Eigen::Vector2d;
using mesh::Mesh;

namespace {

const Vector2d& X(const Mesh& m, int node) { return m.nodes[static_cast<std::size_t>(node)]; }
Vector2d at(const Eigen::VectorXd& v, int node) { return v.segment<2>(2 * node); }

Eigen::VectorXd random_vector(int n, unsigned seed, double scale = 1.0) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = u(gen);
  return v;
}

// Slave edges of LAC row r: 2r and 2r + 1 (the last row may hold one edge).
std::vector<int> row_edges(int r, int num_edges) {
  std::vector<int> e = {2 * r};
  if (2 * r + 1 < num_edges) e.push_back(2 * r + 1);
  return e;
}

// Independent K v for a flat master on the line y = 0 (deformed only along x): the deformed
// slave point x(t) projects vertically; the master field is the P1 interpolant along the
// master nodes sorted by deformed abscissa. The pieces between deformed master vertices are
// integrated by the midpoint rule, exact for the linear integrand on each piece.
double reference_row(const Mesh& m, const ContactPair& pair, const Eigen::VectorXd& w, const Eigen::VectorXd& v,
                     const Vector2d& n, int r) {
  std::vector<std::pair<double, int>> master;  // (deformed x, node)
  for (int node : pair.master) master.emplace_back(X(m, node).x() + w(2 * node), node);
  std::sort(master.begin(), master.end());
  double sum = 0.0;
  const int E = static_cast<int>(pair.slave.size()) - 1;
  for (int e : row_edges(r, E)) {
    const int a = pair.slave[static_cast<std::size_t>(e)], b = pair.slave[static_cast<std::size_t>(e + 1)];
    const double xa = X(m, a).x() + w(2 * a), xb = X(m, b).x() + w(2 * b);
    const double len = (X(m, b) - X(m, a)).norm();
    std::vector<double> cuts = {0.0, 1.0};
    for (const auto& [x, node] : master) {
      if (x > std::min(xa, xb) && x < std::max(xa, xb)) cuts.push_back((x - xa) / (xb - xa));
    }
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double t = 0.5 * (cuts[i] + cuts[i + 1]);
      const double x = (1.0 - t) * xa + t * xb;
      std::size_t j = 0;
      while (j + 2 < master.size() && master[j + 1].first < x) ++j;
      const double lambda = (x - master[j].first) / (master[j + 1].first - master[j].first);
      const Vector2d vm = (1.0 - lambda) * at(v, master[j].second) + lambda * at(v, master[j + 1].second);
      const Vector2d vs = (1.0 - t) * at(v, a) + t * at(v, b);
      sum += (vm - vs).dot(n) * len * (cuts[i + 1] - cuts[i]);
    }
  }
  return sum;
}

// int_{[lo, hi]} of the hat function of node i of the sorted abscissas xs.
double hat_integral(const std::vector<double>& xs, std::size_t i, double lo, double hi) {
  double sum = 0.0;
  const auto piece = [&](double x0, double f0, double x1, double f1) {
    const double a = std::max(x0, lo), b = std::min(x1, hi);
    if (b <= a) return;
    const auto f = [&](double x) { return f0 + (f1 - f0) * (x - x0) / (x1 - x0); };
    sum += 0.5 * (f(a) + f(b)) * (b - a);
  };
  if (i > 0) piece(xs[i - 1], 0.0, xs[i], 1.0);
  if (i + 1 < xs.size()) piece(xs[i], 1.0, xs[i + 1], 0.0);
  return sum;
}

// Nodal forces of a uniform unit pressure: K' 1.
Eigen::VectorXd pressure_forces(const ConstraintRows& rows) {
  return Eigen::VectorXd(rows.K.transpose() * Eigen::VectorXd::Ones(rows.K.rows()));
}

}  // namespace

TEST(LacIntegration, FlatNonMatchingRowsAreTheExactIntegralOfTheJump) {
  // 7 slave edges over a graded 5-segment master, both displaced: the slave tangentially and
  // vertically, the master along the interface only (it stays on y = 0).
  Mesh m = flat_blocks(0.05, 0.95, 0.2, 7, 0.0, 1.0, 5);
  ContactPair pair = make_contact_pair(m);
  for (int node : pair.master) {
    double& x = m.nodes[static_cast<std::size_t>(node)].x();
    x = std::pow(x, 1.4);
  }
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const Eigen::VectorXd noise = random_vector(m.num_dofs(), 17, 0.01);
  for (int node : pair.slave) {
    w(2 * node) = 0.03;
    w(2 * node + 1) = noise(2 * node + 1);
  }
  for (int node : pair.master) w(2 * node) = noise(2 * node);
  // Both chain orientations: the mesh's (slave and master run in opposite directions, so the
  // master abscissa decreases along each slave edge) and a reversed master (normal (0, -1)).
  for (bool reversed : {false, true}) {
    ContactPair p = pair;
    if (reversed) std::reverse(p.master.begin(), p.master.end());
    const Vector2d n = reversed ? Vector2d(0.0, -1.0) : Vector2d(0.0, 1.0);
    const PointwiseContact pc = project_slave_nodes(m, p, w);
    const ContactQuadrature q = make_quadrature(m, p, Discretization::LAC);
    const ConstraintRows rows = constraint_rows(m, p, q, pc, w);
    ASSERT_EQ(rows.K.rows(), 4);
    EXPECT_NEAR(q.weight.sum(), 0.9, 1e-15);
    for (unsigned seed : {1u, 2u, 3u}) {
      const Eigen::VectorXd v = random_vector(m.num_dofs(), seed);
      const Eigen::VectorXd kv = rows.K * v;
      for (int r = 0; r < 4; ++r) {
        EXPECT_NEAR(kv(r), reference_row(m, p, w, v, n, r), 1e-13) << "row " << r << " reversed " << reversed;
      }
    }
    // g_r = int (X(t) - rho) . n2 = 0.2 |I_r| (reference gap), +-.
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(rows.g(r), n.y() * 0.2 * q.weight(r), 1e-15);
    // A linear field v(x) = A x + c: k(w; v) is the jump of v between the reference points.
    Eigen::Matrix2d A;
    A << 0.3, -0.7, 1.1, 0.4;
    Eigen::VectorXd lin(m.num_dofs());
    for (int i = 0; i < m.num_nodes(); ++i) lin.segment<2>(2 * i) = A * X(m, i) + Vector2d(0.2, -0.5);
    const Eigen::VectorXd kl = rows.K * lin;
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(kl(r), reference_row(m, p, w, lin, n, r), 1e-13);
  }
}

TEST(LacIntegration, UniformPressureGivesConsistentNodalForces) {
  // The patch-test property: 8 slave edges over 11 master edges of the same width.
  const Mesh m = flat_blocks(0.0, 1.0, 0.0, 8, 0.0, 1.0, 11);
  const ContactPair pair = make_contact_pair(m);
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  const double p = 0.37;
  for (Discretization d : {Discretization::LAC, Discretization::LACSimpson, Discretization::Collocation}) {
    const ContactQuadrature q = make_quadrature(m, pair, d);
    const ConstraintRows rows = constraint_rows(m, pair, q, pc, w);
    EXPECT_NEAR(q.weight.sum(), 1.0, 1e-15);
    const Eigen::VectorXd f = p * pressure_forces(rows);
    double slave_err = 0.0, master_err = 0.0;
    for (const auto& [chain, sign, err] : {std::tuple{&pair.slave, -1.0, &slave_err}, std::tuple{&pair.master, 1.0, &master_err}}) {
      std::vector<double> xs;
      for (int node : *chain) xs.push_back(X(m, node).x());
      std::vector<int> nodes = *chain;
      std::vector<std::size_t> order(nodes.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return xs[a] < xs[b]; });
      std::vector<double> sorted;
      for (std::size_t i : order) sorted.push_back(xs[i]);
      for (std::size_t k = 0; k < order.size(); ++k) {
        const int node = nodes[order[k]];
        const double expected = sign * p * hat_integral(sorted, k, 0.0, 1.0);  // p * half adjacent edges
        *err = std::max({*err, std::abs(f(2 * node + 1) - expected), std::abs(f(2 * node))});
      }
    }
    if (d == Discretization::LAC) {
      EXPECT_LT(slave_err, 1e-15);
      EXPECT_LT(master_err, 1e-15);
    } else {
      // Simpson: slave nodal weights alternate h/3, 4h/3; both rules see the master only at the
      // slave nodes' projections.
      EXPECT_GT(std::max(slave_err, master_err), 1e-3 * p) << to_string(d);
    }
  }
}

TEST(LacIntegration, OverhangingSlavePartsAreNoCandidates) {
  // Slave [-0.5, 1.5] (10 edges of 0.2) over master [0, 1] (5 edges), gap 0.1: the slave edge
  // [-0.1, 0.1] is split at the master end, row 0 (edges [-0.5, -0.1]) faces no master.
  const Mesh m = flat_blocks(-0.5, 1.5, 0.1, 10, 0.0, 1.0, 5);
  const ContactPair pair = make_contact_pair(m);
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::LAC);
  const ConstraintRows rows = constraint_rows(m, pair, q, pc, w);
  ASSERT_EQ(rows.K.rows(), 5);
  EXPECT_EQ(rows.K.row(0).nonZeros(), 0);
  EXPECT_EQ(rows.K.row(4).nonZeros(), 0);
  const Eigen::VectorXd f = pressure_forces(rows);
  std::vector<double> sx, mx;
  for (int node : pair.slave) sx.push_back(X(m, node).x());  // increasing
  for (int node : pair.master) mx.push_back(X(m, node).x());
  std::reverse(mx.begin(), mx.end());  // the master chain runs right to left
  for (std::size_t k = 0; k < sx.size(); ++k) {
    const int node = pair.slave[k];
    EXPECT_NEAR(f(2 * node + 1), -hat_integral(sx, k, 0.0, 1.0), 1e-15) << "slave x = " << sx[k];
    EXPECT_NEAR(f(2 * node), 0.0, 1e-15);
  }
  for (std::size_t k = 0; k < mx.size(); ++k) {
    const int node = pair.master[mx.size() - 1 - k];
    EXPECT_NEAR(f(2 * node + 1), hat_integral(mx, k, 0.0, 1.0), 1e-15) << "master x = " << mx[k];
  }
  // Gaps: 0.1 x (covered length) plus a positive contribution of the uncovered parts.
  const std::vector<double> covered = {0.0, 0.3, 0.4, 0.3, 0.0};
  for (int r = 0; r < 5; ++r) {
    EXPECT_GE(rows.g(r), 0.1 * covered[static_cast<std::size_t>(r)] - 1e-15);
    if (covered[static_cast<std::size_t>(r)] < 0.4) {
      EXPECT_GT(rows.g(r), 0.1 * covered[static_cast<std::size_t>(r)] + 1e-3);
    }
  }
  EXPECT_NEAR(rows.g(2), 0.1 * 0.4, 1e-15);
}

TEST(LacIntegration, ClosedMasterMatchesTheOpenTop) {
  // The whole boundary of the master block as a closed chain: for a slave inside [0.2, 0.8]
  // only the top is seen, so the rows equal those of the open top chain, wherever the loop
  // starts.
  // 10 master cells: the slave stays away from the corner segments, whose closed-loop vertex
  // normals (averaged with the sides) differ from the open chain's.
  Mesh open = flat_blocks(0.2, 0.8, 0.15, 6, 0.0, 1.0, 10);
  Mesh closed = open;
  auto& edges = closed.boundaries["master"];
  for (const char* g : {"m_left", "m_bottom", "m_right"}) {
    edges.insert(edges.end(), closed.boundaries[g].begin(), closed.boundaries[g].end());
  }
  const ContactPair po = make_contact_pair(open);
  const ContactPair pcl = make_contact_pair(closed);
  ASSERT_EQ(pcl.master.front(), pcl.master.back());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(open.num_dofs());
  for (int node : po.slave) w(2 * node) = 0.05;  // the slave crosses the master vertex at 0.8
  const ContactQuadrature q = make_quadrature(open, po, Discretization::LAC);
  const ConstraintRows ro = constraint_rows(open, po, q, project_slave_nodes(open, po, w), w);
  // Rotate the loop so that it starts under the slave (exercises the wrap of the abscissa).
  for (int shift = 0; shift < 4; ++shift) {
    ContactPair p = pcl;
    p.master.pop_back();
    std::rotate(p.master.begin(), p.master.begin() + shift, p.master.end());
    p.master.push_back(p.master.front());
    const ConstraintRows rc = constraint_rows(closed, p, q, project_slave_nodes(closed, p, w), w);
    EXPECT_NEAR(Eigen::MatrixXd(rc.K - ro.K).cwiseAbs().maxCoeff(), 0.0, 1e-15) << "shift " << shift;
    EXPECT_NEAR((rc.g - ro.g).cwiseAbs().maxCoeff(), 0.0, 1e-15);
  }
}

namespace {

// The restricted evaluation (online magic rows): rows integrated from the projections of their
// own slave nodes only equal the same rows of the full evaluation; the other rows are zero.
TEST(LacIntegration, RowSubsetFromItsSlaveNodesEqualsTheFullRows) {
  // Non-matching, overhanging, displaced: 11 slave edges (6 rows, the last one single-edge).
  const Mesh m = flat_blocks(-0.3, 1.2, 0.02, 11, 0.0, 1.0, 7);
  const ContactPair pair = make_contact_pair(m);
  const Eigen::VectorXd w = random_vector(m.num_dofs(), 7, 0.01);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::LAC);
  const ConstraintRows full = constraint_rows(m, pair, q, project_slave_nodes(m, pair, w), w);
  const int S = static_cast<int>(pair.slave.size());
  ASSERT_EQ(full.K.rows(), 6);
  const std::vector<int> rows = {5, 0, 3, 3};
  const std::vector<int> positions = lac_slave_positions(rows, S);
  EXPECT_EQ(positions, (std::vector<int>{0, 1, 2, 6, 7, 8, 10, 11}));
  const PointwiseContact pw = project_slave_nodes(m, pair, w, positions);
  for (int s = 0; s < S; ++s) {
    const bool projected = std::find(positions.begin(), positions.end(), s) != positions.end();
    EXPECT_EQ(pw.projection[static_cast<std::size_t>(s)].segment >= 0, projected) << "slave position " << s;
  }
  const ConstraintRows sub = integrate_lac_rows(m, pair, q, pw, w, rows);
  const Eigen::MatrixXd Kf(full.K), Ks(sub.K);
  for (int r = 0; r < 6; ++r) {
    const bool listed = std::find(rows.begin(), rows.end(), r) != rows.end();
    const double scale = listed ? 1.0 : 0.0;
    EXPECT_LE((Ks.row(r) - scale * Kf.row(r)).cwiseAbs().maxCoeff(), 1e-15) << "row " << r;
    EXPECT_NEAR(sub.g(r), scale * full.g(r), 1e-15) << "row " << r;
  }
  EXPECT_GT(Kf.row(3).cwiseAbs().maxCoeff(), 0.0);  // a row in contact, not a trivial zero
  // A row whose slave nodes were not projected, and a row outside [0, R), are refused.
  EXPECT_THROW(integrate_lac_rows(m, pair, q, pw, w, std::vector<int>{1}), Error);
  EXPECT_THROW(integrate_lac_rows(m, pair, q, pw, w, std::vector<int>{6}), Error);
  EXPECT_THROW(project_slave_nodes(m, pair, w, std::vector<int>{S}), Error);
}

}  // namespace
