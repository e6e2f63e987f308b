#include "contactrb/online/affine_whitening.hpp"

#include <Eigen/Eigenvalues>

namespace contactrb::online {

void AffineWhitening::setup(const std::vector<Eigen::MatrixXd>& terms) {
  diagonal_available_ = false;
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
  diagonal_available_ = true;
}

bool AffineWhitening::factor(const Eigen::VectorXd& theta, const Eigen::MatrixXd& A, bool diagonal) {
  diagonal_ = diagonal && diagonal_available_;
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

}  // namespace contactrb::online
