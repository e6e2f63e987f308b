#pragma once
// Column-pivoted Householder QR through LAPACK dgeqp3 (A P = Q R; on Debian the liblapack.so.3
// alternative is OpenBLAS, whose dgeqp3 does half of its flops in blocked matrix products).
// Eigen's ColPivHouseholderQR is unblocked: on the estimate's residual factor of hertz-a level 5
// (1 134 x 8 622) it is several times slower. Same rank rule as Eigen's: the leading diagonal
// entries of R above threshold * |R(0, 0)|. Runs on one BLAS thread, so its result does not
// depend on the process's BLAS thread count.
#include <Eigen/Core>
#include <vector>

namespace contactrb::solve {

struct PivotedQR {
  Eigen::MatrixXd R;             // rank x n, upper trapezoidal: the leading rows of R
  std::vector<Eigen::Index> permutation;  // column k of A P is column permutation[k] of A
};

// The rank-truncated R of A P = Q R: |A y| = |R P' y| for every y up to the dropped rows (at most
// the threshold times |R(0, 0)| |y| each). At least one row is kept. Throws contactrb::Error for a
// non-finite A or one too large for LAPACK's int sizes.
PivotedQR pivoted_qr(Eigen::MatrixXd A, double threshold);

}  // namespace contactrb::solve
