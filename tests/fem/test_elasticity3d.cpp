// P1 tetrahedra (Dim = 3) through the fem/ code shared with plane strain: element kernels,
// rigid-body kernels, patch test, uniaxial bar, tractions, products and quadrature, against
// analytic values.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "contactrb/common/error.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/fem/p1_element.hpp"
#include "contactrb/fem/quadrature.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;
using namespace contactrb::fem;

namespace {

const Eigen::Vector3d q0(0.1, -0.2, 0.05), q1(1.3, 0.1, -0.1), q2(0.4, 1.1, 0.2), q3(0.3, 0.2, 0.9);

// A box, interior perturbed: an unstructured tetrahedral mesh.
mesh::Mesh3 unstructured_box(int n) {
  mesh::Mesh3 m = mesh::box({0, 0, 0}, {1.0, 0.8, 0.6}, n, n, n);
  mesh::perturb_interior(m, 0.15, 11);
  return m;
}

// Translations (k = 0, 1, 2) and rotations about the axes (k = 3, 4, 5): u(x) = e_k x x.
Eigen::VectorXd rigid_mode3(const mesh::Mesh3& m, int k) {
  Eigen::VectorXd r(m.num_dofs());
  for (int v = 0; v < m.num_nodes(); ++v) {
    const Eigen::Vector3d& x = m.nodes[static_cast<std::size_t>(v)];
    r.segment<3>(3 * v) = k < 3 ? Eigen::Vector3d(Eigen::Vector3d::Unit(k)) : Eigen::Vector3d(Eigen::Vector3d::Unit(k - 3).cross(x));
  }
  return r;
}

// Solves K u = f with the DOFs of `dofs` prescribed to `prescribed` (global vector).
Eigen::VectorXd solve_with(const SparseMatrix& K, const Eigen::VectorXd& f, const DofMap& dofs,
                           const Eigen::VectorXd& prescribed) {
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(K.rows());
  for (int d : dofs.constrained_dofs()) lift(d) = prescribed(d);
  const SparseMatrix A = dofs.restrict_matrix(K);
  const Eigen::VectorXd b = dofs.restrict(f - K * lift);
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  return lift + dofs.extend(ldlt.solve(b));
}

std::vector<DirichletCondition> clamp_all(const mesh::Mesh3& m) {
  std::vector<DirichletCondition> c;
  for (const auto& [name, faces] : m.boundaries) c.push_back({name, 0.0, 0.0, 0.0});
  return c;
}

}  // namespace

TEST(Tetrahedron, GradientsVolumeAndKernels) {
  const P1Tetrahedron t = p1_tetrahedron(q0, q1, q2, q3);
  EXPECT_NEAR(t.volume, (q1 - q0).dot((q2 - q0).cross(q3 - q0)) / 6.0, 1e-15);
  // f(x) = 1 + 2x - 3y + 4z interpolated at the vertices has gradient (2, -3, 4).
  auto f = [](const Eigen::Vector3d& x) { return 1.0 + 2.0 * x.x() - 3.0 * x.y() + 4.0 * x.z(); };
  const Eigen::Vector3d g = t.grad.transpose() * Eigen::Vector4d(f(q0), f(q1), f(q2), f(q3));
  EXPECT_LT((g - Eigen::Vector3d(2, -3, 4)).norm(), 1e-13);
  EXPECT_LT(t.grad.colwise().sum().norm(), 1e-14);  // partition of unity
  EXPECT_THROW(p1_tetrahedron(q0, q2, q1, q3), contactrb::Error);
  const SimplexElementMatrix<3> M = element_mass(t);
  double total = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) total += M(3 * i, 3 * j);
  EXPECT_NEAR(total, t.volume, 1e-15);
  for (const SimplexElementMatrix<3>& K :
       {element_divergence(t), element_symmetric_gradient(t), element_laplacian(t), element_mass(t)}) {
    EXPECT_EQ(K, K.transpose());
  }
  // Strain of the field u = A x: the Voigt vector (A_xx, A_yy, A_zz, A_xy + A_yx, A_yz + A_zy, A_xz + A_zx).
  Eigen::Matrix3d A;
  A << 0.1, 0.2, -0.3, 0.4, -0.5, 0.6, 0.7, 0.8, 0.9;
  Eigen::Matrix<double, 12, 1> ue;
  const Eigen::Vector3d p[4] = {q0, q1, q2, q3};
  for (int i = 0; i < 4; ++i) ue.segment<3>(3 * i) = A * p[i];
  const VoigtVector<3> eps = strain_operator(t) * ue;
  VoigtVector<3> expected;
  expected << 0.1, -0.5, 0.9, 0.6, 1.4, 0.4;
  EXPECT_LT((eps - expected).norm(), 1e-13);
}

TEST(Tetrahedron, HookeStressIsLameLaw) {
  const Material mat{210.0, 0.3};
  VoigtVector<3> eps;
  eps << 1e-3, -2e-3, 5e-4, 2e-4, -6e-4, 8e-4;
  const VoigtVector<3> s = hooke_stress<3>(eps, mat.lame_lambda(), mat.lame_mu());
  // lambda = E nu / ((1 + nu)(1 - 2 nu)) = 121.153846..., mu = E / (2 (1 + nu)) = 80.769230...
  const double lambda = 210.0 * 0.3 / (1.3 * 0.4), mu = 210.0 / 2.6;
  const double tr = 1e-3 - 2e-3 + 5e-4;
  EXPECT_NEAR(s(0), lambda * tr + 2 * mu * 1e-3, 1e-12);
  EXPECT_NEAR(s(2), lambda * tr + 2 * mu * 5e-4, 1e-12);
  EXPECT_NEAR(s(4), mu * -6e-4, 1e-12);  // sigma_yz = 2 mu eps_yz = mu (2 eps_yz)
}

TEST(Elasticity3d, StiffnessSymmetricWithSixRigidModes) {
  const mesh::Mesh3 m = unstructured_box(2);
  const SparseMatrix K = stiffness(m, {Material{15.0, 0.35}});
  EXPECT_EQ(K.rows(), 3 * m.num_nodes());
  const SparseMatrix Kt = K.transpose();
  EXPECT_EQ((K - Kt).norm(), 0.0);  // symmetric to the last bit
  const Eigen::MatrixXd D(K);
  for (int k = 0; k < 6; ++k) {
    const Eigen::VectorXd r = rigid_mode3(m, k);
    EXPECT_LT((K * r).norm(), 1e-12 * D.norm() * r.norm()) << "mode " << k;
  }
  // Exactly six: the seventh eigenvalue is well away from zero.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(D, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd ev = eig.eigenvalues();
  EXPECT_LT(std::abs(ev(5)), 1e-10 * ev(ev.size() - 1));
  EXPECT_GT(ev(6), 1e-4 * ev(ev.size() - 1));
}

TEST(Elasticity3d, PlaneStrainKeepsThreeRigidModes) {
  const mesh::Mesh m = mesh::rectangle(0, 0, 1, 1, 3, 3);
  const Eigen::MatrixXd D(stiffness(m, {Material{15.0, 0.35}}));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(D, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd ev = eig.eigenvalues();
  EXPECT_LT(std::abs(ev(2)), 1e-10 * ev(ev.size() - 1));
  EXPECT_GT(ev(3), 1e-4 * ev(ev.size() - 1));
}

TEST(Elasticity3d, PatchTestReproducesLinearField) {
  const mesh::Mesh3 m = unstructured_box(4);
  ASSERT_NO_THROW(mesh::validate(m));
  const std::vector<Material> mat{Material{3.0, 0.28}};
  const SparseMatrix K = stiffness(m, mat);
  Eigen::Matrix3d A;
  A << 0.01, -0.02, 0.03, 0.015, 0.005, -0.01, 0.02, 0.01, -0.025;
  const Eigen::Vector3d b(0.1, -0.2, 0.3);
  Eigen::VectorXd exact(m.num_dofs());
  for (int v = 0; v < m.num_nodes(); ++v) exact.segment<3>(3 * v) = A * m.nodes[static_cast<std::size_t>(v)] + b;
  const DofMap dofs(m, clamp_all(m));
  EXPECT_EQ(dofs.num_free(), 3 * 3 * 3 * 3);  // the 27 interior nodes
  const Eigen::VectorXd u = solve_with(K, Eigen::VectorXd::Zero(m.num_dofs()), dofs, exact);
  EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 1e-14);
  // Constant stress: sigma = lambda tr(eps) I + 2 mu eps of eps = sym(A), in every tetrahedron.
  const auto stress = element_stress(m, mat, u);
  const Eigen::Matrix3d eps = 0.5 * (A + A.transpose());
  const Eigen::Matrix3d sigma =
      mat[0].lame_lambda() * eps.trace() * Eigen::Matrix3d::Identity() + 2.0 * mat[0].lame_mu() * eps;
  VoigtVector<3> voigt;
  voigt << sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2);
  for (int t = 0; t < m.num_cells(); ++t) ASSERT_LT((stress.col(t) - voigt).norm(), 1e-13) << t;
}

TEST(Elasticity3d, UniaxialBarUnderTractionAndPressure) {
  // Bar [0, 2] x [0, 1] x [0, 1] on rollers (ux = 0 on x = 0, uy = 0 on y = 0, uz = 0 on z = 0),
  // pulled by s on x = 2: u = (s x / E, -nu s y / E, -nu s z / E), exact in P1.
  mesh::Mesh3 m = mesh::box({0, 0, 0}, {2, 1, 1}, 6, 3, 3);
  mesh::perturb_interior(m, 0.1, 2);
  const Material mat{7.0, 0.3};
  const double s = 0.21;
  const SparseMatrix K = stiffness(m, {mat});
  const DofMap dofs(m, {{"left", 0.0, {}, {}}, {"front", {}, 0.0, {}}, {"bottom", {}, {}, 0.0}});
  EXPECT_EQ(dofs.dim(), 3);
  Eigen::VectorXd exact(m.num_dofs());
  for (int v = 0; v < m.num_nodes(); ++v) {
    const Eigen::Vector3d& x = m.nodes[static_cast<std::size_t>(v)];
    exact.segment<3>(3 * v) = Eigen::Vector3d(s * x.x(), -mat.nu * s * x.y(), -mat.nu * s * x.z()) / mat.E;
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.num_dofs());
  TractionLoad3 pull{"right", false, Eigen::Vector3d(s, 0, 0), 0.0};
  const Eigen::VectorXd u = solve_with(K, traction_load(m, pull), dofs, zero);
  EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 1e-13);
  // The same load as a negative pressure: t = -p n = s e_x on the face x = 2.
  TractionLoad3 suction{"right", true, Eigen::Vector3d::Zero(), -s};
  const Eigen::VectorXd u2 = solve_with(K, traction_load(m, suction), dofs, zero);
  EXPECT_LT((u2 - exact).lpNorm<Eigen::Infinity>(), 1e-13);
  const auto stress = element_stress(m, {mat}, u);
  for (int t = 0; t < m.num_cells(); ++t) {
    VoigtVector<3> expected = VoigtVector<3>::Zero();
    expected(0) = s;
    ASSERT_LT((stress.col(t) - expected).norm(), 1e-12) << t;
  }
}

TEST(Elasticity3d, TractionIntegratesPressureTimesArea) {
  // A box turned by a rotation R: the top face has area 2 x 1.5 = 3 and normal R e_z.
  mesh::Mesh3 m = mesh::box({0, 0, 0}, {2, 1.5, 1}, 5, 4, 3);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  mesh::map_body(m, mesh::kSlaveBody, R, Eigen::Vector3d(1, 2, 3));
  auto resultant = [&](const Eigen::VectorXd& f) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int v = 0; v < m.num_nodes(); ++v) r += f.segment<3>(3 * v);
    return r;
  };
  const double p = 2.5;
  const Eigen::Vector3d pressure = resultant(traction_load(m, TractionLoad3{"top", true, Eigen::Vector3d::Zero(), p}));
  EXPECT_LT((pressure - (-p * 3.0 * R * Eigen::Vector3d::UnitZ())).norm(), 1e-13);
  const Eigen::Vector3d t(0.3, -0.4, 1.2);
  EXPECT_LT((resultant(traction_load(m, TractionLoad3{"top", false, t, 0.0})) - 3.0 * t).norm(), 1e-13);
  // The moment of a uniform pressure about the face centroid vanishes (each facet load is
  // split equally among its nodes: exact for P1).
  const Eigen::Vector3d centroid = R * Eigen::Vector3d(1.0, 0.75, 1.0) + Eigen::Vector3d(1, 2, 3);
  const Eigen::VectorXd f = traction_load(m, TractionLoad3{"top", true, Eigen::Vector3d::Zero(), p});
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (int v = 0; v < m.num_nodes(); ++v) moment += (m.nodes[static_cast<std::size_t>(v)] - centroid).cross(f.segment<3>(3 * v));
  EXPECT_LT(moment.norm(), 1e-13);
  EXPECT_EQ(traction_body(m, "top"), mesh::kSlaveBody);
  EXPECT_THROW(traction_load(m, TractionLoad3{"no_such_group", true, Eigen::Vector3d::Zero(), p}), contactrb::Error);
}

TEST(Elasticity3d, ProductsAndBodyLoads) {
  const mesh::Mesh3 m = unstructured_box(3);
  const double volume = 1.0 * 0.8 * 0.6;
  Eigen::VectorXd ex = Eigen::VectorXd::Zero(m.num_dofs()), id(m.num_dofs());
  for (int v = 0; v < m.num_nodes(); ++v) {
    ex(3 * v) = 1.0;
    id.segment<3>(3 * v) = m.nodes[static_cast<std::size_t>(v)];
  }
  EXPECT_NEAR(ex.dot(mass(m) * ex), volume, 1e-14);
  // |grad x|^2 = 3: the Laplacian energy of the identity field is three times the volume.
  EXPECT_NEAR(id.dot(vector_laplacian(m) * id), 3.0 * volume, 1e-13);
  // int |x|^2 over the box, exact for the P1 mass of a linear field.
  const double second_moment = volume * (1.0 + 0.64 + 0.36) / 3.0;
  EXPECT_NEAR(id.dot(h1_product(m) * id), second_moment + 3.0 * volume, 1e-13);
  // The boundary mass of "top" (z = 0.6, area 0.8): int 1 = area, int x = area * 0.5.
  const SparseMatrix Mb = boundary_mass(m, "top");
  EXPECT_NEAR(ex.dot(Mb * ex), 0.8, 1e-14);
  EXPECT_NEAR(ex.dot(Mb * id), 0.8 * 0.5, 1e-14);
  // Body loads: a constant g gives g * volume, the field (0, 0, x y) gives int x y = V / 4 * 0.8.
  const Eigen::VectorXd f = body_load(m, 0, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_NEAR(f.sum(), -9.81 * volume, 1e-13);
  const Eigen::VectorXd g =
      body_load(m, 0, [](const Eigen::Vector3d& x) { return Eigen::Vector3d(0, 0, x.x() * x.y()); });
  EXPECT_NEAR(g.sum(), volume * 0.5 * 0.4, 1e-14);
  EXPECT_THROW(body_load(m, 1, Eigen::Vector3d(1, 0, 0)), contactrb::Error);
}

TEST(Elasticity3d, DirichletPerComponent) {
  const mesh::Mesh3 m = mesh::box({0, 0, 0}, {1, 1, 1}, 2, 2, 2);
  const DofMap dofs(m, {{"bottom", {}, {}, -0.1}, {"top", 0.0, 0.2, {}}});
  for (int node : mesh::boundary_nodes(m, "bottom")) EXPECT_EQ(dofs.lift()(3 * node + 2), -0.1);
  for (int node : mesh::boundary_nodes(m, "top")) EXPECT_EQ(dofs.lift()(3 * node + 1), 0.2);
  EXPECT_EQ(dofs.num_free(), m.num_dofs() - 9 - 18);
  try {
    DofMap(m, {{"bottom", {}, {}, 0.0}, {"left", {}, {}, 0.5}});
    ADD_FAILURE() << "a DOF prescribed twice with different values was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find(", z) prescribed twice"), std::string::npos) << e.what();
  }
  const mesh::Mesh m2 = mesh::rectangle(0, 0, 1, 1, 2, 2);
  EXPECT_THROW(DofMap(m2, {{"bottom", 0.0, 0.0, 0.0}}), contactrb::Error);  // uz on a 2D mesh
}

namespace {

// The largest |A - B| over the entries, relative to the largest |B|.
double relative_difference(const SparseMatrix& A, const SparseMatrix& B) {
  return Eigen::MatrixXd(A - B).cwiseAbs().maxCoeff() / Eigen::MatrixXd(B).cwiseAbs().maxCoeff();
}

// x -> s x on every body: the stiffness scales with s^(Dim - 2), the mass and body loads with
// s^Dim, the boundary mass and tractions with s^(Dim - 1) (grad ~ 1/s, measures ~ s^Dim).
template <int Dim>
void check_scaling(mesh::SimplexMesh<Dim> m, const std::string& group) {
  const double s = 1.7;
  const mesh::SimplexMesh<Dim> original = m;
  mesh::map_body(m, 0, s * Eigen::Matrix<double, Dim, Dim>::Identity(), Eigen::Matrix<double, Dim, 1>::Zero());
  const std::vector<Material> mat{Material{5.0, 0.3}};
  EXPECT_LT(relative_difference(stiffness(m, mat), std::pow(s, Dim - 2) * stiffness(original, mat)), 1e-14);
  EXPECT_LT(relative_difference(mass(m), std::pow(s, Dim) * mass(original)), 1e-14);
  EXPECT_LT(relative_difference(boundary_mass(m, group), std::pow(s, Dim - 1) * boundary_mass(original, group)),
            1e-14);
  const Eigen::Matrix<double, Dim, 1> g = Eigen::Matrix<double, Dim, 1>::Ones();
  EXPECT_LT((body_load(m, 0, g) - std::pow(s, Dim) * body_load(original, 0, g)).norm(),
            1e-14 * body_load(m, 0, g).norm());
  const SurfaceLoad<Dim> p{group, true, Eigen::Matrix<double, Dim, 1>::Zero(), 2.0};
  EXPECT_LT((traction_load(m, p) - std::pow(s, Dim - 1) * traction_load(original, p)).norm(),
            1e-14 * traction_load(m, p).norm());
}

}  // namespace

TEST(Elasticity3d, UniformScalingOfABody) {
  check_scaling(mesh::box({0, 0, 0}, {1, 0.5, 0.8}, 3, 2, 2), "top");
  check_scaling(mesh::rectangle(0, 0, 1, 0.5, 4, 3), "top");
}

TEST(Quadrature, TetrahedronRulesExactForMonomials) {
  // int_T l0^a l1^b l2^c l3^d / |T| = 3! a! b! c! d! / (3 + a + b + c + d)!.
  auto fact = [](int n) { return std::tgamma(n + 1.0); };
  for (int degree : {0, 1, 2, 3, 4, 5, 6, 7}) {
    const TetrahedronQuadrature& rule = tetrahedron_quadrature(degree);
    EXPECT_GE(rule.degree, degree);
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c) {
          const int d = degree - a - b - c;
          double sum = 0.0;
          for (std::size_t q = 0; q < rule.weights.size(); ++q) {
            const Eigen::Vector4d& l = rule.barycentric[q];
            sum += rule.weights[q] * std::pow(l(0), a) * std::pow(l(1), b) * std::pow(l(2), c) * std::pow(l(3), d);
          }
          const double exact = 6.0 * fact(a) * fact(b) * fact(c) * fact(d) / fact(3 + degree);
          EXPECT_NEAR(sum, exact, 1e-14) << degree << ": " << a << b << c << d;
        }
  }
  EXPECT_THROW(tetrahedron_quadrature(8), contactrb::Error);
  EXPECT_THROW(tetrahedron_quadrature(-1), contactrb::Error);
}
