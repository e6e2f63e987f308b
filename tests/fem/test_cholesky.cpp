#include <gtest/gtest.h>

#include "contactrb/common/error.hpp"
#include "contactrb/fem/cholesky.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "fem_fixtures.hpp"

using namespace contactrb;
using namespace contactrb::fem;

class Cholesky : public ::testing::TestWithParam<CholeskyBackend> {};

TEST_P(Cholesky, SolvesElasticityToRoundOff) {
  const mesh::Mesh m = fem_test::two_bodies(12, 10, 9, 11);
  const SparseMatrix K = stiffness(m, {Material{15.0, 0.35}, Material{1.0, 0.3}});
  const DofMap dofs(m, {{"top", 0.0, -0.1}, {"b_bottom", 0.0, 0.0}});
  const SparseMatrix A = dofs.restrict_matrix(K);
  SparseCholesky chol(GetParam());
  EXPECT_EQ(chol.backend(), GetParam());
  ASSERT_EQ(chol.compute(A), FactorStatus::Success);
  EXPECT_EQ(chol.status(), FactorStatus::Success);
  EXPECT_EQ(chol.rows(), A.rows());
  const Eigen::VectorXd x = Eigen::VectorXd::Random(A.rows());
  const Eigen::VectorXd b = A * x;
  EXPECT_LT((chol.solve(b) - x).norm(), 1e-10 * x.norm());
  EXPECT_LT((A * chol.solve(b) - b).norm(), 1e-13 * b.norm());
  const Eigen::MatrixXd X = Eigen::MatrixXd::Random(A.rows(), 3);
  const Eigen::MatrixXd B = A * X;
  EXPECT_LT((A * chol.solve(B) - B).norm(), 1e-13 * B.norm());
  // Reusable: a second compute on another matrix.
  const SparseMatrix A2 = 2.0 * A;
  ASSERT_EQ(chol.compute(A2), FactorStatus::Success);
  EXPECT_LT((chol.solve(b) - 0.5 * x).norm(), 1e-10 * x.norm());
  // Moves keep the factorization.
  SparseCholesky moved = std::move(chol);
  EXPECT_LT((moved.solve(b) - 0.5 * x).norm(), 1e-10 * x.norm());
}

TEST_P(Cholesky, FailureStatuses) {
  SparseCholesky chol(GetParam());
  EXPECT_THROW(chol.solve(Eigen::VectorXd(3)), Error);  // before compute
  SparseMatrix indefinite(3, 3);
  indefinite.insert(0, 0) = 2.0;
  indefinite.insert(1, 1) = -1.0;
  indefinite.insert(2, 2) = 3.0;
  indefinite.insert(0, 1) = 0.5;
  indefinite.insert(1, 0) = 0.5;
  indefinite.makeCompressed();
  EXPECT_EQ(chol.compute(indefinite), FactorStatus::NotPositiveDefinite);
  EXPECT_THROW(chol.solve(Eigen::VectorXd::Ones(3)), Error);
  // Singular: the elasticity matrix before Dirichlet conditions has rigid modes; a zero
  // pivot on the diagonal of a PSD matrix is reported too.
  SparseMatrix singular(2, 2);
  singular.insert(0, 0) = 1.0;
  singular.makeCompressed();
  EXPECT_EQ(chol.compute(singular), FactorStatus::NotPositiveDefinite);
  SparseMatrix nonsymmetric(2, 2);
  nonsymmetric.insert(0, 0) = 1.0;
  nonsymmetric.insert(1, 1) = 1.0;
  nonsymmetric.insert(1, 0) = 0.3;
  nonsymmetric.makeCompressed();
  EXPECT_EQ(chol.compute(nonsymmetric), FactorStatus::InvalidInput);
  EXPECT_EQ(chol.compute(SparseMatrix(2, 3)), FactorStatus::InvalidInput);
  SparseMatrix nan_matrix(1, 1);
  nan_matrix.insert(0, 0) = std::nan("");
  EXPECT_EQ(chol.compute(nan_matrix), FactorStatus::InvalidInput);
  // Recovers after failures; wrong right-hand side size is a usage error.
  SparseMatrix I(2, 2);
  I.setIdentity();
  ASSERT_EQ(chol.compute(I), FactorStatus::Success);
  EXPECT_THROW(chol.solve(Eigen::VectorXd(3)), Error);
  EXPECT_EQ(chol.compute(SparseMatrix(0, 0)), FactorStatus::Success);
  EXPECT_EQ(chol.solve(Eigen::VectorXd(0)).size(), 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, Cholesky,
                         ::testing::Values(CholeskyBackend::Cholmod, CholeskyBackend::EigenSimplicial),
                         [](const auto& info) { return std::string(to_string(info.param)) == "cholmod" ? "Cholmod" : "EigenSimplicial"; });

TEST(CholeskyStatus, Names) {
  EXPECT_STREQ(to_string(FactorStatus::Success), "success");
  EXPECT_STREQ(to_string(FactorStatus::NotPositiveDefinite), "not positive definite");
  EXPECT_STREQ(to_string(FactorStatus::InvalidInput), "invalid input");
}

// The default (Automatic) backend switches to CHOLMOD from kCholmodMinRows rows: both
// sides of the switch solve an elasticity system to round-off.
TEST(SparseCholeskyAutomatic, SolvesOnBothSidesOfTheSwitch) {
  for (int n : {20, 110}) {  // about 9e2 and 2.5e4 free DOFs
    contactrb::mesh::Mesh m = contactrb::mesh::rectangle(0.0, 0.0, 1.0, 1.0, n, n);
    const contactrb::fem::DofMap dofs(m, {{"bottom", 0.0, 0.0}});
    const Eigen::SparseMatrix<double> A = dofs.restrict_matrix(contactrb::fem::stiffness(m, {{1.0, 0.3}}));
    contactrb::fem::SparseCholesky chol;
    ASSERT_EQ(chol.compute(A), contactrb::fem::FactorStatus::Success);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
    EXPECT_LT((A * chol.solve(b) - b).norm(), 1e-10 * b.norm()) << A.rows();
  }
}
