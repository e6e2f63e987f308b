#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "contactrb/common/error.hpp"
#include "contactrb/fem/cholesky.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "fem_fixtures.hpp"

using namespace contactrb;
using namespace contactrb::fem;

namespace {

const std::vector<Material> kMaterials = {Material{15.0, 0.35}, Material{1.0, 0.3}};

double max_abs(const SparseMatrix& A) {
  double m = 0.0;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

// Rigid-body mode k (0: x translation, 1: y translation, 2: rotation) of one body.
Eigen::VectorXd rigid_mode(const mesh::Mesh& m, int body, int k) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(m.num_dofs());
  for (int t = 0; t < m.num_triangles(); ++t) {
    if (m.body[static_cast<std::size_t>(t)] != body) continue;
    for (int v : m.triangles[static_cast<std::size_t>(t)]) {
      const Eigen::Vector2d& x = m.nodes[static_cast<std::size_t>(v)];
      r.segment<2>(2 * v) = k == 0 ? Eigen::Vector2d(1, 0) : k == 1 ? Eigen::Vector2d(0, 1) : Eigen::Vector2d(-x.y(), x.x());
    }
  }
  return r;
}

}  // namespace

TEST(Material, PlaneStrainConstants) {
  const Material m{15.0, 0.35};
  // lambda_L = E nu / ((1 + nu)(1 - 2 nu)), not the (1 + 2 nu) printed in the paper's (16).
  EXPECT_NEAR(m.lame_lambda(), 15.0 * 0.35 / (1.35 * 0.3), 1e-14);
  EXPECT_NEAR(m.lame_mu(), 15.0 / 2.7, 1e-14);
  EXPECT_NO_THROW(check_material(m));
  EXPECT_THROW(check_material(Material{0.0, 0.3}), Error);
  EXPECT_THROW(check_material(Material{1.0, 0.5}), Error);
  EXPECT_THROW(check_material(Material{1.0, -1.0}), Error);
  EXPECT_THROW(check_material(Material{std::nan(""), 0.3}), Error);
}

TEST(Stiffness, SymmetricAndExactLameSplit) {
  const mesh::Mesh m = fem_test::two_bodies(5, 4, 3, 6);
  const SparseMatrix K = stiffness(m, kMaterials);
  EXPECT_EQ(K.rows(), m.num_dofs());
  EXPECT_EQ(max_abs(SparseMatrix(K - SparseMatrix(K.transpose()))), 0.0);
  SparseMatrix sum(m.num_dofs(), m.num_dofs());
  for (int b = 0; b < 2; ++b) {
    const Material& mat = kMaterials[static_cast<std::size_t>(b)];
    const SparseMatrix Kb = stiffness_body(m, b, mat);
    const SparseMatrix split =
        mat.lame_lambda() * divergence_part(m, b) + 2.0 * mat.lame_mu() * symmetric_gradient_part(m, b);
    EXPECT_EQ(max_abs(SparseMatrix(Kb - split)), 0.0) << "body " << b;  // to the last bit
    sum += Kb;
  }
  EXPECT_EQ(max_abs(SparseMatrix(K - sum)), 0.0);
  EXPECT_THROW(stiffness_body(m, 2, kMaterials[0]), Error);
  EXPECT_THROW(stiffness(m, {kMaterials[0]}), Error);
}

TEST(Stiffness, ThreeRigidModesPerBodyThenPositiveDefinite) {
  const mesh::Mesh m = fem_test::two_bodies(4, 3, 3, 4);
  const SparseMatrix K = stiffness(m, kMaterials);
  const double scale = max_abs(K);
  for (int b = 0; b < 2; ++b) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::VectorXd r = rigid_mode(m, b, k);
      EXPECT_LT((K * r).norm(), 1e-12 * scale * r.norm()) << "body " << b << " mode " << k;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(K), Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& ev = eig.eigenvalues();
  const double largest = ev.maxCoeff();
  int small = 0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) small += ev(i) < 1e-10 * largest;
  EXPECT_EQ(small, 3 * m.num_bodies());
  EXPECT_GT(ev(6), 1e-6 * largest);  // a clear gap after the 6 rigid modes

  const DofMap dofs(m, {{"left", 0.0, 0.0}, {"b_bottom", 0.0, 0.0}});
  const SparseMatrix K00 = dofs.restrict_matrix(K);
  SparseCholesky chol;
  EXPECT_EQ(chol.compute(K00), FactorStatus::Success);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig0(Eigen::MatrixXd(K00), Eigen::EigenvaluesOnly);
  EXPECT_GT(eig0.eigenvalues().minCoeff(), 0.0);
  // A clamp of one component on one point per body does not remove the rotations.
  const DofMap loose(m, {{"left", 0.0, std::nullopt}, {"b_bottom", std::nullopt, 0.0}});
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig1(Eigen::MatrixXd(loose.restrict_matrix(K)),
                                                            Eigen::EigenvaluesOnly);
  int small1 = 0;
  for (Eigen::Index i = 0; i < eig1.eigenvalues().size(); ++i) small1 += eig1.eigenvalues()(i) < 1e-10 * largest;
  EXPECT_EQ(small1, 2);  // body 0 slides in y, body 1 slides in x
}

TEST(Stiffness, PatchTestAffineFieldReproduced) {
  const mesh::Mesh m = fem_test::two_bodies(7, 6, 5, 8, 0.35);
  const SparseMatrix K = stiffness(m, kMaterials);
  std::vector<DirichletCondition> all;
  for (const auto& [name, edges] : m.boundaries) all.push_back({name, 0.0, 0.0});
  const DofMap dofs(m, all);
  ASSERT_GT(dofs.num_free(), 0);
  Eigen::Matrix2d B;
  B << 0.02, -0.05, 0.03, -0.01;
  const Eigen::Vector2d a(0.1, -0.2);
  Eigen::VectorXd exact(m.num_dofs());
  for (int i = 0; i < m.num_nodes(); ++i) exact.segment<2>(2 * i) = a + B * m.nodes[static_cast<std::size_t>(i)];
  // Lifting by the affine field's values on the constrained DOFs (not constant per group).
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(m.num_dofs());
  for (int d : dofs.constrained_dofs()) lift(d) = exact(d);
  SparseCholesky chol;
  ASSERT_EQ(chol.compute(dofs.restrict_matrix(K)), FactorStatus::Success);
  const Eigen::VectorXd u0 = chol.solve(Eigen::VectorXd(dofs.restrict(-(K * lift))));
  const Eigen::VectorXd u = lift + dofs.extend(u0);
  EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 1e-13);

  const Eigen::Matrix3Xd stress = element_stress(m, kMaterials, u);
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Material& mat = kMaterials[static_cast<std::size_t>(m.body[static_cast<std::size_t>(t)])];
    const Eigen::Matrix2d eps = 0.5 * (B + B.transpose());
    const Eigen::Matrix2d sigma =
        mat.lame_lambda() * eps.trace() * Eigen::Matrix2d::Identity() + 2.0 * mat.lame_mu() * eps;
    const Eigen::Vector3d expected(sigma(0, 0), sigma(1, 1), sigma(0, 1));
    ASSERT_LT((stress.col(t) - expected).norm(), 1e-12 * mat.E) << "triangle " << t;
  }
}

TEST(Loads, ConstantAndVariableBodyForce) {
  const mesh::Mesh m = fem_test::two_bodies(4, 5, 3, 3);
  const Eigen::Vector2d g(0.5, -2.0);
  const Eigen::VectorXd f0 = body_load(m, 0, g);
  const Eigen::VectorXd f0q = body_load(m, 0, [&](const Eigen::Vector2d&) { return g; });
  EXPECT_LT((f0 - f0q).norm(), 1e-14);
  // int g . (translation) = area * g; body 0 has area 1, body 1 has area 1.2.
  EXPECT_NEAR(rigid_mode(m, 0, 1).dot(f0), -2.0, 1e-13);
  EXPECT_NEAR(rigid_mode(m, 1, 0).dot(f0), 0.0, 0.0);
  EXPECT_NEAR(rigid_mode(m, 1, 0).dot(body_load(m, 1, g)), 0.6, 1e-13);
  // A linear load: int x dx over [0,1]^2 = 1/2, and the load vector is M times the interpolant.
  auto linear = [](const Eigen::Vector2d& x) { return Eigen::Vector2d(x.x(), 2.0 * x.y() - x.x()); };
  const Eigen::VectorXd fl = body_load(m, 0, linear);
  EXPECT_NEAR(rigid_mode(m, 0, 0).dot(fl), 0.5, 1e-13);
  Eigen::VectorXd interp = Eigen::VectorXd::Zero(m.num_dofs());
  for (int t = 0; t < m.num_triangles(); ++t) {
    if (m.body[static_cast<std::size_t>(t)] != 0) continue;
    for (int v : m.triangles[static_cast<std::size_t>(t)]) interp.segment<2>(2 * v) = linear(m.nodes[static_cast<std::size_t>(v)]);
  }
  const SparseMatrix M = mass(m);
  EXPECT_LT((M * interp - fl).norm(), 1e-14);
  EXPECT_THROW(body_load(m, 3, g), Error);
}

TEST(InnerProducts, MassLaplacianH1AndBoundaryMass) {
  const mesh::Mesh m = fem_test::two_bodies(4, 3, 5, 2);
  const SparseMatrix M = mass(m), L = vector_laplacian(m), H = h1_product(m);
  EXPECT_LT(max_abs(SparseMatrix(H - M - L)), 1e-15);
  const Eigen::VectorXd tx = rigid_mode(m, 0, 0) + rigid_mode(m, 1, 0);
  EXPECT_NEAR(tx.dot(M * tx), 1.0 + 1.2, 1e-13);  // total area
  EXPECT_LT((L * tx).norm(), 1e-13);
  // |grad (x, y)|^2 = 2: the Laplacian energy of the identity field is twice the area.
  Eigen::VectorXd id(m.num_dofs());
  for (int i = 0; i < m.num_nodes(); ++i) id.segment<2>(2 * i) = m.nodes[static_cast<std::size_t>(i)];
  EXPECT_NEAR(id.dot(L * id), 2.0 * 2.2, 1e-12);
  const SparseMatrix G = boundary_mass(m, "b_top");  // top of body 1: length 1, y = 1.2
  EXPECT_NEAR(tx.dot(G * tx), 1.0, 1e-14);
  EXPECT_NEAR(id.dot(G * id), (2.5 * 2.5 * 2.5 - 1.5 * 1.5 * 1.5) / 3.0 + 1.44, 1e-13);  // int x^2 + y^2
  EXPECT_THROW(boundary_mass(m, "nowhere"), Error);
}

// The stiffness on a pattern built beforehand (shared with hf::HFSolver's analysis thread) is the
// stiffness, bitwise; NodalSparsity::restricted_pattern is the pattern DofMap::restrict_matrix
// stores (one DOF of a node prescribed, both, none).
TEST(Stiffness, SharedPatternAndRestrictedPatternAreTheAssembledOnes) {
  const mesh::Mesh m = fem_test::two_bodies(5, 4, 3, 6);
  const NodalSparsity pattern(m, triangles_of_body(m, -1));
  const SparseMatrix K = stiffness(m, kMaterials), Kp = stiffness(m, kMaterials, pattern);
  ASSERT_EQ(K.nonZeros(), Kp.nonZeros());
  EXPECT_TRUE(std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.cols() + 1, Kp.outerIndexPtr()));
  EXPECT_TRUE(std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), Kp.innerIndexPtr()));
  EXPECT_TRUE(std::equal(K.valuePtr(), K.valuePtr() + K.nonZeros(), Kp.valuePtr()));
  const DofMap dofs(m, {{"left", 0.0, std::nullopt}, {"b_bottom", 0.0, 0.0}});
  const SparseMatrix K00 = dofs.restrict_matrix(K);
  std::vector<int> outer, inner;
  pattern.restricted_pattern(dofs.free_dofs(), outer, inner);
  ASSERT_EQ(outer.size(), static_cast<std::size_t>(K00.cols()) + 1);
  ASSERT_EQ(inner.size(), static_cast<std::size_t>(K00.nonZeros()));
  EXPECT_TRUE(std::equal(outer.begin(), outer.end(), K00.outerIndexPtr()));
  EXPECT_TRUE(std::equal(inner.begin(), inner.end(), K00.innerIndexPtr()));
  EXPECT_THROW(pattern.restricted_pattern({0, 0}, outer, inner), Error);
  const mesh::Mesh other = fem_test::two_bodies(4, 4, 3, 6);
  EXPECT_THROW(stiffness(other, kMaterials, pattern), Error);
}
