// ComplementaryCorrection against a small contact problem solved exactly: a chain of springs
// (X = A, tridiagonal) pressed against rows K u <= g. A reduced answer in equilibrium with its own
// multipliers (residual 0) is corrected to the exact solution, so |v|_X is its exact error.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <vector>

#include "contactrb/online/complementary_correction.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"

using contactrb::online::ComplementaryCorrection;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowSparse = ComplementaryCorrection::RowSparse;

namespace {

struct Chain {
  MatrixXd A;     // n x n, SPD
  RowSparse K;    // m x n
  VectorXd f, g;  // load, gap
  VectorXd u, lambda;  // the exact solution
};

// n nodes on springs of stiffness 1 to their neighbours and 0.05 to the ground, pushed by f; row r
// bounds u(r + 2) - 0.5 u(r + 3) from above by a gap that opens away from the middle row.
Chain make_chain(int n, int m) {
  Chain c;
  c.A = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    c.A(i, i) = 0.05 + (i > 0 ? 1.0 : 0.0) + (i + 1 < n ? 1.0 : 0.0);
    if (i + 1 < n) c.A(i, i + 1) = c.A(i + 1, i) = -1.0;
  }
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < m; ++r) {
    t.emplace_back(r, r + 2, 1.0);
    t.emplace_back(r, r + 3, -0.5);
  }
  c.K.resize(m, n);
  c.K.setFromTriplets(t.begin(), t.end());
  c.f = VectorXd::Ones(n);
  c.g.resize(m);  // a Hertz-like gap, closed in the middle of the rows
  for (int r = 0; r < m; ++r) c.g(r) = 0.5 + 0.1 * (r - 0.5 * m) * (r - 0.5 * m);
  // The dual QP: min 1/2 l' (K A^-1 K') l - (K A^-1 f - g)' l over l >= 0.
  const Eigen::LLT<MatrixXd> llt(c.A);
  const MatrixXd Kd = MatrixXd(c.K);
  const MatrixXd S = Kd * llt.solve(Kd.transpose());
  const contactrb::solve::QPResult qp = contactrb::solve::solve_nonnegative_qp(S, Kd * llt.solve(c.f) - c.g);
  EXPECT_EQ(qp.status, contactrb::solve::QPStatus::Solved);
  c.lambda = qp.x;
  c.u = llt.solve(c.f - Kd.transpose() * c.lambda);
  return c;
}

// load_T with load_T' load_T = X^-1: the inverse of the Cholesky factor of X.
MatrixXd inverse_factor(const MatrixXd& X) {
  const Eigen::LLT<MatrixXd> llt(X);
  return llt.matrixL().solve(MatrixXd::Identity(X.rows(), X.cols()));
}

std::vector<int> all_dofs(int n) {
  std::vector<int> d(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) d[static_cast<std::size_t>(i)] = i;
  return d;
}

double energy_norm(const MatrixXd& A, const VectorXd& v) { return std::sqrt(v.dot(A * v)); }

}  // namespace

TEST(ComplementaryCorrection, ExactSolutionIsReferenceChainInContact) {
  const Chain c = make_chain(30, 20);
  const VectorXd slack = c.g - c.K * c.u;
  EXPECT_GE(slack.minCoeff(), -1e-12);
  EXPECT_GE(c.lambda.minCoeff(), 0.0);
  EXPECT_LE(std::abs(c.lambda.dot(slack)), 1e-12 * c.lambda.norm());
  int active = 0;
  for (int r = 0; r < c.lambda.size(); ++r) active += c.lambda(r) > 0.0;
  EXPECT_GE(active, 3);                       // some rows in contact
  EXPECT_LT(active, int(c.lambda.size()));  // and some open: the active set is not trivial
}

TEST(ComplementaryCorrection, EquilibratedAnswerIsCorrectedToTheExactSolution) {
  const Chain c = make_chain(30, 20);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> uni(0.0, 0.3);
  for (const double t : {1.0, 2.5}) {
    SCOPED_TRACE(t);
    // A(mu) = t X. A reduced answer: non-negative multipliers spread over the neighbours of the
    // contact rows, the displacement in equilibrium with them (residual 0), crossing some rows.
    const MatrixXd X = c.A / t;
    VectorXd lambda_rb = c.lambda;
    for (int r = 0; r < lambda_rb.size(); ++r) {
      if (c.lambda(r) > 0.0 || (r > 0 && c.lambda(r - 1) > 0.0)) lambda_rb(r) = std::max(0.0, c.lambda(r) + uni(gen) - 0.15);
    }
    const VectorXd u_rb = c.A.llt().solve(c.f - MatrixXd(c.K).transpose() * lambda_rb);
    const VectorXd slack = c.g - c.K * u_rb;
    ASSERT_LT(slack.minCoeff(), -1e-6);  // the reduced answer crosses some rows
    ComplementaryCorrection cc;
    cc.setup(inverse_factor(X), all_dofs(30), 30);
    const ComplementaryCorrection::Result res = cc.evaluate(c.K, slack, lambda_rb, t);
    ASSERT_TRUE(res.available);
    // The problem holds the rows with a multiplier or crossed, and those the correction closes:
    // not the open rows far from the contact.
    EXPECT_GT(res.rows, 0);
    EXPECT_LT(res.rows, 20);
    // |v / t|_A(mu) = |v|_X / sqrt(t) is the error of u_rb in the energy norm of A(mu).
    const double error = energy_norm(c.A, c.u - u_rb);
    EXPECT_NEAR(res.v_norm / std::sqrt(t), error, 1e-10 * error);
  }
}

TEST(ComplementaryCorrection, CorrectionIsWithinTheResidualOfTheError) {
  // With a residual r, u~ - u_hf is bounded by |r|_X^-1: |v|_X <= |e|_X + |r|_X^-1.
  const Chain c = make_chain(30, 20);
  std::mt19937 gen(11);
  std::normal_distribution<double> normal(0.0, 1e-2);
  ComplementaryCorrection cc;
  cc.setup(inverse_factor(c.A), all_dofs(30), 30);
  for (int trial = 0; trial < 5; ++trial) {
    VectorXd u_rb = c.u;
    for (int i = 0; i < u_rb.size(); ++i) u_rb(i) += normal(gen);
    const VectorXd lambda_rb = c.lambda;
    const VectorXd r = c.f - c.A * u_rb - MatrixXd(c.K).transpose() * lambda_rb;
    const double r_dual = std::sqrt(r.dot(c.A.llt().solve(r)));
    const ComplementaryCorrection::Result res = cc.evaluate(c.K, c.g - c.K * u_rb, lambda_rb, 1.0);
    ASSERT_TRUE(res.available);
    const double error = energy_norm(c.A, c.u - u_rb);
    EXPECT_LE(res.v_norm, error + r_dual + 1e-12);
    EXPECT_GE(res.v_norm + r_dual, error * (1.0 - 1e-12));  // the bound |e| <= |v| + |r|
  }
}

TEST(ComplementaryCorrection, RefusesWhatItCannotMeasure) {
  const Chain c = make_chain(30, 20);
  const VectorXd slack = c.g - c.K * c.u;
  std::vector<int> dofs = all_dofs(30);
  // DOFs 2-12 only: rows 0-9 measured. Row 12's multiplier lies outside: unavailable.
  std::vector<int> first(dofs.begin() + 2, dofs.begin() + 13);
  ComplementaryCorrection cc;
  const Eigen::LLT<MatrixXd> llt(c.A);
  MatrixXd sub(11, 11);
  for (int i = 0; i < 11; ++i) {
    for (int j = 0; j < 11; ++j) sub(i, j) = llt.solve(VectorXd::Unit(30, j + 2))(i + 2);
  }
  const Eigen::LLT<MatrixXd> sub_llt(sub);
  cc.setup(MatrixXd(sub_llt.matrixU()), first, 30);  // U' U = X^-1 on the measured DOFs
  VectorXd lambda = c.lambda;
  lambda(12) = 0.1;
  EXPECT_FALSE(cc.evaluate(c.K, slack, lambda, 1.0).available);
  // No multiplier outside, but an unmeasured row with a closed gap: unavailable.
  lambda.tail(10).setZero();
  VectorXd closed = slack;
  closed(15) = -1e-3;
  EXPECT_FALSE(cc.evaluate(c.K, closed, lambda, 1.0).available);
  // The same with the unmeasured rows wide open: the measured rows are corrected.
  VectorXd open = slack;
  open.tail(10).setConstant(1e3);
  const ComplementaryCorrection::Result res = cc.evaluate(c.K, open, lambda, 1.0);
  EXPECT_TRUE(res.available);
  EXPECT_LE(res.rows, 10);
}
