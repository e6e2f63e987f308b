// The 3D contact geometry (docs/contact.md, "Three dimensions"): closest points on the master
// triangles, the tree search, the rim rule, the rows (27)-(28) and the nodal-area weights.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/master_surface.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/contact/triangle_hit.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;
using namespace contactrb::contact;
using Eigen::Vector3d;
using mesh::Mesh3;

namespace {

const Vector3d& X(const Mesh3& m, int node) { return m.nodes[static_cast<std::size_t>(node)]; }
void set(Eigen::VectorXd& v, int node, const Vector3d& value) { v.segment<3>(3 * node) = value; }

// Squared distance from x to triangle (a, b, c) by another route than the Voronoi regions of
// closest_on_triangle: the orthogonal projection on the plane when it falls inside (signed
// areas), else the nearest of the three edges.
double brute_distance2(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& x) {
  const Vector3d n = (b - a).cross(c - a);
  const Vector3d q = x - n * (x - a).dot(n) / n.squaredNorm();
  const double s0 = (b - q).cross(c - q).dot(n), s1 = (c - q).cross(a - q).dot(n), s2 = (a - q).cross(b - q).dot(n);
  if (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) return (x - q).squaredNorm();
  const auto edge = [&x](const Vector3d& p, const Vector3d& r) {
    const double t = std::clamp((x - p).dot(r - p) / (r - p).squaredNorm(), 0.0, 1.0);
    return (x - (p + t * (r - p))).squaredNorm();
  };
  return std::min({edge(a, b), edge(b, c), edge(c, a)});
}

// Signed gap of every slave node: g(w)_s - k(w; w)_s (docs/contact.md, "Formulation").
Eigen::VectorXd signed_gap(const PointwiseContact3& pc, const Eigen::VectorXd& w) { return pc.g - pc.K * w; }

// The master block of stacked_blocks(level, gap) mapped so that its top face is the sphere
// cap of radius R centred at (0.5, 0.5, -R): (x, y, z) -> c + (R + z) d, d = unit(x - 0.5,
// y - 0.5, R). The map keeps the tetrahedra positive.
Mesh3 sphere_cap_blocks(int level, double R) {
  Mesh3 m = mesh::stacked_blocks(level, 0.1);
  for (auto& p : m.nodes) {
    if (p.z() > 0.0) continue;  // slave block
    const Vector3d d = Vector3d(p.x() - 0.5, p.y() - 0.5, R).normalized();
    p = Vector3d(0.5, 0.5, -R) + (R + p.z()) * d;
  }
  return m;
}

}  // namespace

TEST(Projection3, ClosestPointOnTriangleEqualsAnIndependentComputation) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto rnd = [&] { return Vector3d(u(gen), u(gen), u(gen)); };
  for (int trial = 0; trial < 20000; ++trial) {
    const Vector3d a = rnd(), b = rnd(), c = rnd(), x = 2.0 * rnd();
    const TriangleHit h = closest_on_triangle(a, b, c, 7, x);
    const double truth = brute_distance2(a, b, c, x);
    ASSERT_NEAR(h.d2, truth, 1e-12 * (1.0 + truth)) << "trial " << trial;
    // The barycentric coordinates give the closest point itself.
    ASSERT_NEAR(h.phi.sum(), 1.0, 1e-14);
    ASSERT_GE(h.phi.minCoeff(), -1e-15);
    const Vector3d p = h.phi(0) * a + h.phi(1) * b + h.phi(2) * c;
    ASSERT_NEAR((x - p).squaredNorm(), truth, 1e-12 * (1.0 + truth));
    EXPECT_EQ(h.facet, 7);
  }
}

TEST(Projection3, TreeEqualsAllPairsAndBruteForceOnARandomSurface) {
  // A wavy, randomly perturbed master (stacked_blocks(2): 32 x 32 squares, 2048 triangles);
  // 2401 slave nodes scattered near, inside and far from it, a few exactly on vertices.
  const Mesh3 m = mesh::stacked_blocks(2, 0.05);
  const ContactPair3 pair = make_contact_pair(m);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (int v : pair.master) {
    const Vector3d& p = X(m, v);
    set(w, v, Vector3d(0.002 * u(gen), 0.002 * u(gen), 0.05 * std::sin(6.0 * p.x()) * std::cos(5.0 * p.y()) + 0.002 * u(gen)));
  }
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const Vector3d target = s % 2 == 0 ? Vector3d(0.5 + 0.6 * u(gen), 0.5 + 0.6 * u(gen), 0.05 * u(gen))
                                       : Vector3d(2.0 * u(gen), 2.0 * u(gen), 2.0 * u(gen));
    set(w, pair.slave[s], target - X(m, pair.slave[s]));
  }
  for (int k : {1, 3, 5}) {  // exactly on master vertices (interior and rim)
    const int v = pair.master[static_cast<std::size_t>(97 * k)];
    set(w, pair.slave[static_cast<std::size_t>(k)], X(m, v) + w.segment<3>(3 * v) - X(m, pair.slave[static_cast<std::size_t>(k)]));
  }
  ProjectionOptions brute, tree;
  brute.search = SearchMethod::AllPairs;
  tree.search = SearchMethod::Tree;
  const PointwiseContact3 a = project_slave_nodes(m, pair, w, brute);
  const PointwiseContact3 b = project_slave_nodes(m, pair, w, tree);
  const PointwiseContact3 c = project_slave_nodes(m, pair, w);  // Automatic: the tree
  const MasterSurface surface = deformed_master(m, pair, w);
  int non_candidates = 0;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    for (const PointwiseContact3* other : {&b, &c}) {
      const SlaveProjection3& p = a.projection[s];
      const SlaveProjection3& q = other->projection[s];
      ASSERT_EQ(p.facet, q.facet) << "slave " << s;
      ASSERT_EQ(p.phi, q.phi);
      ASSERT_EQ(p.distance, q.distance);
      ASSERT_EQ(p.normal, q.normal);
      ASSERT_EQ(p.rho, q.rho);
      ASSERT_EQ(p.candidate, q.candidate);
    }
    // Brute force over every triangle, independent closest-point routine.
    const Vector3d x = X(m, pair.slave[s]) + w.segment<3>(3 * pair.slave[s]);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : surface.face) {
      best = std::min(best, brute_distance2(surface.y[static_cast<std::size_t>(t[0])], surface.y[static_cast<std::size_t>(t[1])],
                                            surface.y[static_cast<std::size_t>(t[2])], x));
    }
    ASSERT_NEAR(a.projection[s].distance, std::sqrt(best), 1e-12) << "slave " << s;
    non_candidates += a.projection[s].candidate ? 0 : 1;
  }
  EXPECT_EQ(a.g, b.g);
  EXPECT_EQ(Eigen::MatrixXd(a.K - b.K).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT(a.projection[1].distance, 1e-15);
  EXPECT_GT(non_candidates, 0);  // the far nodes beyond the rim face no master
  EXPECT_LT(non_candidates, 3 * static_cast<int>(pair.slave.size()) / 4);
}

TEST(Projection3, RigidTranslationAlongTheNormalChangesEveryGapByD) {
  // Flat, non-matching (7 x 7 slave squares over 4 x 4 master squares), gap 0.05, same width:
  // the slave nodes on the sides lie exactly above the master rim and stay candidates.
  const Mesh3 m = mesh::stacked_blocks(0, 0.05);
  const ContactPair3 pair = make_contact_pair(m);
  const Eigen::VectorXd w0 = Eigen::VectorXd::Zero(m.num_dofs());
  const PointwiseContact3 p0 = project_slave_nodes(m, pair, w0);
  const Eigen::VectorXd gap0 = signed_gap(p0, w0);
  for (const double d : {0.02, -0.03, 0.25}) {
    Eigen::VectorXd w = w0;
    for (int v : pair.slave) set(w, v, Vector3d(0.0, 0.0, d));  // the master normal is +z
    const PointwiseContact3 p = project_slave_nodes(m, pair, w);
    const Eigen::VectorXd gap = signed_gap(p, w);
    for (std::size_t s = 0; s < pair.slave.size(); ++s) {
      ASSERT_TRUE(p.projection[s].candidate) << "slave " << s;
      EXPECT_NEAR(gap0(static_cast<Eigen::Index>(s)), 0.05, 1e-15);
      EXPECT_NEAR(gap(static_cast<Eigen::Index>(s)) - gap0(static_cast<Eigen::Index>(s)), d, 1e-15);
      EXPECT_EQ(p.projection[s].normal, Vector3d(0.0, 0.0, 1.0));
    }
  }
}

TEST(Projection3, NodalAreasSumToTheSlaveFaceArea) {
  const Mesh3 m = mesh::stacked_blocks(1, 0.0);  // slave face: 13 x 13 squares of side h
  const ContactPair3 pair = make_contact_pair(m);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::Collocation);
  ASSERT_EQ(q.weight.size(), static_cast<Eigen::Index>(pair.slave.size()));
  EXPECT_NEAR(q.weight.sum(), 1.0, 1e-14);
  const double h = 1.0 / 13.0;
  int interior = 0;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const Vector3d& p = X(m, pair.slave[s]);
    const bool inside = p.x() > 1e-12 && p.x() < 1.0 - 1e-12 && p.y() > 1e-12 && p.y() < 1.0 - 1e-12;
    if (!inside) continue;
    ++interior;
    EXPECT_NEAR(q.weight(static_cast<Eigen::Index>(s)), h * h, 1e-15);  // six triangles of h^2 / 2
  }
  EXPECT_EQ(interior, 12 * 12);
  EXPECT_EQ(q.center_node, pair.slave);
  // The rows are the weighted pointwise rows.
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const PointwiseContact3 pc = project_slave_nodes(m, pair, w);
  const ConstraintRows rows = constraint_rows(m, pair, q, pc, w);
  EXPECT_NEAR((rows.g - q.weight.cwiseProduct(pc.g)).cwiseAbs().maxCoeff(), 0.0, 1e-16);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> weighted = q.W * pc.K;
  EXPECT_NEAR((Eigen::MatrixXd(rows.K) - Eigen::MatrixXd(weighted)).cwiseAbs().maxCoeff(), 0.0, 1e-16);
  EXPECT_THROW(make_quadrature(m, pair, Discretization::LACSimpson), Error);
}

TEST(Projection3, KRowsAtAVertexAnEdgeAndAnInteriorPoint) {
  const Mesh3 m = mesh::stacked_blocks(0, 0.1);
  const ContactPair3 pair = make_contact_pair(m);
  // Master triangle 5 and a slave node placed 0.1 above chosen points of it.
  const int f = 5;
  const auto& t = pair.master_faces[static_cast<std::size_t>(f)];
  std::array<int, 3> node{};
  for (int i = 0; i < 3; ++i) node[static_cast<std::size_t>(i)] = pair.master[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
  const int s = 20;
  const int slave_node = pair.slave[static_cast<std::size_t>(s)];
  // Other triangles holding an edge or vertex of f: ties go to the lowest index.
  const auto lowest_face_with = [&pair](std::vector<int> vertices) {
    for (std::size_t g = 0; g < pair.master_faces.size(); ++g) {
      const auto& u = pair.master_faces[g];
      if (std::all_of(vertices.begin(), vertices.end(), [&u](int v) { return std::find(u.begin(), u.end(), v) != u.end(); })) {
        return static_cast<int>(g);
      }
    }
    return -1;
  };
  const std::vector<std::pair<Vector3d, std::vector<int>>> cases = {
      {Vector3d(0.0, 0.0, 1.0), {0}},                  // vertex t_2
      {Vector3d(0.5, 0.5, 0.0), {0, 1}},               // midpoint of edge (t_0, t_1)
      {Vector3d(0.2, 0.3, 0.5), {0, 1, 2}}};           // interior point
  for (const auto& [phi, on] : cases) {
    Vector3d target = Vector3d::Zero();
    for (int i = 0; i < 3; ++i) target += phi(i) * X(m, node[static_cast<std::size_t>(i)]);
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
    set(w, slave_node, target + Vector3d(0.0, 0.0, 0.1) - X(m, slave_node));
    const PointwiseContact3 pc = project_slave_nodes(m, pair, w);
    const SlaveProjection3& p = pc.projection[static_cast<std::size_t>(s)];
    ASSERT_TRUE(p.candidate);
    EXPECT_NEAR(p.distance, 0.1, 1e-15);
    // The reported triangle holds the target point and is the lowest such index.
    std::vector<int> support;
    for (int i = 0; i < 3; ++i) {
      if (phi(i) != 0.0) support.push_back(t[static_cast<std::size_t>(i)]);
    }
    EXPECT_EQ(p.facet, lowest_face_with(support));
    // K row: +phi at the z DOF of every master node with its weight, -1 at the slave's.
    const Eigen::VectorXd row = Eigen::MatrixXd(pc.K.row(s)).transpose();
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(m.num_dofs());
    for (int i = 0; i < 3; ++i) expected(3 * node[static_cast<std::size_t>(i)] + 2) += phi(i);
    expected(3 * slave_node + 2) = -1.0;
    EXPECT_NEAR((row - expected).cwiseAbs().maxCoeff(), 0.0, 1e-15) << "phi " << phi.transpose();
    EXPECT_NEAR((p.rho - target).norm(), 0.0, 1e-15);
    EXPECT_NEAR(pc.g(s), X(m, slave_node).z(), 1e-15);  // (X_s - rho) . n2 with rho on z = 0
    if (on.size() == 1) {
      EXPECT_EQ(p.phi.maxCoeff(), 1.0);  // a vertex exactly
    }
  }
}

TEST(Projection3, SlaveNodesBeyondTheRimAreNoCandidates) {
  const Mesh3 m = mesh::stacked_blocks(0, 0.1);
  const ContactPair3 pair = make_contact_pair(m);
  for (const Vector3d& shift : {Vector3d(0.3, 0.0, 0.0), Vector3d(-0.2, 0.35, 0.0), Vector3d(0.3, 0.3, 0.0)}) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
    for (int v : pair.slave) set(w, v, shift);
    const PointwiseContact3 pc = project_slave_nodes(m, pair, w);
    for (std::size_t s = 0; s < pair.slave.size(); ++s) {
      const Vector3d x = X(m, pair.slave[s]) + shift;
      const Vector3d inside = x.cwiseMax(Vector3d(0.0, 0.0, x.z())).cwiseMin(Vector3d(1.0, 1.0, x.z()));
      const bool over = (x - inside).norm() < 1e-12;  // above the unit master square
      const SlaveProjection3& p = pc.projection[s];
      ASSERT_EQ(p.candidate, over) << "slave " << s << " at " << x.transpose();
      EXPECT_NEAR(p.distance, (x - Vector3d(inside.x(), inside.y(), 0.0)).norm(), 1e-15);
      if (!over) {
        EXPECT_EQ(pc.K.row(static_cast<Eigen::Index>(s)).nonZeros(), 0);
        EXPECT_EQ(pc.g(static_cast<Eigen::Index>(s)), p.distance);
      }
    }
  }
}

TEST(Projection3, InterpolatedNormalsAgreeAcrossEveryEdge) {
  const Mesh3 m = sphere_cap_blocks(1, 1.0);
  const ContactPair3 pair = make_contact_pair(m);
  const MasterSurface surface = deformed_master(m, pair, Eigen::VectorXd::Zero(m.num_dofs()));
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edges;  // edge -> (face, opposite)
  for (int f = 0; f < surface.num_facets(); ++f) {
    const auto& t = surface.face[static_cast<std::size_t>(f)];
    for (int i = 0; i < 3; ++i) {
      const int a = t[static_cast<std::size_t>((i + 1) % 3)], b = t[static_cast<std::size_t>((i + 2) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(f, i);
    }
  }
  const auto phi_at = [&surface](int f, int a, int b, double tau) {
    Vector3d phi = Vector3d::Zero();
    const auto& t = surface.face[static_cast<std::size_t>(f)];
    for (int i = 0; i < 3; ++i) {
      if (t[static_cast<std::size_t>(i)] == a) phi(i) = 1.0 - tau;
      if (t[static_cast<std::size_t>(i)] == b) phi(i) = tau;
    }
    return phi;
  };
  int shared = 0;
  double jump = 0.0, kink = 0.0;
  for (const auto& [e, faces] : edges) {
    if (faces.size() != 2) continue;
    ++shared;
    const int f1 = faces[0].first, f2 = faces[1].first;
    for (const double tau : {0.0, 0.25, 0.5, 0.9}) {
      jump = std::max(jump, (surface.normal_at(f1, phi_at(f1, e.first, e.second, tau)) -
                             surface.normal_at(f2, phi_at(f2, e.first, e.second, tau)))
                                .norm());
    }
    kink = std::max(kink, (surface.normal[static_cast<std::size_t>(f1)] - surface.normal[static_cast<std::size_t>(f2)]).norm());
  }
  EXPECT_EQ(shared, 3 * 8 * 8 - 2 * 8);  // 8 x 8 squares cut in two: interior edges
  EXPECT_LT(jump, 1e-15);
  EXPECT_GT(kink, 1e-2);  // the triangle normals do jump
}

TEST(Projection3, SphereCapNormalsConvergeAtSecondOrder) {
  // Slave nodes placed on the sphere of radius R + 0.02 above the cap. Errors of n2 against
  // the sphere normal at the closest point, and of the signed gap against 0.02, for
  // h = 1/8, 1/16, 1/32 (master squares across the cap).
  const double R = 1.0, delta = 0.02;
  std::vector<double> normal_error, gap_error;
  for (int level = 1; level <= 3; ++level) {
    const Mesh3 m = sphere_cap_blocks(level, R);
    const ContactPair3 pair = make_contact_pair(m);
    const Vector3d c(0.5, 0.5, -R);
    Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
    std::vector<std::size_t> probes;
    for (std::size_t s = 0; s < pair.slave.size(); ++s) {
      const Vector3d& X0 = X(m, pair.slave[s]);
      const Vector3d d = Vector3d(X0.x() - 0.5, X0.y() - 0.5, R).normalized();
      set(w, pair.slave[s], c + (R + delta) * d - X0);
      if (std::abs(X0.x() - 0.5) < 0.4 && std::abs(X0.y() - 0.5) < 0.4) probes.push_back(s);
    }
    const PointwiseContact3 pc = project_slave_nodes(m, pair, w);
    const Eigen::VectorXd gap = signed_gap(pc, w);
    double en = 0.0, eg = 0.0;
    for (const std::size_t s : probes) {
      ASSERT_TRUE(pc.projection[s].candidate);
      // The exact normal at the closest point rho of the (undeformed) triangulated cap.
      en = std::max(en, (pc.projection[s].normal - (pc.projection[s].rho - c).normalized()).norm());
      eg = std::max(eg, std::abs(gap(static_cast<Eigen::Index>(s)) - delta));
    }
    normal_error.push_back(en);
    gap_error.push_back(eg);
  }
  for (std::size_t k = 1; k < normal_error.size(); ++k) {
    const double rate = std::log2(normal_error[k - 1] / normal_error[k]);
    EXPECT_GT(rate, 1.8) << "normal errors " << normal_error[k - 1] << " -> " << normal_error[k];
    EXPECT_GT(std::log2(gap_error[k - 1] / gap_error[k]), 1.8) << "gap errors " << gap_error[k - 1] << " -> " << gap_error[k];
  }
  EXPECT_LT(normal_error.back(), 1e-3);
  std::printf("sphere cap, h = 1/8, 1/16, 1/32: n2 error %.3g %.3g %.3g, gap error %.3g %.3g %.3g\n", normal_error[0],
              normal_error[1], normal_error[2], gap_error[0], gap_error[1], gap_error[2]);
}

TEST(Projection3, RejectsBadInput) {
  const Mesh3 m = mesh::stacked_blocks(0, 0.1);
  const ContactPair3 pair = make_contact_pair(m);
  EXPECT_THROW(project_slave_nodes(m, pair, Eigen::VectorXd::Zero(m.num_dofs() - 1)), Error);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  w(7) = std::nan("");
  EXPECT_THROW(project_slave_nodes(m, pair, w), Error);
  w.setZero();
  // A master triangle collapsed by the displacement has no normal.
  const auto& t = pair.master_faces.front();
  for (int i = 1; i < 3; ++i) {
    const int v = pair.master[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
    set(w, v, X(m, pair.master[static_cast<std::size_t>(t[0])]) - X(m, v));
  }
  EXPECT_THROW(project_slave_nodes(m, pair, w), Error);
  const std::vector<int> outside{static_cast<int>(pair.slave.size())};
  EXPECT_THROW(project_slave_nodes(m, pair, Eigen::VectorXd::Zero(m.num_dofs()), outside), Error);
  // Contact groups on the wrong body, or missing.
  Mesh3 swapped = m;
  std::swap(swapped.boundaries["slave"], swapped.boundaries["master"]);
  EXPECT_THROW(make_contact_pair(swapped), Error);
  Mesh3 missing = m;
  missing.boundaries.erase("master");
  EXPECT_THROW(make_contact_pair(missing), Error);
}

TEST(Projection3, RestrictedPositionsGiveTheRowsOfTheFullProjection) {
  const Mesh3 m = mesh::stacked_blocks(1, 0.05);
  const ContactPair3 pair = make_contact_pair(m);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  for (int v : pair.slave) set(w, v, Vector3d(0.01 * X(m, v).y(), 0.0, -0.02 * X(m, v).x()));
  const PointwiseContact3 full = project_slave_nodes(m, pair, w);
  const std::vector<int> positions{3, 17, 17, 100};
  const PointwiseContact3 some = project_slave_nodes(m, pair, w, positions);
  for (int s = 0; s < static_cast<int>(pair.slave.size()); ++s) {
    const bool listed = std::find(positions.begin(), positions.end(), s) != positions.end();
    const Eigen::RowVectorXd a = Eigen::MatrixXd(full.K.row(s)), b = Eigen::MatrixXd(some.K.row(s));
    if (listed) {
      EXPECT_EQ(a, b);
      EXPECT_EQ(full.g(s), some.g(s));
      EXPECT_EQ(full.projection[static_cast<std::size_t>(s)].facet, some.projection[static_cast<std::size_t>(s)].facet);
    } else {
      EXPECT_EQ(some.K.row(s).nonZeros(), 0);
      EXPECT_EQ(some.projection[static_cast<std::size_t>(s)].facet, -1);
    }
  }
}
