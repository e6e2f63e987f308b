#include "contactrb/online/affine_whitening.hpp"

#include <Eigen/Eigenvalues>

namespace contactrb::online {

void AffineWhitening::setup(const std::vector<Eigen::MatrixXd>& terms) {
  diagonal_ = false;
  const Eigen::Index n = terms.empty() ? 0 : terms.front().rows();
  scale_.resize(n);
  work_.resize(n);
  if (terms.empty() || terms.size() > 2 || n == 0) return;
  Eigen::MatrixXd B = terms[0];
  for (std::size_t j = 1; j < terms.size(); ++j) B += terms[j];
  const Eigen::LLT<Eigen::MatrixXd> llt_B(B);
  if (llt_B.info() != Eigen::Success) return;
  term_diagonal_.resize(n, static_cast<Eigen::Index>(terms.size()));
  if (terms.size() == 1) {
    V_ = llt_B.matrixU().solve(Eigen::MatrixXd::Identity(n, n));  // L_B^-T: V'BV = I
    term_diagonal_.col(0).setOnes();
  } else {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(terms[1], B,
                                                                        Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (eig.info() != Eigen::Success || !eig.eigenvectors().allFinite()) return;
    V_ = eig.eigenvectors();
    term_diagonal_.col(1) = eig.eigenvalues();
    term_diagonal_.col(0) = Eigen::VectorXd::Ones(n) - eig.eigenvalues();
  }
  diagonal_ = true;
}

bool AffineWhitening::factor(const Eigen::VectorXd& theta, const Eigen::MatrixXd& A) {
  if (diagonal_) {
    const Eigen::VectorXd d = term_diagonal_ * theta;
    if (!(d.minCoeff() > 0.0) || !d.allFinite()) return false;
    scale_ = d.cwiseSqrt().cwiseInverse();
    return true;
  }
  llt_.compute(A);
  if (llt_.info() != Eigen::Success) return false;
  U_ = llt_.matrixL().transpose();
  inv_diag_ = U_.diagonal().cwiseInverse();
  return true;
}

void AffineWhitening::solve_factor(Eigen::MatrixXd& x) const {
  if (diagonal_) {
    work_m_.noalias() = V_.transpose() * x;
    x = scale_.asDiagonal() * work_m_;
    return;
  }
  llt_.matrixL().solveInPlace(x);
}

void AffineWhitening::solve_factor(Eigen::VectorXd& x) const {
  if (diagonal_) {
    work_.noalias() = V_.transpose() * x;
    x = work_.cwiseProduct(scale_);
    return;
  }
  llt_.matrixL().solveInPlace(x);
}

void AffineWhitening::solve_factor_transpose(Eigen::VectorXd& x) const {
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

void AffineWhitening::solve_factor_transpose(Eigen::MatrixXd& x) const {
  if (diagonal_) {
    work_m_ = scale_.asDiagonal() * x;
    x.noalias() = V_ * work_m_;
    return;
  }
  llt_.matrixU().solveInPlace(x);
}

}  // namespace contactrb::online
