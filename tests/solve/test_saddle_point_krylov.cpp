// solve::solve_saddle_point (GMRES with the AMG / Schur block preconditioner) and
// solve::AmgPreconditioner against a dense LU of the same saddle point: a 3D-like system matrix
// (a 2D grid Laplacian per component, two components), symmetric and nonsymmetric constraint
// rows; the statuses of bad input and of a capped iteration count.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <tuple>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/solve/amg_preconditioner.hpp"
#include "contactrb/solve/saddle_point_krylov.hpp"

using namespace contactrb;

namespace {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Two decoupled components of the 5-point Laplacian on a k x k grid (Dirichlet boundary),
// unknowns interleaved by node as in the elasticity DOF map.
Eigen::SparseMatrix<double> grid_laplacian(int k, std::vector<int>& component) {
  const int nodes = k * k, n = 2 * nodes;
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) {
        const int p = 2 * (i * k + j) + c;
        t.emplace_back(p, p, 4.0 + 0.5 * c);
        if (i > 0) t.emplace_back(p, p - 2 * k, -1.0);
        if (i + 1 < k) t.emplace_back(p, p + 2 * k, -1.0);
        if (j > 0) t.emplace_back(p, p - 2, -1.0);
        if (j + 1 < k) t.emplace_back(p, p + 2, -1.0);
      }
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  component.resize(static_cast<std::size_t>(n));
  for (int p = 0; p < n; ++p) component[static_cast<std::size_t>(p)] = p % 2;
  return A;
}

// m constraint rows coupling a node's first component with its neighbour's (a contact-like row).
RowSparse constraint_rows(int n, int m, double weight, double skew) {
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < m; ++a) {
    const int p = 2 * (7 * a + 3);
    t.emplace_back(a, p, weight);
    t.emplace_back(a, p + 2, -weight * (1.0 + skew));
  }
  RowSparse B(m, n);
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

Eigen::VectorXd dense_solution(const Eigen::SparseMatrix<double>& F, const RowSparse& B, const RowSparse& C,
                               const Eigen::VectorXd& rhs) {
  const Eigen::Index n = F.rows(), m = B.rows();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + m, n + m);
  M.topLeftCorner(n, n) = Eigen::MatrixXd(F);
  M.topRightCorner(n, m) = Eigen::MatrixXd(B).transpose();
  M.bottomLeftCorner(m, n) = Eigen::MatrixXd(C);
  return M.partialPivLu().solve(rhs);
}

// The 20 x 20 two-component grid operator, its AMG hierarchy and 12 unskewed constraint rows.
struct GridProblem {
  GridProblem() : A(grid_laplacian(20, component)), n(static_cast<int>(A.rows())), B(constraint_rows(n, m, 1e-3, 0.0)) {
    status = amg.compute(A, component, 2);
  }
  std::vector<int> component;
  Eigen::SparseMatrix<double> A;
  int n = 0;
  static constexpr int m = 12;
  RowSparse B;
  solve::AmgPreconditioner amg;
  solve::AmgStatus status = solve::AmgStatus::InvalidInput;
};

}  // namespace

TEST(SaddlePointKrylov, MatchesTheDenseSolveSymmetricAndNot) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  const GridProblem g;
  ASSERT_EQ(g.status, solve::AmgStatus::Success);
  EXPECT_GE(g.amg.levels(), 2);
  const auto& [A, n, B, amg] = std::tie(g.A, g.n, g.B, g.amg);
  const int m = GridProblem::m;
  Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n + m, -1.0, 2.0);
  for (double skew : {0.0, 0.3}) {
    const RowSparse C = constraint_rows(n, m, 1e-3, skew);
    const Eigen::VectorXd exact = dense_solution(A, B, C, rhs);
    solve::SaddlePointKrylovSettings s;
    s.tolerance = 1e-12;
    const solve::SaddlePointKrylovResult r =
        solve::solve_saddle_point(A, B, C, amg, rhs, Eigen::VectorXd::Zero(n + m), s);
    ASSERT_EQ(r.status, solve::SaddlePointKrylovStatus::Converged) << "skew " << skew;
    EXPECT_LE((r.x - exact).lpNorm<Eigen::Infinity>(), 1e-9 * exact.lpNorm<Eigen::Infinity>()) << "skew " << skew;
    EXPECT_LT(r.iterations, 60) << "skew " << skew;
  }
}

TEST(SaddlePointKrylov, CappedIterationsAndBadInputAreStatuses) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  const GridProblem g;
  ASSERT_EQ(g.status, solve::AmgStatus::Success);
  const auto& [A, n, B, amg] = std::tie(g.A, g.n, g.B, g.amg);
  const int m = GridProblem::m;
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(n + m);
  solve::SaddlePointKrylovSettings s;
  s.max_iterations = 1;
  const solve::SaddlePointKrylovResult capped =
      solve::solve_saddle_point(A, B, B, amg, rhs, Eigen::VectorXd::Zero(n + m), s);
  EXPECT_EQ(capped.status, solve::SaddlePointKrylovStatus::MaxIterations);
  EXPECT_EQ(capped.iterations, 1);
  EXPECT_GT(capped.relative_residual, s.tolerance);
  EXPECT_EQ(solve::solve_saddle_point(A, B, B, amg, rhs, Eigen::VectorXd::Zero(n), {}).status,
            solve::SaddlePointKrylovStatus::InvalidInput);
  const solve::AmgPreconditioner none;
  EXPECT_EQ(solve::solve_saddle_point(A, B, B, none, rhs, Eigen::VectorXd::Zero(n + m), {}).status,
            solve::SaddlePointKrylovStatus::InvalidInput);
  EXPECT_THROW(none.apply(Eigen::VectorXd::Zero(n)), Error);
  solve::AmgPreconditioner bad;
  EXPECT_EQ(bad.compute(A, std::vector<int>(3, 0), 2), solve::AmgStatus::InvalidInput);
  EXPECT_EQ(bad.compute(Eigen::SparseMatrix<double>(3, 4), {}, 1), solve::AmgStatus::InvalidInput);
  EXPECT_EQ(solve::amg_status_from_string("invalid input"), solve::AmgStatus::InvalidInput);
}

// Both smoothers (solve::AmgSmoother): a V-cycle with forward Gauss-Seidel down and backward up,
// or symmetric sweeps both ways, is a symmetric operator (x' M^-1 y = y' M^-1 x); the two cycles
// differ (the option takes effect) and both precondition the saddle point to its dense solution.
TEST(SaddlePointKrylov, BothSmoothersGiveSymmetricCyclesAndTheSolution) {
  if (!solve::amg_available()) GTEST_SKIP() << "this build has no hypre";
  std::vector<int> component;
  const Eigen::SparseMatrix<double> A = grid_laplacian(20, component);
  const int n = static_cast<int>(A.rows()), m = GridProblem::m;
  const RowSparse B = constraint_rows(n, m, 1e-3, 0.0);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0).array().sin();
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(n, 0.0, 3.0).array().cos();
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n + m, -1.0, 2.0);
  const Eigen::VectorXd exact = dense_solution(A, B, B, rhs);
  std::vector<Eigen::VectorXd> cycles;
  for (solve::AmgSmoother smoother : {solve::AmgSmoother::ForwardBackward, solve::AmgSmoother::Symmetric}) {
    solve::AmgSettings settings;
    settings.smoother = smoother;
    solve::AmgPreconditioner amg;
    ASSERT_EQ(amg.compute(A, component, 2, settings), solve::AmgStatus::Success);
    const Eigen::VectorXd My = amg.apply(y);
    EXPECT_NEAR(x.dot(My), y.dot(amg.apply(x)), 1e-12 * x.norm() * My.norm()) << solve::to_string(smoother);
    cycles.push_back(My);
    solve::SaddlePointKrylovSettings s;
    s.tolerance = 1e-12;
    const solve::SaddlePointKrylovResult r = solve::solve_saddle_point(A, B, B, amg, rhs, Eigen::VectorXd::Zero(n + m), s);
    ASSERT_EQ(r.status, solve::SaddlePointKrylovStatus::Converged) << solve::to_string(smoother);
    EXPECT_LE((r.x - exact).lpNorm<Eigen::Infinity>(), 1e-9 * exact.lpNorm<Eigen::Infinity>()) << solve::to_string(smoother);
  }
  EXPECT_GT((cycles[0] - cycles[1]).norm(), 1e-6 * cycles[1].norm());
  EXPECT_EQ(solve::amg_smoother_from_string("symmetric"), solve::AmgSmoother::Symmetric);
  EXPECT_EQ(solve::amg_smoother_from_string(solve::to_string(solve::AmgSmoother::ForwardBackward)),
            solve::AmgSmoother::ForwardBackward);
  EXPECT_THROW(solve::amg_smoother_from_string("jacobi"), Error);
}
