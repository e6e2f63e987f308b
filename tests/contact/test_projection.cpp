#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact/contact_fixtures.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/projection.hpp"

using namespace contactrb;
using namespace contactrb::contact;
using contact_test::flat_blocks;
using contact_test::half_annulus;
using contact_test::join;
using Eigen::Vector2d;
using mesh::Mesh;

namespace {

const Vector2d& X(const Mesh& m, int node) { return m.nodes[static_cast<std::size_t>(node)]; }
Vector2d at(const Eigen::VectorXd& v, int node) { return v.segment<2>(2 * node); }
void set(Eigen::VectorXd& v, int node, const Vector2d& value) { v.segment<2>(2 * node) = value; }

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = u(gen);
  return v;
}

// Master nodes of a flat (horizontal) master, sorted by x: an independent way to find the
// segment above which a slave abscissa lies.
std::vector<int> sorted_by_x(const Mesh& m, std::vector<int> nodes) {
  std::sort(nodes.begin(), nodes.end(), [&](int a, int b) { return X(m, a).x() < X(m, b).x(); });
  return nodes;
}

}  // namespace

TEST(Projection, FlatInterfaceGapNormalAndXi) {
  // Non-matching: 7 slave edges over 5 master edges, gap 0.25.
  const Mesh m = flat_blocks(0.0, 1.0, 0.25, 7, 0.0, 1.0, 5);
  const ContactPair pair = make_contact_pair(m);
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  ASSERT_EQ(pc.projection.size(), pair.slave.size());
  ASSERT_EQ(pc.K.rows(), static_cast<Eigen::Index>(pair.slave.size()));
  ASSERT_EQ(pc.K.cols(), m.num_dofs());
  const std::vector<int> sorted = sorted_by_x(m, pair.master);
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const SlaveProjection& p = pc.projection[s];
    const Vector2d& xs = X(m, pair.slave[s]);
    EXPECT_TRUE(p.candidate);
    EXPECT_EQ(pc.g(static_cast<Eigen::Index>(s)), 0.25);
    EXPECT_EQ(p.distance, 0.25);
    EXPECT_EQ(p.normal, Vector2d(0.0, 1.0));
    EXPECT_NEAR(p.rho.x(), xs.x(), 1e-15);
    EXPECT_EQ(p.rho.y(), 0.0);
    // Independent xi: the master chain runs right to left, segment k = [1 - k/5, 1 - (k+1)/5].
    const int a = pair.master[static_cast<std::size_t>(p.segment)];
    const int b = pair.master[static_cast<std::size_t>(p.segment + 1)];
    ASSERT_LE(X(m, b).x(), xs.x() + 1e-15);
    ASSERT_GE(X(m, a).x(), xs.x() - 1e-15);
    EXPECT_NEAR(p.xi, (X(m, a).x() - xs.x()) / 0.2, 1e-14);
  }
  // Slave x = 3/7 lies in master segment [0.4, 0.6] = segment 2 (from the right), xi = (0.6 - 3/7) / 0.2.
  EXPECT_EQ(pc.projection[3].segment, 2);
  EXPECT_NEAR(pc.projection[3].xi, (0.6 - 3.0 / 7.0) / 0.2, 1e-14);
}

TEST(Projection, FlatKRowsInterpolateTheMaster) {
  const Mesh m = flat_blocks(0.1, 0.9, 0.3, 6, 0.0, 1.0, 4);
  const ContactPair pair = make_contact_pair(m);
  const PointwiseContact pc = project_slave_nodes(m, pair, Eigen::VectorXd::Zero(m.num_dofs()));
  const Eigen::VectorXd v = random_vector(m.num_dofs(), 3);
  const Eigen::VectorXd kv = pc.K * v;
  const std::vector<int> sorted = sorted_by_x(m, pair.master);
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const int node = pair.slave[s];
    const double x = X(m, node).x();
    // Independent: piecewise linear interpolation of v along the x-sorted master nodes.
    std::size_t j = 0;
    while (j + 2 < sorted.size() && X(m, sorted[j + 1]).x() < x) ++j;
    const double xl = X(m, sorted[j]).x(), xr = X(m, sorted[j + 1]).x();
    const double t = (x - xl) / (xr - xl);
    const Vector2d vm = (1.0 - t) * at(v, sorted[j]) + t * at(v, sorted[j + 1]);
    const double expected = (vm - at(v, node)).dot(Vector2d(0.0, 1.0));
    EXPECT_NEAR(kv(static_cast<Eigen::Index>(s)), expected, 1e-14) << "slave " << s;
  }
}

TEST(Projection, RigidTranslationOfTheSlave) {
  const Mesh m = flat_blocks(0.2, 0.8, 0.25, 6, 0.0, 1.0, 5);
  const ContactPair pair = make_contact_pair(m);
  const PointwiseContact rest = project_slave_nodes(m, pair, Eigen::VectorXd::Zero(m.num_dofs()));
  for (const Vector2d& shift : {Vector2d(0.13, 0.0), Vector2d(-0.17, 0.0), Vector2d(0.05, -0.2)}) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
    for (int v : pair.slave) set(w, v, shift);  // only the contact nodes matter here
    const PointwiseContact pc = project_slave_nodes(m, pair, w);
    // Flat master: g(w) is the reference vertical gap whatever the tangential position ...
    for (Eigen::Index s = 0; s < pc.g.size(); ++s) EXPECT_NEAR(pc.g(s), rest.g(s), 1e-15);
    // ... and g(w) - k(w; w) is the deformed gap 0.25 + shift.y.
    const Eigen::VectorXd gap = pc.g - pc.K * w;
    for (Eigen::Index s = 0; s < gap.size(); ++s) EXPECT_NEAR(gap(s), 0.25 + shift.y(), 1e-15);
  }
}

TEST(Projection, ConstraintAtWIsTheSignedDistanceCircleVersusLine) {
  // Slave nodes deformed onto a circle of radius 1 centred at (0, c), master rotated rigidly by
  // theta about (0.3, 0): g(w) - k(w; w) must be the signed distance to the rotated line.
  const Mesh m = flat_blocks(-0.6, 0.6, 0.5, 12, -2.0, 2.0, 9);
  const ContactPair pair = make_contact_pair(m);
  const double theta = 0.1, c = 0.95;
  Eigen::Matrix2d R;
  R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  const Vector2d pivot(0.3, 0.0);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (int v : pair.master) set(w, v, R * (X(m, v) - pivot) + pivot - X(m, v));
  for (int v : pair.slave) {
    const double x = X(m, v).x();
    set(w, v, Vector2d(x, c - std::sqrt(1.0 - x * x)) - X(m, v));
  }
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  const Eigen::VectorXd constraint_gap = pc.g - pc.K * w;
  const Vector2d n = R * Vector2d(0.0, 1.0);
  bool penetrates = false;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const Vector2d xs = X(m, pair.slave[s]) + at(w, pair.slave[s]);
    const double signed_distance = (xs - pivot).dot(n);  // the pivot lies on the rotated line
    EXPECT_TRUE(pc.projection[s].candidate);
    EXPECT_NEAR(pc.projection[s].normal.x(), n.x(), 1e-14);
    EXPECT_NEAR(pc.projection[s].normal.y(), n.y(), 1e-14);
    EXPECT_NEAR(constraint_gap(static_cast<Eigen::Index>(s)), signed_distance, 1e-14) << "slave " << s;
    EXPECT_NEAR(pc.projection[s].distance, std::abs(signed_distance), 1e-14);
    penetrates = penetrates || signed_distance < 0.0;
  }
  EXPECT_TRUE(penetrates);  // the configuration exercises the sign of the gap
}

TEST(Projection, CurvedMasterUsesTheInterpolatedVertexNormal) {
  // Master: outer arc (radius 1) of a half annulus with 12 segments, from theta = 0 to pi.
  const int nseg = 12;
  const Mesh m = join(mesh::rectangle(-0.1, 1.5, 0.1, 1.7, 3, 1, mesh::kSlaveBody), half_annulus(0.5, 1.0, nseg, 2));
  ASSERT_NO_THROW(mesh::validate(m));
  const ContactPair pair = make_contact_pair(m);
  ASSERT_EQ(pair.slave.size(), 4u);
  ASSERT_EQ(pair.master.size(), static_cast<std::size_t>(nseg + 1));
  const double dt = std::numbers::pi / nseg;
  const auto radial = [](double t) { return Vector2d(std::cos(t), std::sin(t)); };
  const auto M = [&](int j) { return X(m, pair.master[static_cast<std::size_t>(j)]); };
  const auto seg_normal = [&](int k) {
    const Vector2d e = M(k + 1) - M(k);
    return Vector2d(e.y(), -e.x()).normalized();
  };
  // Independent vertex normals: master vertex j lies at angle j dt on the unit circle, so the
  // average of its two chord normals is radial there.
  const auto vertex_normal = [&](int j) { return Vector2d(M(j).normalized()); };
  for (int j = 1; j < nseg; ++j) {
    ASSERT_NEAR((vertex_normal(j) - (seg_normal(j - 1) + seg_normal(j)).normalized()).norm(), 0.0, 1e-15);
  }
  // Slave 0 radially above vertex 5 (interior), slave 1 above the midpoint of segment 7,
  // slave 2 slightly inside the master below the midpoint of segment 3, slave 3 at 0.04 off
  // segment 9 along its normal at xi = 1/4.
  const double t_vertex = 5 * dt, t_mid = 7.5 * dt, t_in = 3.5 * dt;
  const double r_mid = std::cos(0.5 * dt);  // distance of a chord midpoint to the centre
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const Vector2d quarter = 0.75 * M(9) + 0.25 * M(10);
  const std::vector<Vector2d> target = {1.05 * radial(t_vertex), (r_mid + 0.05) * radial(t_mid),
                                        (r_mid - 0.01) * radial(t_in), quarter + 0.04 * seg_normal(9)};
  for (std::size_t s = 0; s < 4; ++s) set(w, pair.slave[s], target[s] - X(m, pair.slave[s]));
  const PointwiseContact pc = project_slave_nodes(m, pair, w);

  // Vertex: the lower segment index wins the tie, so (segment 4, xi = 1) exactly; the normal
  // is the vertex normal, radial at the vertex.
  const SlaveProjection& pv = pc.projection[0];
  EXPECT_EQ(pv.segment, 4);
  EXPECT_EQ(pv.xi, 1.0);
  EXPECT_NEAR((pv.normal - (seg_normal(4) + seg_normal(5)).normalized()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((pv.normal - radial(t_vertex)).norm(), 0.0, 1e-14);
  EXPECT_NEAR(pv.distance, 0.05, 1e-14);
  EXPECT_TRUE(pv.candidate);

  // Segment midpoint: the average of the two vertex normals, radial at the midpoint (here it
  // coincides with the chord normal).
  const SlaveProjection& ps = pc.projection[1];
  EXPECT_EQ(ps.segment, 7);
  EXPECT_NEAR(ps.xi, 0.5, 1e-13);
  EXPECT_NEAR((ps.normal - (vertex_normal(7) + vertex_normal(8)).normalized()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((ps.normal - radial(t_mid)).norm(), 0.0, 1e-14);
  EXPECT_NEAR(ps.distance, 0.05, 1e-14);

  // xi = 1/4: the interpolated normal, which differs from the chord normal.
  const SlaveProjection& pq = pc.projection[3];
  EXPECT_EQ(pq.segment, 9);
  EXPECT_NEAR(pq.xi, 0.25, 1e-13);
  const Vector2d n_quarter = (0.75 * vertex_normal(9) + 0.25 * vertex_normal(10)).normalized();
  EXPECT_NEAR((pq.normal - n_quarter).norm(), 0.0, 1e-13);
  EXPECT_GT((pq.normal - seg_normal(9)).norm(), 0.05);
  EXPECT_NEAR(pq.distance, 0.04, 1e-14);
  EXPECT_NEAR((pq.rho - quarter).norm(), 0.0, 1e-14);  // the master is not displaced

  // g(w) - k(w; w) = (x_s - closest point) . n2.
  const Eigen::VectorXd gap = pc.g - pc.K * w;
  EXPECT_EQ(pc.projection[2].segment, 3);
  EXPECT_NEAR(pc.projection[2].distance, 0.01, 1e-14);
  EXPECT_NEAR(gap(2), -0.01, 1e-14);
  EXPECT_NEAR(gap(0), 0.05, 1e-14);
  EXPECT_NEAR(gap(1), 0.05, 1e-14);
  EXPECT_NEAR(gap(3), 0.04 * seg_normal(9).dot(n_quarter), 1e-14);
  EXPECT_NEAR(pc.g(3), (X(m, pair.slave[3]) - quarter).dot(n_quarter), 1e-13);
}

TEST(Projection, ContactMapIsContinuousAtAMasterVertex) {
  // A slave node exactly on a master vertex of a curved master; perturbations of 1e-9 move its
  // closest point between the vertex and the interiors of the two adjacent segments. With the
  // interpolated normal K and g change by O(1e-9); with segment normals they jumped by O(dt).
  const int nseg = 12;
  const Mesh m = join(mesh::rectangle(-0.1, 1.5, 0.1, 1.7, 2, 1, mesh::kSlaveBody), half_annulus(0.5, 1.0, nseg, 2));
  const ContactPair pair = make_contact_pair(m);
  const int vertex = 5;
  const Vector2d yv = X(m, pair.master[vertex]);
  const Vector2d n = yv.normalized(), tau(-n.y(), n.x());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  // Middle slave node on the vertex, its neighbours along the tangent (slave edges straddle it).
  set(w, pair.slave[1], yv - X(m, pair.slave[1]));
  set(w, pair.slave[0], yv - 0.1 * tau - X(m, pair.slave[0]));
  set(w, pair.slave[2], yv + 0.1 * tau - X(m, pair.slave[2]));
  const PointwiseContact base = project_slave_nodes(m, pair, w);
  const ContactQuadrature lac = make_quadrature(m, pair, Discretization::LAC);
  const ConstraintRows base_rows = constraint_rows(m, pair, lac, base, w);
  std::vector<int> segments;
  for (const Vector2d& dir : {n, Vector2d(-n), tau, Vector2d(-tau)}) {
    for (double eps : {1e-9, 1e-12}) {
      Eigen::VectorXd wp = w;
      set(wp, pair.slave[1], at(w, pair.slave[1]) + eps * dir);
      const PointwiseContact pc = project_slave_nodes(m, pair, wp);
      segments.push_back(pc.projection[1].segment * 10 + (pc.projection[1].xi == 1.0 ? 1 : 0));
      const double dK = Eigen::MatrixXd(pc.K - base.K).cwiseAbs().maxCoeff();
      const double dg = (pc.g - base.g).cwiseAbs().maxCoeff();
      EXPECT_LT(dK, 100.0 * eps) << "direction " << dir.transpose() << " eps " << eps;
      EXPECT_LT(dg, 100.0 * eps);
      const ConstraintRows rows = constraint_rows(m, pair, lac, pc, wp);
      EXPECT_LT(Eigen::MatrixXd(rows.K - base_rows.K).cwiseAbs().maxCoeff(), 100.0 * eps);
      EXPECT_LT((rows.g - base_rows.g).cwiseAbs().maxCoeff(), 100.0 * eps);
    }
  }
  // The perturbations did visit both adjacent segments (interior and vertex hits).
  std::sort(segments.begin(), segments.end());
  segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
  EXPECT_GE(segments.size(), 2u);
}

TEST(Projection, OverhangingSlaveNodesAreNoCandidates) {
  // Slave [-0.5, 1.5] (8 edges of 0.25) over master [0, 1]: nodes at x < 0 or x > 1 face no master.
  const Mesh m = flat_blocks(-0.5, 1.5, 0.2, 8, 0.0, 1.0, 4);
  const ContactPair pair = make_contact_pair(m);
  const PointwiseContact pc = project_slave_nodes(m, pair, Eigen::VectorXd::Zero(m.num_dofs()));
  int candidates = 0;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const Vector2d& xs = X(m, pair.slave[s]);
    const SlaveProjection& p = pc.projection[s];
    const Eigen::Index row = static_cast<Eigen::Index>(s);
    const bool overhang = xs.x() < 0.0 || xs.x() > 1.0;
    EXPECT_EQ(p.candidate, !overhang) << "x = " << xs.x();
    if (overhang) {
      const double dx = xs.x() < 0.0 ? -xs.x() : xs.x() - 1.0;
      EXPECT_EQ(pc.K.row(row).nonZeros(), 0);
      EXPECT_NEAR(pc.g(row), std::hypot(dx, 0.2), 1e-15);
      EXPECT_GT(pc.g(row), 0.0);
      EXPECT_EQ(p.distance, pc.g(row));
    } else {
      ++candidates;
      EXPECT_EQ(pc.g(row), 0.2);
      EXPECT_GT(pc.K.row(row).nonZeros(), 0);
    }
  }
  EXPECT_EQ(candidates, 5);  // x = 0, 0.25, ..., 1: the aligned end nodes stay candidates
}

TEST(Projection, ClosedMasterHasNoEndsAndAveragesTheCornerNormal) {
  // Master: the whole boundary of the block [0, 1] x [-1, 0]; one slave node placed beyond the
  // corner (1, 0) along the diagonal must be a candidate with normal (1, 1)/sqrt(2).
  Mesh m = flat_blocks(0.0, 1.0, 0.25, 2, 0.0, 1.0, 2);
  auto& edges = m.boundaries["master"];
  for (const char* g : {"m_left", "m_bottom", "m_right"}) edges.insert(edges.end(), m.boundaries[g].begin(), m.boundaries[g].end());
  const ContactPair pair = make_contact_pair(m);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  set(w, pair.slave[0], Vector2d(1.1, 0.1) - X(m, pair.slave[0]));
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  const SlaveProjection& p = pc.projection[0];
  EXPECT_TRUE(p.candidate);
  EXPECT_NEAR((p.normal - Vector2d(1.0, 1.0) / std::sqrt(2.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(p.distance, 0.1 * std::sqrt(2.0), 1e-15);
  EXPECT_TRUE(p.xi == 0.0 || p.xi == 1.0);
}

TEST(Projection, TreeSearchEqualsAllPairsOnALargeCurvedMaster) {
  // 2500-segment wavy arc; 1201 slave nodes scattered inside, near and far from it.
  const int nseg = 2500;
  const Mesh m = join(mesh::rectangle(-1.0, 2.0, 1.0, 2.5, 1200, 1, mesh::kSlaveBody), half_annulus(0.5, 1.0, nseg, 1));
  const ContactPair pair = make_contact_pair(m);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (std::size_t k = 0; k < pair.master.size(); ++k) {
    const Vector2d& p = X(m, pair.master[k]);
    const double bump = 0.03 * std::sin(40.0 * std::atan2(p.y(), p.x())) + 1e-4 * u(gen);
    set(w, pair.master[k], bump * p);
  }
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    // Half the nodes within 0.05 of the unit circle, the rest anywhere in [-2, 2] x [-1, 2].
    Vector2d target;
    if (s % 2 == 0) {
      const double t = std::numbers::pi * (0.5 + 0.6 * u(gen));
      target = (1.0 + 0.05 * u(gen)) * Vector2d(std::cos(t), std::sin(t));
    } else {
      target = Vector2d(2.0 * u(gen), 0.5 + 1.5 * u(gen));
    }
    set(w, pair.slave[s], target - X(m, pair.slave[s]));
  }
  // Include exact vertex hits and a node exactly on a segment.
  set(w, pair.slave[1], X(m, pair.master[100]) + at(w, pair.master[100]) - X(m, pair.slave[1]));
  set(w, pair.slave[3], 1.02 * (X(m, pair.master[700]) + at(w, pair.master[700])) - X(m, pair.slave[3]));

  ProjectionOptions brute, tree;
  brute.search = SearchMethod::AllPairs;
  tree.search = SearchMethod::Tree;
  const PointwiseContact a = project_slave_nodes(m, pair, w, brute);
  const PointwiseContact b = project_slave_nodes(m, pair, w, tree);
  const PointwiseContact c = project_slave_nodes(m, pair, w);  // Automatic: the tree from 32 segments
  int non_candidates = 0;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    for (const PointwiseContact* other : {&b, &c}) {
      const SlaveProjection& p = a.projection[s];
      const SlaveProjection& q = other->projection[s];
      ASSERT_EQ(p.segment, q.segment) << "slave " << s;
      ASSERT_EQ(p.xi, q.xi);
      ASSERT_EQ(p.distance, q.distance);
      ASSERT_EQ(p.normal, q.normal);
      ASSERT_EQ(p.rho, q.rho);
      ASSERT_EQ(p.candidate, q.candidate);
    }
    non_candidates += a.projection[s].candidate ? 0 : 1;
  }
  EXPECT_EQ(a.g, b.g);
  EXPECT_EQ(Eigen::MatrixXd(a.K - b.K).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT(a.projection[1].distance, 1e-15);  // a vertex hit (up to the round-off of X + w)
  EXPECT_GT(non_candidates, 0);  // points below the arc's ends face no master
  EXPECT_LT(non_candidates, static_cast<int>(pair.slave.size()) / 2);
}

TEST(ConstraintRows, CollocationAndSimpsonAreTheWeightedPointwiseRows) {
  const Mesh m = flat_blocks(0.0, 1.0, 0.25, 5, 0.0, 1.0, 3);
  const ContactPair pair = make_contact_pair(m);
  const Eigen::VectorXd w = 0.01 * random_vector(m.num_dofs(), 5);
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  const ContactQuadrature col = make_quadrature(m, pair, Discretization::Collocation);
  const ConstraintRows rc = constraint_rows(m, pair, col, pc, w);
  ASSERT_EQ(rc.K.rows(), 6);
  for (int r = 0; r < 6; ++r) {
    EXPECT_NEAR(rc.g(r), col.weight(r) * pc.g(r), 1e-16);
    EXPECT_NEAR((Eigen::RowVectorXd(rc.K.row(r)) - col.weight(r) * Eigen::RowVectorXd(pc.K.row(r))).norm(), 0.0, 1e-15);
  }
  const ContactQuadrature lac = make_quadrature(m, pair, Discretization::LACSimpson);
  const ConstraintRows rl = constraint_rows(m, pair, lac, pc, w);
  ASSERT_EQ(rl.K.rows(), 3);
  const Eigen::VectorXd v = random_vector(m.num_dofs(), 9);
  EXPECT_NEAR((rl.K * v - lac.W * (pc.K * v)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((rl.g - lac.W * pc.g).norm(), 0.0, 1e-15);

  PointwiseContact wrong = pc;
  wrong.g.resize(3);
  EXPECT_THROW(constraint_rows(m, pair, lac, wrong, w), Error);
  EXPECT_THROW(constraint_rows(m, pair, make_quadrature(m, pair, Discretization::LAC), wrong, w), Error);
  EXPECT_THROW(constraint_rows(m, pair, make_quadrature(m, pair, Discretization::LAC), pc, Eigen::VectorXd::Zero(3)),
               Error);
}

TEST(Projection, RejectsBadDisplacements) {
  const Mesh m = flat_blocks(0.0, 1.0, 0.25, 3, 0.0, 1.0, 3);
  const ContactPair pair = make_contact_pair(m);
  try {
    project_slave_nodes(m, pair, Eigen::VectorXd::Zero(7));
    FAIL() << "no error for a wrong size";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("size 7"), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::to_string(m.num_dofs())), std::string::npos) << msg;
  }
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  w(5) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(project_slave_nodes(m, pair, w), Error);
  // A master segment collapsed by w has no normal.
  w.setZero();
  set(w, pair.master[1], X(m, pair.master[0]) - X(m, pair.master[1]));
  EXPECT_THROW(project_slave_nodes(m, pair, w), Error);
}

// Finite displacements whose squared distances overflow (1e155) leave the search at its
// initial segment -1, which must never index the master chain: one clear error, with both
// searches.
TEST(Projection, OverflowingDistancesAreAnErrorNotAnIndexOfMinusOne) {
  const Mesh m = flat_blocks(0.0, 1.0, 0.25, 7, 0.0, 1.0, 5);
  const ContactPair pair = make_contact_pair(m);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (int s : pair.slave) set(w, s, Vector2d(0.0, 1e155));
  for (const SearchMethod method : {SearchMethod::AllPairs, SearchMethod::Tree}) {
    ProjectionOptions options;
    options.search = method;
    try {
      (void)project_slave_nodes(m, pair, w, options);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("to the master boundary is not finite (positions of magnitude 1e+155"), std::string::npos)
          << what;
    }
  }
  // Just below the overflow the same data project normally (distance 1e153 - 0.25 above).
  for (int s : pair.slave) set(w, s, Vector2d(0.0, 1e153));
  const PointwiseContact pc = project_slave_nodes(m, pair, w);
  for (const SlaveProjection& p : pc.projection) EXPECT_GE(p.segment, 0);
}
