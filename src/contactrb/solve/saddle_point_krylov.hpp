#pragma once
// Right-preconditioned GMRES (solve/gmres.hpp) on a saddle-point system
//   [ F  B' ] [ x ]   [ f ]
//   [ C  0  ] [ y ] = [ g ],     F: n x n, B, C: m x n,
// the semi-smooth Newton systems of the active rows (hf/newton_linear_system.hpp: F = A_00 + H,
// B = K_A, C = K_A (frozen geometry) or -D_A), preconditioned by the block upper-triangular
//   P = [ F^  B' ]      F^-1 ~ one AMG V-cycle on A_00 (solve/amg_preconditioner.hpp),
//       [ 0  -S^ ],     S^ = C diag(F)^-1 B', a sparse m x m approximation of C F^-1 B'
// (Elman, Silvester, Wathen, "Finite Elements and Fast Iterative Solvers", Section 9.2; with
// exact blocks GMRES converges in two steps). The constraint rows and multiplier columns are
// equilibrated against the mean diagonal of F, so that the residual weighs forces and gaps alike
// (docs/solvers.md, "AMG-preconditioned Krylov solve").
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "contactrb/solve/amg_preconditioner.hpp"

namespace contactrb::solve {

struct SaddlePointKrylovSettings {
  double tolerance = 1e-4;   // residual of the equilibrated system relative to the one at x_ref
  int max_iterations = 400;  // GMRES products in all
  int restart = 80;          // Krylov vectors kept (memory: restart x (n + m) doubles)
};

enum class SaddlePointKrylovStatus { Converged, MaxIterations, SchurSingular, InvalidInput };
const char* to_string(SaddlePointKrylovStatus status);
SaddlePointKrylovStatus saddle_point_krylov_status_from_string(const std::string& name);

struct SaddlePointKrylovResult {
  SaddlePointKrylovStatus status = SaddlePointKrylovStatus::InvalidInput;
  Eigen::VectorXd x;               // [x; y], n + m
  int iterations = 0;              // GMRES products
  double relative_residual = 0.0;  // of the equilibrated system, relative to the one at x_ref
};

// x0: the initial guess [x; y] (n + m); the tolerance is relative to the residual at x_ref
// (nullptr: at x0), so that a warm start (x0 near the solution) stops at the same accuracy as a
// start from x_ref. `amg` holds the hierarchy of A_00 (F without its contact terms).
// InvalidInput: sizes that do not match or `amg` without a hierarchy.
SaddlePointKrylovResult solve_saddle_point(const Eigen::SparseMatrix<double>& F,
                                           const Eigen::SparseMatrix<double, Eigen::RowMajor>& B,
                                           const Eigen::SparseMatrix<double, Eigen::RowMajor>& C,
                                           const AmgPreconditioner& amg, const Eigen::VectorXd& rhs,
                                           const Eigen::VectorXd& x0, const SaddlePointKrylovSettings& settings,
                                           const Eigen::VectorXd* x_ref = nullptr);

}  // namespace contactrb::solve
