#include "contactrb/solve/constrained_eigenvalue.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"

namespace contactrb::solve {

namespace {

using Index = Eigen::Index;

// A vector x of ker D with its image S x (S = C^-1), kept together so that S is never formed.
struct Pair {
  Eigen::VectorXd x;
  Eigen::VectorXd Sx;
};

// C_D = C - C D'(D C D')^-1 D C (the header): apply(y) = (C_D y, S C_D y).
class ConstrainedInverse {
 public:
  ConstrainedInverse(const Eigen::MatrixXd& C, const Eigen::SparseMatrix<double, Eigen::RowMajor>& D) : C_(C), D_(D) {
    if (D.rows() == 0) return;
    CDt_ = C * D.transpose();
    Eigen::MatrixXd G = D * CDt_;
    G = 0.5 * (G + G.transpose()).eval();
    llt_.compute(G);
    if (llt_.info() == Eigen::Success && llt_.matrixLLT().diagonal().minCoeff() > 0.0) return;
    // Dependent rows: the pseudo-inverse of D C D' (the header).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
    require(eig.info() == Eigen::Success && eig.eigenvalues().maxCoeff() > 0.0,
            "largest_constrained_eigenvalue: D C D' is not positive semi-definite (C must be positive definite)");
    const double cut = kDependentRows * eig.eigenvalues().maxCoeff();
    Eigen::VectorXd inv = Eigen::VectorXd::Zero(G.rows());
    for (Index i = 0; i < G.rows(); ++i) {
      if (eig.eigenvalues()(i) > cut) inv(i) = 1.0 / eig.eigenvalues()(i);
    }
    pseudo_inverse_ = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
    pseudo_ = true;
  }

  Pair apply(const Eigen::VectorXd& y) const {
    Pair out{C_ * y, y};
    if (D_.rows() == 0) return out;
    const Eigen::VectorXd Dcy = D_ * out.x;
    const Eigen::VectorXd mu = pseudo_ ? Eigen::VectorXd(pseudo_inverse_ * Dcy) : Eigen::VectorXd(llt_.solve(Dcy));
    out.x -= CDt_ * mu;
    out.Sx -= D_.transpose() * mu;
    return out;
  }

 private:
  const Eigen::MatrixXd& C_;
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& D_;
  Eigen::MatrixXd CDt_;  // C D'
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd pseudo_inverse_;
  bool pseudo_ = false;
};

// A fixed pseudo-random start (the same bits on every machine: raw mt19937_64 words), so that
// the result does not depend on where it runs; random, so that no symmetry of the problem makes
// it orthogonal to the wanted eigenvector.
Eigen::VectorXd start_vector(Index m) {
  std::mt19937_64 words(20190101);
  Eigen::VectorXd v(m);
  for (Index i = 0; i < m; ++i) v(i) = static_cast<double>(words() >> 11) * 0x1p-53 - 0.5;
  return v;
}

// The Krylov basis Q (S-orthonormal columns) and S Q, grown by blocks of columns.
class LanczosBasis {
 public:
  explicit LanczosBasis(Index m) : Q_(m, 0), SQ_(m, 0) {}
  Index size() const { return size_; }
  Eigen::VectorXd column(Index j) const { return Q_.col(j); }

  void append(const Pair& p, double norm) {
    if (size_ == Q_.cols()) {
      const Index grown = std::min<Index>(Q_.rows(), size_ + 64);
      Q_.conservativeResize(Eigen::NoChange, grown);
      SQ_.conservativeResize(Eigen::NoChange, grown);
    }
    Q_.col(size_) = p.x / norm;
    SQ_.col(size_) = p.Sx / norm;
    ++size_;
  }

  // p minus its S-projection on the basis, classical Gram-Schmidt applied twice (one pass loses
  // orthogonality once Ritz values converge).
  void orthogonalize(Pair& p) const {
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd c = Q_.leftCols(size_).transpose() * p.Sx;
      p.x.noalias() -= Q_.leftCols(size_) * c;
      p.Sx.noalias() -= SQ_.leftCols(size_) * c;
    }
  }

 private:
  Eigen::MatrixXd Q_, SQ_;
  Index size_ = 0;
};

struct Ritz {
  double theta = 0.0;     // the largest Ritz value
  double residual = 0.0;  // |C_D M x - theta x|_S for its Ritz vector x (|x|_S = 1)
  double scale = 0.0;     // the largest |Ritz value|
};

// The largest Ritz pair of the tridiagonal T (alpha, beta) whose next off-diagonal is `next`.
Ritz largest_ritz(const std::vector<double>& alpha, const std::vector<double>& beta, double next) {
  const Index k = static_cast<Index>(alpha.size());
  const Eigen::VectorXd diag = Eigen::Map<const Eigen::VectorXd>(alpha.data(), k);
  const Eigen::VectorXd sub = Eigen::Map<const Eigen::VectorXd>(beta.data(), k - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;
  eig.computeFromTridiagonal(diag, sub, Eigen::ComputeEigenvectors);
  require(eig.info() == Eigen::Success, "largest_constrained_eigenvalue: the tridiagonal eigenproblem did not converge");
  Ritz r;
  r.theta = eig.eigenvalues()(k - 1);
  r.residual = next * std::abs(eig.eigenvectors()(k - 1, k - 1));
  r.scale = std::max(std::abs(eig.eigenvalues()(0)), std::abs(r.theta));
  return r;
}

}  // namespace

ConstrainedEigenvalueResult largest_constrained_eigenvalue(const Eigen::MatrixXd& C,
                                                           const Eigen::SparseMatrix<double>& M,
                                                           const Eigen::SparseMatrix<double, Eigen::RowMajor>& D,
                                                           const ConstrainedEigenvalueSettings& settings) {
  const Index m = C.rows();
  require(C.cols() == m && M.rows() == m && M.cols() == m && D.cols() == m,
          "largest_constrained_eigenvalue: C is " + std::to_string(C.rows()) + " x " + std::to_string(C.cols()) +
              ", M " + std::to_string(M.rows()) + " x " + std::to_string(M.cols()) + ", D " +
              std::to_string(D.rows()) + " x " + std::to_string(D.cols()) + ": C and M must be square, of D's columns");
  ConstrainedEigenvalueResult out;
  out.converged = true;
  if (m == 0) return out;
  const ConstrainedInverse inverse(C, D);
  const Index steps = settings.max_iterations > 0 ? std::min<Index>(settings.max_iterations, m) : m;

  // Start in the range of C_D M; a start S-orthogonal to it (C_D M v = 0 up to round-off) means
  // M vanishes on ker D.
  const Eigen::VectorXd y0 = M * start_vector(m);
  Pair p = inverse.apply(y0);
  const double norm2 = p.x.dot(p.Sx);
  if (!(norm2 > 64.0 * Eigen::NumTraits<double>::epsilon() * y0.dot(C * y0))) return out;
  LanczosBasis basis(m);
  basis.append(p, std::sqrt(norm2));
  std::vector<double> alpha, beta;
  out.converged = false;
  for (;;) {
    const Eigen::VectorXd q = basis.column(basis.size() - 1);
    const Eigen::VectorXd y = M * q;
    alpha.push_back(q.dot(y));  // <C_D M q, q>_S = q'M q
    p = inverse.apply(y);
    basis.orthogonalize(p);
    const double next = std::sqrt(std::max(0.0, p.x.dot(p.Sx)));
    const Ritz ritz = largest_ritz(alpha, beta, next);
    out.value = std::max(0.0, ritz.theta);
    out.iterations = static_cast<int>(alpha.size());
    out.residual = ritz.scale > 0.0 ? ritz.residual / ritz.scale : 0.0;
    if (ritz.residual <= settings.tolerance * ritz.scale) {
      out.converged = true;
      return out;
    }
    if (basis.size() == steps) return out;
    beta.push_back(next);
    basis.append(p, next);
  }
}

}  // namespace contactrb::solve
