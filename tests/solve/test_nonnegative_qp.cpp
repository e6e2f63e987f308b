#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"
#include "qp_reference.hpp"

using namespace contactrb::solve;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Solves, then asserts Solved, tiny KKT residuals, a consistent passive set and the
// brute-force optimal objective.
void expect_matches_brute_force(const MatrixXd& Q, const VectorXd& c, const std::string& what) {
  SCOPED_TRACE(what);
  const QPResult r = solve_nonnegative_qp(Q, c);
  ASSERT_EQ(r.status, QPStatus::Solved) << r.message;
  EXPECT_TRUE(r.message.empty());
  EXPECT_TRUE(qpref::kkt_ok(Q, c, r.x));
  EXPECT_GE(r.x.minCoeff(), 0.0);
  for (int i = 0; i < r.x.size(); ++i)
    EXPECT_EQ(std::count(r.passive.begin(), r.passive.end(), i) == 1, r.x[i] > 0.0);
  EXPECT_TRUE(std::is_sorted(r.passive.begin(), r.passive.end()));
  const qpref::Reference ref = qpref::brute_force(Q, c);
  const double f = qpref::objective(Q, c, r.x);
  const double scale = std::max(qpref::objective_scale(Q, c, ref.x), qpref::objective_scale(Q, c, r.x));
  EXPECT_NEAR(f, ref.f, 1e-10 * scale) << "n = " << Q.rows();
}

}  // namespace

TEST(NonnegativeQPBruteForce, PositiveDefinite) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 1 + trial % 10;
    const MatrixXd B = qpref::randn(rng, n + 2, n);
    const MatrixXd Q = qpref::gram(B);
    const VectorXd c = qpref::randn(rng, n, 1);
    expect_matches_brute_force(Q, c, "PD trial " + std::to_string(trial));
  }
}

TEST(NonnegativeQPBruteForce, RankDeficient) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 2 + trial % 9;
    const int rank = 1 + trial % (n - 1);
    const MatrixXd B = qpref::randn(rng, rank, n);  // Q = B'B has rank < n
    const MatrixXd Q = qpref::gram(B);
    // c = B'b - u, u >= 0: bounded (c'd = -u'd <= 0 for every d >= 0 with Q d = 0).
    VectorXd u = VectorXd::Zero(n);
    for (int i = 0; i < n; ++i)
      if (U(rng) < 0.4) u[i] = U(rng);
    const VectorXd c = B.transpose() * qpref::randn(rng, rank, 1) - u;
    expect_matches_brute_force(Q, c, "rank-deficient trial " + std::to_string(trial));
  }
}

TEST(NonnegativeQPBruteForce, DuplicatedColumns) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 2 + trial % 9;
    const int m = 1 + trial % 6;
    MatrixXd Xi = qpref::randn(rng, m, n);
    for (int j = 1; j < n; j += 2) Xi.col(j) = Xi.col(j - 1);  // duplicated columns
    if (trial % 3 == 0) Xi.col(n - 1) = 2.0 * Xi.col(0);       // a parallel one
    const VectorXd x = qpref::randn(rng, m, 1);
    const MatrixXd Q = qpref::gram(Xi);
    const VectorXd c = Xi.transpose() * x;
    expect_matches_brute_force(Q, c, "duplicated columns trial " + std::to_string(trial));
  }
}

TEST(NonnegativeQPBruteForce, ZeroMatrixNonpositiveC) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int n = 1; n <= 10; ++n) {
    VectorXd c(n);
    for (int i = 0; i < n; ++i) c[i] = U(rng) < 0.3 ? 0.0 : -U(rng);
    const MatrixXd Q = MatrixXd::Zero(n, n);
    expect_matches_brute_force(Q, c, "Q = 0, n = " + std::to_string(n));
    const QPResult r = solve_nonnegative_qp(Q, c);
    EXPECT_TRUE(r.x.isZero(0.0));
    EXPECT_TRUE(r.passive.empty());
  }
}

TEST(NonnegativeQPBruteForce, ZeroRowsAndColumns) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 2 + trial % 9;
    MatrixXd Q = qpref::gram(qpref::randn(rng, n, n));
    VectorXd c = qpref::randn(rng, n, 1);
    for (int i = trial % 2; i < n; i += 3) {
      Q.row(i).setZero();
      Q.col(i).setZero();
      c[i] = -std::abs(c[i]) * (trial % 4 == 0 ? 0.0 : 1.0);  // bounded: c_i <= 0 on zero columns
    }
    expect_matches_brute_force(Q, c, "zero rows trial " + std::to_string(trial));
  }
}

TEST(NonnegativeQPBruteForce, Degenerate) {
  std::mt19937 rng(6);
  std::uniform_int_distribution<int> pick(0, 2);
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 1 + trial % 10;
    const int rows = trial % 2 ? n + 1 : std::max(1, n / 2);
    const MatrixXd B = qpref::randn(rng, rows, n);
    const MatrixXd Q = qpref::gram(B);
    // Optimum x* with zeros, gradient r >= 0 with r_i = 0 at some zero x*_i (weakly active),
    // so that c = Q x* - r: degenerate by construction.
    VectorXd xs(n), r(n);
    for (int i = 0; i < n; ++i) {
      const int kind = pick(rng);
      xs[i] = kind == 0 ? 1.0 : 0.0;  // ties: equal positive values
      r[i] = kind == 2 ? 1.0 : 0.0;   // zero gradients on some inactive entries
    }
    const VectorXd c = Q * xs - r;
    expect_matches_brute_force(Q, c, "degenerate trial " + std::to_string(trial));
    // c with zero entries and ties.
    VectorXd c2 = VectorXd::Zero(n);
    for (int i = 0; i < n; i += 2) c2[i] = (i % 4 == 0) ? 1.0 : -1.0;
    if (rows < n) c2 = Q * c2.cwiseMax(0.0);  // keep the rank-deficient problem bounded
    expect_matches_brute_force(Q, c2, "zeros and ties trial " + std::to_string(trial));
  }
  // Identity with equal c: every entry ties.
  for (int n = 1; n <= 8; ++n)
    expect_matches_brute_force(MatrixXd::Identity(n, n), VectorXd::Ones(n), "identity ties");
}

TEST(NonnegativeQPKnown, DiagonalClosedForm) {
  VectorXd d(5), c(5);
  d << 1.0, 2.0, 4.0, 0.5, 3.0;
  c << 1.0, -2.0, 8.0, 0.0, -1e-3;
  const QPResult r = solve_nonnegative_qp(d.asDiagonal().toDenseMatrix(), c);
  ASSERT_EQ(r.status, QPStatus::Solved) << r.message;
  VectorXd expected(5);
  expected << 1.0, 0.0, 2.0, 0.0, 0.0;
  EXPECT_TRUE(r.x.isApprox(expected, 1e-15));
  EXPECT_EQ(r.passive, (std::vector<int>{0, 2}));
}

TEST(NonnegativeQPKnown, TwoByTwo) {
  MatrixXd Q(2, 2);
  Q << 2.0, 1.0, 1.0, 2.0;
  VectorXd c(2);
  c << 1.0, -1.0;  // unconstrained minimizer (1, -1); constrained (1/2, 0), gradient (0, 3/2)
  const QPResult r = solve_nonnegative_qp(Q, c);
  ASSERT_EQ(r.status, QPStatus::Solved);
  EXPECT_NEAR(r.x[0], 0.5, 1e-15);
  EXPECT_EQ(r.x[1], 0.0);
  EXPECT_LE(r.kkt.max(), 1e-15);
}

TEST(NonnegativeQPKnown, RankOneAllOnes) {
  // min 1/2 (sum x)^2 - sum x: every x >= 0 with sum x = 1 is optimal, f = -1/2.
  for (int n = 1; n <= 30; ++n) {
    const QPResult r = solve_nonnegative_qp(MatrixXd::Ones(n, n), VectorXd::Ones(n));
    ASSERT_EQ(r.status, QPStatus::Solved) << r.message;
    EXPECT_NEAR(r.x.sum(), 1.0, 1e-14);
    EXPECT_EQ(r.passive.size(), 1u);  // the active-set method keeps Q_PP nonsingular
  }
}

TEST(NonnegativeQPKnown, ZeroIsOptimal) {
  std::mt19937 rng(7);
  for (int n : {1, 3, 10, 40}) {
    const MatrixXd Q = qpref::gram(qpref::randn(rng, n, n));
    const VectorXd c = -qpref::randn(rng, n, 1).cwiseAbs();
    const QPResult r = solve_nonnegative_qp(Q, c);
    ASSERT_EQ(r.status, QPStatus::Solved);
    EXPECT_TRUE(r.x.isZero(0.0));
    EXPECT_TRUE(r.passive.empty());
    EXPECT_EQ(r.iterations, 0);
  }
}

TEST(NonnegativeQPKnown, AllPositive) {
  std::mt19937 rng(8);
  for (int n : {1, 2, 5, 20, 60}) {
    const MatrixXd Q = qpref::gram(qpref::randn(rng, n + 5, n));
    const VectorXd xs = VectorXd::Constant(n, 1.0) + qpref::randn(rng, n, 1).cwiseAbs();
    const VectorXd c = Q * xs;
    const QPResult r = solve_nonnegative_qp(Q, c);
    ASSERT_EQ(r.status, QPStatus::Solved) << r.message;
    EXPECT_LE((r.x - xs).cwiseAbs().maxCoeff(), 1e-8 * xs.cwiseAbs().maxCoeff());
    EXPECT_EQ(static_cast<int>(r.passive.size()), n);
  }
}

TEST(NonnegativeQPKnown, EmptyProblem) {
  const QPResult r = solve_nonnegative_qp(MatrixXd(0, 0), VectorXd(0));
  EXPECT_EQ(r.status, QPStatus::Solved);
  EXPECT_EQ(r.x.size(), 0);
}

TEST(NonnegativeQPKnown, LargerRandomKKT) {
  std::mt19937 rng(9);
  for (int n : {100, 300}) {
    const MatrixXd Q = qpref::gram(qpref::randn(rng, n + 10, n));
    const VectorXd c = qpref::randn(rng, n, 1);
    const QPResult r = solve_nonnegative_qp(Q, c);
    ASSERT_EQ(r.status, QPStatus::Solved) << r.message;
    EXPECT_TRUE(qpref::kkt_ok(Q, c, r.x, 1e-12));
  }
}

TEST(NonnegativeQPStatus, Unbounded) {
  {
    VectorXd c(3);
    c << -1.0, 2.0, 0.0;
    const QPResult r = solve_nonnegative_qp(MatrixXd::Zero(3, 3), c);
    EXPECT_EQ(r.status, QPStatus::Unbounded);
    EXPECT_FALSE(r.message.empty());
    ASSERT_EQ(r.ray.size(), 3);
    EXPECT_EQ(r.ray, VectorXd::Unit(3, 1));
  }
  {
    // Q = [1 -1; -1 1] has null vector (1, 1) >= 0 and c'(1, 1) = 2 > 0.
    MatrixXd Q(2, 2);
    Q << 1.0, -1.0, -1.0, 1.0;
    VectorXd c(2);
    c << 1.0, 1.0;
    const QPResult r = solve_nonnegative_qp(Q, c);
    EXPECT_EQ(r.status, QPStatus::Unbounded);
    ASSERT_EQ(r.ray.size(), 2);
    EXPECT_NEAR(r.ray[0], 1.0, 1e-14);
    EXPECT_NEAR(r.ray[1], 1.0, 1e-14);
    EXPECT_GE(r.x.minCoeff(), 0.0);  // still a feasible point
    // Same Q, c in the range of Q: bounded, optimum x0 - x1 = 1 with f = -1/2.
    c << 1.0, -1.0;
    const QPResult b = solve_nonnegative_qp(Q, c);
    ASSERT_EQ(b.status, QPStatus::Solved) << b.message;
    EXPECT_NEAR(qpref::objective(Q, c, b.x), -0.5, 1e-14);
  }
}

TEST(NonnegativeQPStatus, MaxIterations) {
  const int n = 20;
  const MatrixXd Q = MatrixXd::Identity(n, n) + MatrixXd::Constant(n, n, 0.1);
  const VectorXd c = Q * VectorXd::LinSpaced(n, 1.0, 2.0);  // all variables positive
  QPSettings s;
  s.max_iterations = 3;
  const QPResult r = solve_nonnegative_qp(Q, c, s);
  EXPECT_EQ(r.status, QPStatus::MaxIterations);
  EXPECT_EQ(r.iterations, 3);
  EXPECT_NE(r.message.find("max_iterations = 3"), std::string::npos) << r.message;
  EXPECT_GE(r.x.minCoeff(), 0.0);
  s.max_iterations = -1;
  EXPECT_EQ(solve_nonnegative_qp(Q, c, s).status, QPStatus::Solved);
}

TEST(NonnegativeQPStatus, ToString) {
  EXPECT_STREQ(to_string(QPStatus::Solved), "solved");
  EXPECT_STREQ(to_string(QPStatus::MaxIterations), "max-iterations");
  EXPECT_STREQ(to_string(QPStatus::Numerics), "numerics");
  EXPECT_STREQ(to_string(QPStatus::Unbounded), "unbounded");
  EXPECT_STREQ(to_string(QPStatus::InvalidInput), "invalid-input");
}

namespace {
void expect_error(const std::function<void()>& f, const std::vector<std::string>& needles) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const contactrb::Error& e) {
    const std::string what = e.what();
    for (const auto& s : needles) EXPECT_NE(what.find(s), std::string::npos) << what << " lacks " << s;
  }
}
}  // namespace

TEST(NonnegativeQPStatus, InvalidInputThrows) {
  const MatrixXd Q = MatrixXd::Identity(3, 3);
  const VectorXd c = VectorXd::Ones(3);
  expect_error([&] { solve_nonnegative_qp(MatrixXd::Zero(3, 4), c); }, {"Q", "3 x 4"});
  expect_error([&] { solve_nonnegative_qp(Q, VectorXd::Ones(2)); }, {"c", "size 2", "3 x 3"});
  MatrixXd Qn = Q;
  Qn(1, 2) = std::nan("");
  expect_error([&] { solve_nonnegative_qp(Qn, c); }, {"Q(1, 2)", "not finite"});
  VectorXd ci = c;
  ci[2] = std::numeric_limits<double>::infinity();
  expect_error([&] { solve_nonnegative_qp(Q, ci); }, {"c(2)", "not finite"});
  MatrixXd Qs = Q;
  Qs(0, 2) = 1e-3;
  expect_error([&] { solve_nonnegative_qp(Qs, c); }, {"not symmetric", "3 x 3"});
  Qs(2, 0) = 1e-3 * (1 + 1e-14);  // symmetric up to rounding: accepted
  EXPECT_NO_THROW(solve_nonnegative_qp(Qs, c));
  MatrixXd Qd = Q;
  Qd(1, 1) = -1.0;
  expect_error([&] { solve_nonnegative_qp(Qd, c); }, {"Q(1, 1)", "positive semidefinite"});
  expect_error([&] { solve_nonnegative_qp(Q, c, {}, {0, 3}); }, {"warm_passive[1] = 3", "[0, 3)"});
  QPSettings bad;
  bad.tolerance = 0.0;
  expect_error([&] { solve_nonnegative_qp(Q, c, bad); }, {"tolerance"});
  bad = QPSettings{};
  bad.max_iterations = -2;
  expect_error([&] { solve_nonnegative_qp(Q, c, bad); }, {"max_iterations"});
  expect_error([&] { kkt_residuals(Q, c, VectorXd::Ones(2)); }, {"x has size 2"});
}

TEST(NonnegativeQPStatus, NotPsdIsNumericsOrSolvedNeverHangs) {
  // Indefinite but with a nonnegative diagonal: the solver must stop with a status.
  MatrixXd Q(2, 2);
  Q << 1.0, 2.0, 2.0, 1.0;
  VectorXd c(2);
  c << 1.0, 1.0;
  const QPResult r = solve_nonnegative_qp(Q, c);
  EXPECT_NE(r.status, QPStatus::MaxIterations);
  EXPECT_GE(r.x.minCoeff(), 0.0);
}

TEST(NonnegativeQPKKT, Residuals) {
  MatrixXd Q(2, 2);
  Q << 2.0, 0.0, 0.0, 1.0;
  VectorXd c(2), x(2);
  c << 2.0, 1.0;
  x << 2.0, -0.5;  // r = Qx - c = (2, -1.5)
  const KKTResiduals k = kkt_residuals(Q, c, x);
  EXPECT_DOUBLE_EQ(k.primal, 0.5);
  EXPECT_DOUBLE_EQ(k.dual, 1.5);
  EXPECT_DOUBLE_EQ(k.complementarity, 4.0);
  EXPECT_DOUBLE_EQ(k.max(), 4.0);
}

TEST(NonnegativeQPWarmStart, SameSolutionFromAnySet) {
  std::mt19937 rng(10);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 3 + trial % 25;
    const bool deficient = trial % 3 == 2;
    const MatrixXd B = qpref::randn(rng, deficient ? n / 2 + 1 : n + 3, n);
    const MatrixXd Q = qpref::gram(B);
    const VectorXd c = deficient ? VectorXd(B.transpose() * qpref::randn(rng, B.rows(), 1))
                                 : VectorXd(qpref::randn(rng, n, 1));
    const QPResult cold = solve_nonnegative_qp(Q, c);
    ASSERT_EQ(cold.status, QPStatus::Solved) << cold.message;
    const double f = qpref::objective(Q, c, cold.x);
    const double scale = qpref::objective_scale(Q, c, cold.x);

    std::vector<int> all(static_cast<std::size_t>(n)), wrong, complement;
    for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
    for (int i = 0; i < n; ++i) {
      const bool in = std::binary_search(cold.passive.begin(), cold.passive.end(), i);
      if (!in) complement.push_back(i);
      if (in != (i % 4 == 0)) wrong.push_back(i);  // flips every fourth membership
    }
    std::vector<int> with_duplicates = cold.passive;
    with_duplicates.insert(with_duplicates.end(), cold.passive.begin(), cold.passive.end());
    for (const auto& [name, warm] :
         std::vector<std::pair<std::string, std::vector<int>>>{{"optimal", cold.passive},
                                                               {"wrong", wrong},
                                                               {"all (infeasible)", all},
                                                               {"complement", complement},
                                                               {"duplicates", with_duplicates}}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " warm set " + name);
      const QPResult w = solve_nonnegative_qp(Q, c, {}, warm);
      ASSERT_EQ(w.status, QPStatus::Solved) << w.message;
      EXPECT_TRUE(qpref::kkt_ok(Q, c, w.x));
      EXPECT_NEAR(qpref::objective(Q, c, w.x), f, 1e-10 * scale);
      if (!deficient) {  // unique solution
        EXPECT_LE((w.x - cold.x).cwiseAbs().maxCoeff(), 1e-8 * std::max(1.0, cold.x.cwiseAbs().maxCoeff()));
        if (name == "optimal") {
          EXPECT_LE(w.iterations, 1);
        }
      }
    }
  }
}

TEST(NonnegativeQPSolverObject, ReusesWorkspaceAcrossSizes) {
  std::mt19937 rng(11);
  NonnegativeQPSolver solver;
  for (int n : {10, 25, 5, 25, 1, 40, 12}) {
    const MatrixXd Q = qpref::gram(qpref::randn(rng, n + 2, n));
    const VectorXd c = qpref::randn(rng, n, 1);
    const QPResult& r = solver.solve(Q, c);
    const QPResult ref = solve_nonnegative_qp(Q, c);
    ASSERT_EQ(r.status, QPStatus::Solved);
    EXPECT_EQ(r.x, ref.x);
    EXPECT_EQ(r.passive, ref.passive);
    EXPECT_EQ(r.iterations, ref.iterations);
    const QPResult& w = solver.solve(Q, c, ref.passive);
    EXPECT_TRUE(w.x.isApprox(ref.x, 1e-10));
  }
}
