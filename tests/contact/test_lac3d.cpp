// The exactly integrated LAC in 3D (lac3d.hpp, docs/contact.md "LAC in three dimensions"),
// against independent truths: uniform fields, P1 fields integrated by the slave-side weights,
// consistent nodal areas, coverage areas computed by another route, and a fine quadrature of
// the pointwise maps (27)-(28) on a curved master.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/lac3d.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;
using namespace contactrb::contact;
using Eigen::Vector2d;
using Eigen::Vector3d;
using mesh::Mesh3;

namespace {

std::size_t sz(int i) { return static_cast<std::size_t>(i); }
const Vector3d& X(const Mesh3& m, int node) { return m.nodes[sz(node)]; }
void set(Eigen::VectorXd& v, int node, const Vector3d& value) { v.segment<3>(3 * node) = value; }

struct Lac {
  ContactPair3 pair;
  ContactQuadrature q;
  PointwiseContact3 pc;
  ConstraintRows rows;
};

Lac lac_rows(const Mesh3& m, const Eigen::VectorXd& w, Discretization d = Discretization::LAC) {
  Lac l;
  l.pair = make_contact_pair(m);
  l.q = make_quadrature(m, l.pair, d);
  l.pc = project_slave_nodes(m, l.pair, w);
  l.rows = constraint_rows(m, l.pair, l.q, l.pc, w);
  return l;
}

// A field equal to `value` on the nodes of body `body`, zero elsewhere.
Eigen::VectorXd body_field(const Mesh3& m, int body, const Vector3d& value) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(m.num_dofs());
  for (int t = 0; t < m.num_cells(); ++t) {
    if (m.body[sz(t)] != body) continue;
    for (int n : m.tetrahedra[sz(t)]) set(v, n, value);
  }
  return v;
}

// Nodal areas (a third of each adjacent triangle) of a group, deformed by w.
Eigen::VectorXd nodal_areas(const Mesh3& m, const char* group, const Eigen::VectorXd& w) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(m.num_nodes());
  for (const mesh::Face& f : m.boundary(group)) {
    const auto x = [&](int v) { return Vector3d(X(m, v) + w.segment<3>(3 * v)); };
    const double a = 0.5 * (x(f.b) - x(f.a)).cross(x(f.c) - x(f.a)).norm();
    for (int v : f.vertices()) area(v) += a / 3.0;
  }
  return area;
}

// The smooth tangential sliding of the master face used below: zero on its rim, so the
// deformed master stays the square [0, 1]^2 of the plane z = 0.
Vector3d sliding(const Vector3d& p) {
  const double b = std::sin(std::numbers::pi * p.x()) * std::sin(std::numbers::pi * p.y());
  return Vector3d(0.03 * b, -0.02 * b, 0.0);
}

// The slave point (reference, and displaced by w) at barycentric coordinates l of face f.
Vector3d face_point(const Mesh3& m, const mesh::Face& f, const Vector3d& l) {
  return l(0) * X(m, f.a) + l(1) * X(m, f.b) + l(2) * X(m, f.c);
}

// A coarse slave block [0, 1]^2 x [gap, gap + 0.5] (5 x 5 squares) on a finer master block
// [0, 1]^2 x [-0.5, 0] (11 x 11 squares): the other way round from stacked_blocks.
Mesh3 fine_master_blocks(double gap) {
  Mesh3 slave = mesh::box(Vector3d(0.0, 0.0, gap), Vector3d(1.0, 1.0, gap + 0.5), 5, 5, 2, mesh::kSlaveBody);
  Mesh3 master = mesh::box(Vector3d(0.0, 0.0, -0.5), Vector3d(1.0, 1.0, 0.0), 11, 11, 3, mesh::kMasterBody);
  for (const char* g : {"front", "back", "left", "right", "top"}) mesh::rename_boundary(slave, g, std::string("s_") + g);
  for (const char* g : {"front", "back", "left", "right", "bottom"}) {
    mesh::rename_boundary(master, g, std::string("m_") + g);
  }
  mesh::rename_boundary(slave, "bottom", mesh::kSlaveBoundary);
  mesh::rename_boundary(master, "top", mesh::kMasterBoundary);
  return mesh::merge(slave, master);
}

}  // namespace

TEST(Lac3, UniformGapAndNormalTranslationAreReproduced) {
  // Non-matching flat blocks, gap 0.05: 13 x 13 slave squares over 8 x 8 master squares
  // (stacked_blocks) and 5 x 5 over 11 x 11; w = 0 and w = the master sliding in its plane (the
  // segmentation changes, the gap does not).
  const double gap = 0.05, t = 0.01;
  for (const Mesh3& m : {mesh::stacked_blocks(1, gap), fine_master_blocks(gap)}) {
    const ContactPair3 pair = make_contact_pair(m);
    Eigen::VectorXd slide = Eigen::VectorXd::Zero(m.num_dofs());
    for (int v : pair.master) set(slide, v, sliding(X(m, v)));
    for (const Eigen::VectorXd& w : {Eigen::VectorXd(Eigen::VectorXd::Zero(m.num_dofs())), slide}) {
      const Lac l = lac_rows(m, w);
      ASSERT_EQ(l.rows.g.size(), static_cast<Eigen::Index>(pair.slave.size()));
      const Eigen::VectorXd& I = l.q.weight;
      EXPECT_NEAR((l.rows.g - gap * I).cwiseAbs().maxCoeff(), 0.0, 1e-16);
      // A rigid normal translation of the slave block (toward the master) and of the master block.
      const Eigen::VectorXd down = l.rows.K * body_field(m, mesh::kSlaveBody, Vector3d(0.0, 0.0, -t));
      const Eigen::VectorXd up = l.rows.K * body_field(m, mesh::kMasterBody, Vector3d(0.0, 0.0, t));
      EXPECT_NEAR((down - t * I).cwiseAbs().maxCoeff(), 0.0, 1e-17);
      EXPECT_NEAR((up - t * I).cwiseAbs().maxCoeff(), 0.0, 1e-17);
      // K' 1 is the consistent load of a unit pressure: the nodal areas of both surfaces (the
      // master's deformed by the sliding), normal to the interface (the patch-test property).
      const Eigen::VectorXd load = l.rows.K.transpose() * Eigen::VectorXd::Ones(l.rows.K.rows());
      const Eigen::VectorXd slave_area = nodal_areas(m, mesh::kSlaveBoundary, w);
      const Eigen::VectorXd master_area = nodal_areas(m, mesh::kMasterBoundary, w);
      double worst = 0.0;
      for (int v = 0; v < m.num_nodes(); ++v) {
        worst = std::max(worst, std::abs(load(3 * v)) + std::abs(load(3 * v + 1)));
        worst = std::max(worst, std::abs(load(3 * v + 2) - (master_area(v) - slave_area(v))));
      }
      EXPECT_LT(worst, 1e-16);
    }
  }
}

TEST(Lac3, WeightsAreTheSlaveSideIntegralsAndCoverageIsComplete) {
  const Mesh3 m = mesh::stacked_blocks(1, 0.0);
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const Lac l = lac_rows(m, w);
  const ContactQuadrature collocation = make_quadrature(m, l.pair, Discretization::Collocation);
  EXPECT_NEAR(l.q.weight.sum(), 1.0, 1e-14);  // the slave face
  EXPECT_NEAR((l.q.weight - collocation.weight).cwiseAbs().maxCoeff(), 0.0, 1e-17);
  EXPECT_EQ(l.q.center_node, l.pair.slave);
  // W integrates P1 slave fields exactly over the dual cells: 1 and x over the cells of an
  // interior node of the structured slave face (six triangles, point symmetric) give |I_r|
  // and x_r |I_r|.
  Eigen::VectorXd xs(static_cast<Eigen::Index>(l.pair.slave.size()));
  for (std::size_t s = 0; s < l.pair.slave.size(); ++s) xs(static_cast<Eigen::Index>(s)) = X(m, l.pair.slave[s]).x();
  const Eigen::VectorXd Wx = l.q.W * xs;
  for (std::size_t s = 0; s < l.pair.slave.size(); ++s) {
    const Vector3d& p = X(m, l.pair.slave[s]);
    if (p.x() < 1e-12 || p.x() > 1.0 - 1e-12 || p.y() < 1e-12 || p.y() > 1.0 - 1e-12) continue;
    EXPECT_NEAR(Wx(static_cast<Eigen::Index>(s)), p.x() * l.q.weight(static_cast<Eigen::Index>(s)), 1e-16);
  }
  // The pieces of each slave triangle over the master triangles add up to its area.
  const LacCoverage3 c = lac_coverage(m, l.pair, l.pc, w);
  EXPECT_EQ(c.triangle_area.size(), static_cast<Eigen::Index>(l.pair.slave_faces.size()));
  EXPECT_NEAR((c.covered_area - c.triangle_area).cwiseAbs().maxCoeff(), 0.0, 1e-17);
  EXPECT_NEAR((c.row_covered - l.q.weight).cwiseAbs().maxCoeff(), 0.0, 1e-17);
  EXPECT_NEAR(c.triangle_area.sum(), 1.0, 1e-14);
}

TEST(Lac3, TiltedSlaveOnAFlatMasterIsIntegratedExactly) {
  // The slave block rotated by w about the line y = 0.5, z = 0.1 (angle 0.04): the signed gap is
  // affine on each slave triangle, so its exact cell integrals are W times its nodal values.
  const Mesh3 m = mesh::stacked_blocks(1, 0.1);
  const ContactPair3 pair = make_contact_pair(m);
  const double angle = 0.04;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle, Vector3d::UnitX()).toRotationMatrix();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const Vector3d axis_point(0.0, 0.5, 0.1);
  for (int t = 0; t < m.num_cells(); ++t) {
    if (m.body[sz(t)] != mesh::kSlaveBody) continue;
    for (int n : m.tetrahedra[sz(t)]) set(w, n, axis_point + Q * (X(m, n) - axis_point) - X(m, n));
  }
  const Lac l = lac_rows(m, w);
  const Eigen::VectorXd signed_gap_rows = l.rows.g - l.rows.K * w;
  const Eigen::VectorXd signed_gap_nodes = l.pc.g - l.pc.K * w;
  EXPECT_GT(signed_gap_nodes.maxCoeff() - signed_gap_nodes.minCoeff(), 0.03);  // really tilted
  EXPECT_NEAR((signed_gap_rows - l.q.W * signed_gap_nodes).cwiseAbs().maxCoeff(), 0.0, 1e-15);
  // An affine normal field on the master (reference coordinates): its values at the feet of the
  // slave points are affine on each slave triangle too.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(m.num_dofs());
  const auto field = [](const Vector3d& p) { return 0.3 + 0.7 * p.x() - 0.4 * p.y(); };
  for (int n : pair.master) set(v, n, Vector3d(0.0, 0.0, field(X(m, n))));
  Eigen::VectorXd at_feet(static_cast<Eigen::Index>(pair.slave.size()));
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const int n = pair.slave[s];
    at_feet(static_cast<Eigen::Index>(s)) = field(X(m, n) + w.segment<3>(3 * n));
  }
  EXPECT_NEAR((l.rows.K * v - l.q.W * at_feet).cwiseAbs().maxCoeff(), 0.0, 1e-15);
}

TEST(Lac3, RotatedBlocksKeepTheUniformGap) {
  // The whole patch geometry rotated (a tilted flat master): round-off only.
  Mesh3 m = mesh::stacked_blocks(1, 0.05);
  const Eigen::Matrix3d Q =
      (Eigen::AngleAxisd(0.7, Vector3d(1.0, 2.0, 0.5).normalized())).toRotationMatrix();
  for (auto& p : m.nodes) p = Q * p + Vector3d(0.2, -0.1, 0.3);
  const Lac l = lac_rows(m, Eigen::VectorXd::Zero(m.num_dofs()));
  EXPECT_NEAR((l.rows.g - 0.05 * l.q.weight).cwiseAbs().maxCoeff(), 0.0, 1e-15);
  const Eigen::VectorXd down = l.rows.K * body_field(m, mesh::kSlaveBody, Q * Vector3d(0.0, 0.0, -0.01));
  EXPECT_NEAR((down - 0.01 * l.q.weight).cwiseAbs().maxCoeff(), 0.0, 1e-16);
}

TEST(Lac3, SlaveCellsPartlyBeyondTheRim) {
  // The slave block shifted by s along x: its cells beyond x = 1 face no master triangle.
  const double gap = 0.05, shift = 0.3;
  const Mesh3 m = mesh::stacked_blocks(1, gap);
  const ContactPair3 pair = make_contact_pair(m);
  const Eigen::VectorXd w = body_field(m, mesh::kSlaveBody, Vector3d(shift, 0.0, 0.0));
  const Lac l = lac_rows(m, w);
  const LacCoverage3 c = lac_coverage(m, l.pair, l.pc, w);
  // Truth by another route: the area of each (reference) dual cell left of x = 1 - shift, as
  // the integral of the cell's height over x (affine between the cell's vertices: midpoint
  // rule per piece).
  const double cut = 1.0 - shift;
  Eigen::VectorXd truth = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(pair.slave.size()));
  for (const mesh::Face& f : pair.slave_faces) {
    for (int a = 0; a < 3; ++a) {
      Vector3d la = Vector3d::Zero(), lab = Vector3d::Zero(), lac = Vector3d::Zero();
      la(a) = 1.0;
      lab(a) = lab((a + 1) % 3) = 0.5;
      lac(a) = lac((a + 2) % 3) = 0.5;
      const std::array<Vector3d, 4> corner{face_point(m, f, la), face_point(m, f, lab),
                                           face_point(m, f, Vector3d::Constant(1.0 / 3.0)), face_point(m, f, lac)};
      std::vector<double> xs{cut};
      for (const auto& p : corner) xs.push_back(p.x());
      std::sort(xs.begin(), xs.end());
      const auto height = [&corner](double x) {
        double lo = 1e300, hi = -1e300;
        for (std::size_t i = 0; i < 4; ++i) {
          const Vector3d& p = corner[i];
          const Vector3d& q = corner[(i + 1) % 4];
          if ((p.x() - x) * (q.x() - x) > 0.0 || p.x() == q.x()) continue;
          const double y = p.y() + (x - p.x()) / (q.x() - p.x()) * (q.y() - p.y());
          lo = std::min(lo, y);
          hi = std::max(hi, y);
        }
        return hi > lo ? hi - lo : 0.0;
      };
      double area = 0.0;
      for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
        if (xs[i + 1] > cut || xs[i + 1] <= xs[i]) continue;
        area += (xs[i + 1] - xs[i]) * height(0.5 * (xs[i] + xs[i + 1]));
      }
      const int node = f.vertices()[sz(a)];
      const auto s = std::lower_bound(pair.slave.begin(), pair.slave.end(), node) - pair.slave.begin();
      truth(s) += area;
    }
  }
  EXPECT_NEAR((c.row_covered - truth).cwiseAbs().maxCoeff(), 0.0, 1e-15);
  int beyond = 0, straddling = 0;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const auto r = static_cast<Eigen::Index>(s);
    const double I = l.q.weight(r), covered = truth(r);
    // The K row acts on the covered part only: its normal components sum to -covered on the
    // slave nodes and +covered on the master nodes (flat master, n2 = e_z).
    double slave_sum = 0.0, master_sum = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(l.rows.K, r); it; ++it) {
      if (it.col() % 3 != 2) continue;
      const int node = static_cast<int>(it.col() / 3);
      (std::binary_search(pair.slave.begin(), pair.slave.end(), node) ? slave_sum : master_sum) += it.value();
    }
    EXPECT_NEAR(slave_sum, -covered, 1e-15);
    EXPECT_NEAR(master_sum, covered, 1e-15);
    // The uncovered part adds (its area) x (a distance to the master >= gap) to g.
    EXPECT_GE(l.rows.g(r), gap * I - 1e-16);
    if (covered == 0.0) {
      ++beyond;
      EXPECT_EQ(l.rows.K.row(r).nonZeros(), 0);
      const double x = X(m, pair.slave[s]).x() + shift;
      EXPECT_GT(l.rows.g(r), gap * I);
      EXPECT_LT(l.rows.g(r), std::hypot(x - 1.0 + 0.1, gap) * I);  // the farthest corner of the cell
    } else if (covered < I - 1e-15) {
      ++straddling;
      EXPECT_GT(l.rows.g(r), gap * I);
    } else {
      EXPECT_NEAR(l.rows.g(r), gap * I, 1e-16);
    }
  }
  EXPECT_GT(beyond, 40);
  EXPECT_GT(straddling, 10);
}

namespace {

// The contact patch test (docs/contact.md, "Contact patch test") with every row active: two
// blocks of one material pressed by Dirichlet data that the uniform stress sigma_zz = -p holds
// exactly (u = (nu p / E (x - 1/2), nu p / E (y - 1/2), -p / E (z + 1/2)) on both blocks, which
// touch at z = 0) on the slave top and the master bottom, the lateral faces free; the saddle point A u + K' lambda = f, K u = g on the free DOFs, solved by its Schur
// complement. The FE solution is the exact one and lambda = p if the rows give every
// interface node its consistent load.
struct PatchResult {
  double pressure_error = 0.0;      // max |lambda_r - p| / p
  double displacement_error = 0.0;  // max |u - exact| / (p / E)
};

PatchResult patch_test(int level, Discretization d) {
  const double E = 10.0, nu = 0.3, p = 0.2;
  const Mesh3 m = mesh::stacked_blocks(level, 0.0);
  const fem::Material material{E, nu};
  const fem::SparseMatrix A = fem::stiffness(m, std::vector<fem::Material>{material, material});
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(m.num_dofs());
  const Lac l = lac_rows(m, w, d);
  const double strain = p / E;
  Eigen::VectorXd exact(m.num_dofs());
  for (int n = 0; n < m.num_nodes(); ++n) {
    const Vector3d& x = X(m, n);
    set(exact, n, Vector3d(nu * strain * (x.x() - 0.5), nu * strain * (x.y() - 0.5), -strain * (x.z() + 0.5)));
  }
  // Dirichlet: every component on the slave top and the master bottom.
  std::vector<char> fixed(sz(m.num_dofs()), 0);
  for (const char* group : {"top", "bottom"}) {
    for (const mesh::Face& f : m.boundary(group)) {
      for (int v : f.vertices()) {
        for (int c = 0; c < 3; ++c) fixed[sz(3 * v + c)] = 1;
      }
    }
  }
  std::vector<int> free_dofs;
  for (int i = 0; i < m.num_dofs(); ++i) {
    if (fixed[sz(i)] == 0) free_dofs.push_back(i);
  }
  const auto F = static_cast<Eigen::Index>(free_dofs.size());
  Eigen::SparseMatrix<double> P(m.num_dofs(), F);  // free DOFs -> all DOFs
  for (Eigen::Index k = 0; k < F; ++k) P.insert(free_dofs[sz(static_cast<int>(k))], k) = 1.0;
  Eigen::VectorXd lift = exact;
  for (int i : free_dofs) lift(i) = 0.0;
  const Eigen::SparseMatrix<double> Aff = P.transpose() * A * P;
  const Eigen::SparseMatrix<double> Kf = Eigen::SparseMatrix<double>(l.rows.K) * P;
  const Eigen::VectorXd ff = -(P.transpose() * (A * lift));
  const Eigen::VectorXd gf = l.rows.g - l.rows.K * lift;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Aff);
  const Eigen::MatrixXd AinvKt = ldlt.solve(Eigen::MatrixXd(Kf.transpose()));
  const Eigen::MatrixXd S = Kf * AinvKt;
  const Eigen::VectorXd lambda = S.llt().solve(Kf * ldlt.solve(ff) - gf);
  const Eigen::VectorXd u = lift + P * ldlt.solve(ff - Kf.transpose() * lambda);
  PatchResult r;
  r.pressure_error = (lambda.array() - p).abs().maxCoeff() / p;
  r.displacement_error = (u - exact).cwiseAbs().maxCoeff() / strain;
  return r;
}

}  // namespace

TEST(Lac3, PatchTestGivesTheUniformPressureToRoundOff) {
  for (int level : {0, 1}) {
    const PatchResult lac = patch_test(level, Discretization::LAC);
    const PatchResult col = patch_test(level, Discretization::Collocation);
    std::printf("level %d: pressure error LAC %.2e, collocation %.2e; displacement error LAC %.2e, collocation %.2e\n",
                level, lac.pressure_error, col.pressure_error, lac.displacement_error, col.displacement_error);
    EXPECT_LT(lac.pressure_error, 1e-11);
    EXPECT_LT(lac.displacement_error, 1e-11);
    EXPECT_GT(col.pressure_error, 1e-3);  // non-matching meshes: collocation fails it
  }
}

namespace {

// The master face of stacked_blocks(level, gap) lifted onto the sphere of radius R through
// (0.5, 0.5, 0): z += sqrt(R^2 - r^2) - R, r the distance to the axis x = y = 0.5 (a graph over
// the unit square: the rim stays above the square's edges). The slave face gets a smooth bump.
struct Curved {
  Mesh3 m;
  Eigen::VectorXd w, v;
};

Curved curved(int level) {
  constexpr double R = 1.5;
  Curved c;
  c.m = mesh::stacked_blocks(level, 0.05);
  for (auto& p : c.m.nodes) {
    if (p.z() > 1e-12) continue;  // slave block
    const double r2 = (p.x() - 0.5) * (p.x() - 0.5) + (p.y() - 0.5) * (p.y() - 0.5);
    p.z() += (std::sqrt(R * R - r2) - R) * (1.0 + p.z() / 0.5);  // the bottom stays flat
  }
  c.w = Eigen::VectorXd::Zero(c.m.num_dofs());
  c.v = Eigen::VectorXd::Zero(c.m.num_dofs());
  for (int n = 0; n < c.m.num_nodes(); ++n) {
    const Vector3d& p = X(c.m, n);
    if (p.z() > 1e-12) set(c.w, n, Vector3d(0.01 * p.y(), 0.0, -0.03 * std::cos(2.0 * p.x()) * std::cos(1.5 * p.y())));
    set(c.v, n, Vector3d(std::sin(p.x() + 0.3 * p.z()), std::cos(2.0 * p.y()), 1.0 + p.x() * p.y() - p.z()));
  }
  return c;
}

// Rows of the slave nodes in [0.25, 0.75]^2 (far from the rim: every point of their cells
// projects inside the master).
std::vector<int> central_rows(const Mesh3& m, const ContactPair3& pair) {
  std::vector<int> rows;
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const Vector3d& p = X(m, pair.slave[s]);
    if (std::abs(p.x() - 0.5) <= 0.25 && std::abs(p.y() - 0.5) <= 0.25) rows.push_back(static_cast<int>(s));
  }
  return rows;
}

// The rows r of `rows` computed by a fine quadrature of the pointwise maps (27)-(28): each
// dual cell split into its two triangles (vertex, midpoint, centroid), each refined n x n, the
// centroid rule on every small triangle, the pointwise maps at these points by
// project_slave_nodes on a copy of the mesh holding them as slave nodes.
struct FineRows {
  Eigen::VectorXd g, Kv;
};

FineRows fine_rows(const Mesh3& m, const ContactPair3& pair, const Eigen::VectorXd& w, const Eigen::VectorXd& v,
                   const std::vector<int>& rows, int n) {
  Mesh3 aux;
  aux.nodes = m.nodes;
  std::vector<Vector3d> lambdas;  // per point: barycentric coordinates in its face
  std::vector<int> face_of, row_of;
  std::vector<double> weight;
  for (std::size_t fi = 0; fi < pair.slave_faces.size(); ++fi) {
    const mesh::Face& f = pair.slave_faces[fi];
    const double area = 0.5 * (X(m, f.b) - X(m, f.a)).cross(X(m, f.c) - X(m, f.a)).norm();
    for (int a = 0; a < 3; ++a) {
      const int node = f.vertices()[sz(a)];
      const int s = static_cast<int>(std::lower_bound(pair.slave.begin(), pair.slave.end(), node) - pair.slave.begin());
      const auto it = std::lower_bound(rows.begin(), rows.end(), s);
      if (it == rows.end() || *it != s) continue;
      for (int half = 1; half <= 2; ++half) {
        Vector3d A = Vector3d::Zero(), B = Vector3d::Zero(), C = Vector3d::Constant(1.0 / 3.0);
        A(a) = 1.0;
        B(a) = 0.5;
        B((a + half) % 3) = 0.5;
        // Each half of the cell is a sixth of the face.
        for (int i = 0; i < n; ++i) {
          for (int j = 0; i + j < n; ++j) {
            const auto point = [&](double u, double t) { return Vector3d(A + u / n * (B - A) + t / n * (C - A)); };
            const std::array<std::array<Vector3d, 3>, 2> small{
                std::array<Vector3d, 3>{point(i, j), point(i + 1, j), point(i, j + 1)},
                std::array<Vector3d, 3>{point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)}};
            for (int k = 0; k < (i + j + 1 < n ? 2 : 1); ++k) {
              lambdas.push_back((small[sz(k)][0] + small[sz(k)][1] + small[sz(k)][2]) / 3.0);
              face_of.push_back(static_cast<int>(fi));
              row_of.push_back(static_cast<int>(it - rows.begin()));
              weight.push_back(area / 6.0 / (n * n));
            }
          }
        }
      }
    }
  }
  ContactPair3 p = pair;
  p.slave.clear();
  Eigen::VectorXd wa = Eigen::VectorXd::Zero(3 * (m.num_nodes() + static_cast<int>(lambdas.size())));
  Eigen::VectorXd va = wa;
  wa.head(m.num_dofs()) = w;
  va.head(m.num_dofs()) = v;
  for (std::size_t q = 0; q < lambdas.size(); ++q) {
    const mesh::Face& f = pair.slave_faces[sz(face_of[q])];
    const Vector3d& l = lambdas[q];
    const int node = static_cast<int>(aux.nodes.size());
    aux.nodes.push_back(face_point(m, f, l));
    for (int c = 0; c < 3; ++c) {
      wa(3 * node + c) = l(0) * w(3 * f.a + c) + l(1) * w(3 * f.b + c) + l(2) * w(3 * f.c + c);
      va(3 * node + c) = l(0) * v(3 * f.a + c) + l(1) * v(3 * f.b + c) + l(2) * v(3 * f.c + c);
    }
    p.slave.push_back(node);
  }
  const PointwiseContact3 pc = project_slave_nodes(aux, p, wa);
  const Eigen::VectorXd Kv = pc.K * va;
  FineRows out;
  out.g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size()));
  out.Kv = out.g;
  for (std::size_t q = 0; q < lambdas.size(); ++q) {
    EXPECT_TRUE(pc.projection[q].candidate);
    out.g(row_of[q]) += weight[q] * pc.g(static_cast<Eigen::Index>(q));
    out.Kv(row_of[q]) += weight[q] * Kv(static_cast<Eigen::Index>(q));
  }
  return out;
}

}  // namespace

TEST(Lac3, CurvedMasterAgreesWithAFineQuadratureOfThePointwiseMaps) {
  std::vector<double> error_g, error_Kv;
  for (int level : {0, 1, 2}) {
    const Curved c = curved(level);
    const Lac l = lac_rows(c.m, c.w);
    const std::vector<int> rows = central_rows(c.m, l.pair);
    const FineRows fine = fine_rows(c.m, l.pair, c.w, c.v, rows, 12);
    const Eigen::VectorXd Kv = l.rows.K * c.v;
    double eg = 0.0, ek = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(rows[i]);
      const auto k = static_cast<Eigen::Index>(i);
      eg = std::max(eg, std::abs(l.rows.g(r) - fine.g(k)) / l.q.weight(r));
      ek = std::max(ek, std::abs(Kv(r) - fine.Kv(k)) / l.q.weight(r));
    }
    error_g.push_back(eg);
    error_Kv.push_back(ek);
    std::printf("level %d: %zu rows, max |g_r - fine| / |I_r| = %.2e, max |(K v)_r - fine| / |I_r| = %.2e\n", level,
                rows.size(), eg, ek);
  }
  // The gaps converge at second order. K v converges more slowly: the rows take the master
  // point along d_T, the pointwise maps the closest point on the faceted master; the feet differ
  // by about (gap) x (angle between a master facet and the smooth normal), O(gap h / R).
  for (std::size_t i = 1; i < error_g.size(); ++i) EXPECT_LT(error_g[i], 0.4 * error_g[i - 1]);
  EXPECT_LT(error_g.back(), 5e-5);
  EXPECT_LT(error_Kv.back(), 0.3 * error_Kv.front());
  EXPECT_LT(error_Kv.back(), 1e-3);
}

TEST(Lac3, RowsAndCollocationConvergeToEachOther) {
  std::vector<double> dg, dk;
  for (int level : {0, 1, 2}) {
    const Curved c = curved(level);
    const Lac lac = lac_rows(c.m, c.w);
    const Lac col = lac_rows(c.m, c.w, Discretization::Collocation);
    const std::vector<int> rows = central_rows(c.m, lac.pair);
    const Eigen::VectorXd a = lac.rows.K * c.v, b = col.rows.K * c.v;
    double eg = 0.0, ek = 0.0;
    for (int r : rows) {
      const double I = lac.q.weight(r);
      ASSERT_NEAR(I, col.q.weight(r), 1e-17);
      eg = std::max(eg, std::abs(lac.rows.g(r) - col.rows.g(r)) / I);
      ek = std::max(ek, std::abs(a(r) - b(r)) / I);
    }
    dg.push_back(eg);
    dk.push_back(ek);
    std::printf("level %d: max |g_lac - g_col| / |I_r| = %.2e, max |K_lac v - K_col v| / |I_r| = %.2e\n", level, eg, ek);
  }
  for (std::size_t i = 1; i < dg.size(); ++i) {
    EXPECT_LT(dg[i], 0.8 * dg[i - 1]);
    EXPECT_LT(dk[i], 0.8 * dk[i - 1]);
  }
  EXPECT_LT(dg.back(), 0.3 * dg.front());  // h / 4: about h^1.1 and h^1.3 over these levels
  EXPECT_LT(dk.back(), 0.3 * dk.front());
}

TEST(Lac3, RestrictedRowsAreTheFullRows) {
  const Curved c = curved(0);
  const Lac l = lac_rows(c.m, c.w);
  const std::vector<int> rows{0, 5, 17, 17, 30};
  const std::vector<int> positions = lac_slave_positions(l.pair, rows);
  const PointwiseContact3 some = project_slave_nodes(c.m, l.pair, c.w, positions);
  const ConstraintRows restricted = integrate_lac_rows(c.m, l.pair, l.q, some, c.w, rows);
  for (int r = 0; r < static_cast<int>(l.pair.slave.size()); ++r) {
    const bool in = std::find(rows.begin(), rows.end(), r) != rows.end();
    EXPECT_EQ(restricted.g(r), in ? l.rows.g(r) : 0.0);
    const Eigen::SparseVector<double> a = restricted.K.row(r), b = l.rows.K.row(r);
    EXPECT_EQ(a.nonZeros(), in ? b.nonZeros() : 0);
    if (in) {
      EXPECT_EQ((Eigen::VectorXd(a) - Eigen::VectorXd(b)).cwiseAbs().maxCoeff(), 0.0);
    }
  }
  // A row needing an unprojected slave node, a row outside [0, R), a wrong quadrature.
  const std::vector<int> other{40};
  EXPECT_THROW(integrate_lac_rows(c.m, l.pair, l.q, some, c.w, other), Error);
  const std::vector<int> outside{static_cast<int>(l.pair.slave.size())};
  EXPECT_THROW(integrate_lac_rows(c.m, l.pair, l.q, l.pc, c.w, outside), Error);
  const ContactQuadrature col = make_quadrature(c.m, l.pair, Discretization::Collocation);
  EXPECT_THROW(integrate_lac_rows(c.m, l.pair, col, l.pc, c.w), Error);
  EXPECT_THROW(integrate_lac_rows(c.m, l.pair, l.q, l.pc, Eigen::VectorXd::Zero(3)), Error);
  Eigen::VectorXd bad = c.w;
  bad(7) = std::nan("");
  EXPECT_THROW(integrate_lac_rows(c.m, l.pair, l.q, l.pc, bad), Error);
  EXPECT_THROW(lac_coverage(c.m, l.pair, l.pc, bad), Error);
  EXPECT_THROW(make_quadrature(c.m, l.pair, Discretization::LACSimpson), Error);
}
