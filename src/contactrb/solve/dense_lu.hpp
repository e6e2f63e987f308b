#pragma once
// Dense LU with partial pivoting through LAPACK (dgetrf / dgetrs / dgecon; on Debian the
// liblapack.so.3 alternative is OpenBLAS, blocked and threaded). For the reduced Newton systems
// of size |E| + |A| (hf/semismooth_newton.hpp), 1e2 to a few 1e3: Eigen's PartialPivLU with
// its portable kernels takes 0.1-0.2 s per system of size ~1 000, several times LAPACK's blocked
// one. Same interface idea as Eigen's solvers: compute(), then solve().
#include <Eigen/Core>
#include <vector>

namespace contactrb::solve {

class DenseLU {
 public:
  // Factorizes M (square; takes ownership). Returns false for a non-square or non-finite M;
  // an exactly singular M (a zero pivot) factorizes with rcond() == 0.
  bool compute(Eigen::MatrixXd M);
  // Reciprocal condition number estimate in the 1-norm (LAPACK dgecon); 0 when singular.
  double rcond() const { return rcond_; }
  Eigen::Index rows() const { return lu_.rows(); }
  // Throws contactrb::Error unless compute() succeeded with rcond() > 0 and b has rows() entries.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> pivots_;
  double rcond_ = 0.0;
  bool ok_ = false;
};

}  // namespace contactrb::solve
