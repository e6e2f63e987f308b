#pragma once
// Exact non-negative quadratic program
//     min 1/2 x' Q x - c' x   subject to x >= 0,
// Q symmetric positive semidefinite and dense, by a primal active-set method with finite
// termination. One solver serves three places (DESIGN.md): the HF contact QP in dual form
// (Q = K A^-1 K'), the online reduced QP (Q = D A_hat^-1 D') and cone projections
// (Q = Xi' M Xi, c = Xi' M lambda).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace contactrb::solve {

enum class QPStatus { Solved, MaxIterations, Numerics, Unbounded, InvalidInput };
const char* to_string(QPStatus status);

struct QPSettings {
  int max_iterations = -1;        // -1: 10 * (n + 10)
  double tolerance = 1e-12;       // relative KKT tolerance (scaled by max(1, |c|_inf, |Q|_inf))
};

// KKT residuals of a candidate x: gradient r = Q x - c must be >= 0, x >= 0, x' r = 0.
struct KKTResiduals {
  double primal = 0.0;          // max(0, -min x)
  double dual = 0.0;            // max(0, -min r)
  double complementarity = 0.0; // max |x_i r_i|
  double max() const;
};
KKTResiduals kkt_residuals(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const Eigen::VectorXd& x);

struct QPResult {
  QPStatus status = QPStatus::InvalidInput;
  Eigen::VectorXd x;
  int iterations = 0;
  KKTResiduals kkt;
  std::vector<int> passive;  // indices with x_i > 0 (the free set at exit), sorted
  std::string message;       // empty when Solved
};

// warm_passive: optional initial passive (free) set, e.g. the previous Kacanov iterate's.
// Throws contactrb::Error for mismatched sizes or non-finite input (a usage error);
// numerical trouble is a status.
QPResult solve_nonnegative_qp(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c,
                              const QPSettings& settings = {},
                              const std::vector<int>& warm_passive = {});

// Non-negative least squares in a weighted norm: argmin_{y >= 0} |x - Xi y|_M, M = diag(m)
// (m empty: identity). Returns the QP result with x = y; used by cone projections.
QPResult solve_nnls(const Eigen::MatrixXd& Xi, const Eigen::VectorXd& x,
                    const Eigen::VectorXd& m = {}, const QPSettings& settings = {});

}  // namespace contactrb::solve
