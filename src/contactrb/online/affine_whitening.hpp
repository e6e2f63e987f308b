#pragma once
// A factor A_hat(mu) = L L' of the reduced stiffness (49) and its inverse applications
// x <- L^-1 x, x <- L^-T x, the whitening of the online solve (online_solver.hpp: E = L^-1 D',
// u_bar = L^-T (L^-1 f - E lambda)). Two forms:
//
//  Simultaneous diagonalization (at most two affine terms, A_hat(mu) = sum_j theta_j(mu) A_j):
//   the generalized eigenvectors V of (A_2, B), B = A_1 + A_2 (V'BV = I, V'A_2V = diag(l)), give
//   V'A_jV = diag(l_j) with l_1 = 1 - l, l_2 = l, so A_hat(mu) = V^-T diag(d) V^-1 with
//   d = sum_j theta_j(mu) l_j. Then L = V^-T diag(sqrt d): L^-1 = diag(d^-1/2) V' and
//   L^-T = V diag(d^-1/2). Per query the factor costs N (d) instead of N^3/3 (Cholesky), and a
//   row of Theta_c L^-T is a row of the precomputed Theta_c V scaled by d^-1/2 (N flops instead
//   of a triangular solve, N^2/2; MagicPointEvaluator::prepare_scaled). A_hat(mu) is positive
//   definite exactly when every d_i > 0. One term: V = L_B^-T from the Cholesky factor of B.
//  Cholesky (three terms or more, or B not positive definite): L the Cholesky factor of
//   A_hat(mu), computed per query.
//
// Both are factors of the same matrix: the answers agree to round-off (docs/offline-online.md,
// "Cost of a query with the exact rows").
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

namespace contactrb::online {

class AffineWhitening {
 public:
  // The affine terms A_j (N x N, symmetric). The simultaneous form is available when there are
  // at most two and their sum is positive definite.
  void setup(const std::vector<Eigen::MatrixXd>& terms);
  bool diagonal_available() const { return diagonal_available_; }
  // V (N x N): the basis that diagonalizes every term (diagonal_available() only).
  const Eigen::MatrixXd& basis() const { return V_; }

  // Per query: A = sum_j theta_j A_j (the caller's assembly, used by the Cholesky form) and the
  // thetas; the simultaneous form when `diagonal` and available, the Cholesky form otherwise.
  // Why a choice: L^-1 applied to R columns costs N^2 R in the simultaneous form and N^2 R / 2
  // by a triangular solve, so it pays where the columns come pre-solved (the touched rows of
  // Theta_c L^-T) and not where every step solves D' (EIM rows, registered cones). false when
  // A_hat(mu) is not positive definite.
  bool factor(const Eigen::VectorXd& theta, const Eigen::MatrixXd& A, bool diagonal = true);
  // The form of the last factor.
  bool diagonal() const { return diagonal_; }

  // d^-1/2 (diagonal form), after factor.
  const Eigen::VectorXd& scale() const { return scale_; }
  // x <- L^-1 x (N x k).
  void solve_factor(Eigen::MatrixXd& x) const;
  void solve_factor(Eigen::VectorXd& x) const;
  // x <- L^-T x (a vector, or N x k).
  void solve_factor_transpose(Eigen::VectorXd& x) const;
  void solve_factor_transpose(Eigen::MatrixXd& x) const;
  // The Cholesky form's L (not diagonal()).
  const Eigen::LLT<Eigen::MatrixXd>& cholesky() const { return llt_; }

 private:
  bool diagonal_available_ = false;
  bool diagonal_ = false;
  Eigen::MatrixXd V_;                 // N x N
  Eigen::MatrixXd term_diagonal_;     // N x J: l_j
  Eigen::VectorXd scale_;             // d^-1/2
  mutable Eigen::VectorXd work_;      // N
  mutable Eigen::MatrixXd work_m_;    // N x k
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd U_;                 // L' (Cholesky form; column-major: solve_factor_transpose reads its columns)
  Eigen::VectorXd inv_diag_;          // 1 / U_ii
};

// Inline: a query's steps call them with the solver's own workspaces; the Cholesky form's
// triangular solves are then instantiated where the step's products are.
inline void AffineWhitening::solve_factor(Eigen::MatrixXd& x) const {
  if (diagonal_) {
    work_m_.noalias() = V_.transpose() * x;
    x = scale_.asDiagonal() * work_m_;
    return;
  }
  llt_.matrixL().solveInPlace(x);
}

inline void AffineWhitening::solve_factor(Eigen::VectorXd& x) const {
  if (diagonal_) {
    work_.noalias() = V_.transpose() * x;
    x = work_.cwiseProduct(scale_);
    return;
  }
  llt_.matrixL().solveInPlace(x);
}

inline void AffineWhitening::solve_factor_transpose(Eigen::VectorXd& x) const {
  if (diagonal_) {
    work_ = x.cwiseProduct(scale_);
    x.noalias() = V_ * work_;
    return;
  }
  // By columns of U = L': each step an axpy on contiguous memory. Eigen's row-wise solve with
  // the transposed view chains one reduction per row: about twice the time at N ~ 50.
  for (Eigen::Index i = x.size() - 1; i >= 0; --i) {
    x(i) *= inv_diag_(i);
    x.head(i).noalias() -= x(i) * U_.col(i).head(i);
  }
}

inline void AffineWhitening::solve_factor_transpose(Eigen::MatrixXd& x) const {
  if (diagonal_) {
    work_m_ = scale_.asDiagonal() * x;
    x.noalias() = V_ * work_m_;
    return;
  }
  llt_.matrixU().solveInPlace(x);
}

}  // namespace contactrb::online
