#pragma once
// Exact non-negative quadratic program
//     min 1/2 x' Q x - c' x   subject to x >= 0,
// Q symmetric positive semidefinite and dense, by a primal active-set method with finite
// termination. One solver serves three places (DESIGN.md): the HF contact QP in dual form
// (Q = K A^-1 K'), the online reduced QP (Q = D A_hat^-1 D') and cone projections
// (Q = Xi' M Xi, c = Xi' M lambda). Algorithm, statuses and limits: docs/solvers.md.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace contactrb::solve {

enum class QPStatus { Solved, MaxIterations, Numerics, Unbounded, InvalidInput };
const char* to_string(QPStatus status);
QPStatus qp_status_from_string(const std::string& name);  // throws contactrb::Error

struct QPSettings {
  int max_iterations = -1;  // -1: 10 * (n + 10); counts subproblem steps (see docs)
  // Relative KKT tolerance. With s = max(|c|_inf, |Q|_inf |x|_inf) (|Q|_inf: max row sum)
  // at the returned x, the status is Solved iff
  //   primal <= tolerance |x|_inf,  dual <= tolerance s,  complementarity <= tolerance s |x|_inf.
  // The same threshold tolerance * s decides which gradient entries count as negative.
  double tolerance = 1e-12;
  // A variable j whose Schur complement pivot Q_jj - Q_jP Q_PP^-1 Q_Pj is <= rank_tolerance * Q_jj
  // is treated as linearly dependent on the passive set P (for NNLS: sin^2 of the angle between
  // column j and the span of the passive columns).
  double rank_tolerance = 1e-12;
  // Q is rejected (contactrb::Error) when max |Q_ij - Q_ji| > symmetry_tolerance * max |Q_ij|.
  double symmetry_tolerance = 1e-10;
};

// KKT residuals of a candidate x: gradient r = Q x - c must be >= 0, x >= 0, x' r = 0.
struct KKTResiduals {
  double primal = 0.0;           // max(0, -min x)
  double dual = 0.0;             // max(0, -min r)
  double complementarity = 0.0;  // max |x_i r_i|
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
  double kkt_scale = 0.0;    // s of QPSettings::tolerance at the returned x
  Eigen::VectorXd ray;       // Unbounded only: d >= 0, Q d ~ 0, c'd > 0, |d|_inf = 1; else empty
};

// warm_passive: optional initial passive (free) set, e.g. the previous Kacanov iterate's.
// Any set is valid (duplicates are ignored; a wrong or infeasible set only costs iterations).
// Throws contactrb::Error for mismatched sizes or non-finite input (a usage error);
// numerical trouble is a status.
QPResult solve_nonnegative_qp(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c,
                              const QPSettings& settings = {}, const std::vector<int>& warm_passive = {});

// The same solver as an object that keeps its workspace (factor, gradient, index sets) and its
// result between calls: once sized, a call allocates nothing on the heap for problems of the
// same or smaller size (the message string aside). For the online reduced QP.
class NonnegativeQPSolver {
 public:
  explicit NonnegativeQPSolver(const QPSettings& settings = {});
  ~NonnegativeQPSolver();
  NonnegativeQPSolver(NonnegativeQPSolver&&) noexcept;
  NonnegativeQPSolver& operator=(NonnegativeQPSolver&&) noexcept;

  const QPResult& solve(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c,
                        const std::vector<int>& warm_passive = {});
  const QPResult& result() const { return result_; }
  const QPSettings& settings() const { return settings_; }
  void set_settings(const QPSettings& settings) { settings_ = settings; }

  struct Workspace;  // defined in nonnegative_qp.cpp

 private:
  QPSettings settings_;
  std::unique_ptr<Workspace> workspace_;
  QPResult result_;
};

// Non-negative least squares in a weighted norm: argmin_{y >= 0} |x - Xi y|_M, M = diag(m)
// (m empty: identity). Returns the QP result with x = y; used by cone projections.
QPResult solve_nnls(const Eigen::MatrixXd& Xi, const Eigen::VectorXd& x, const Eigen::VectorXd& m = {},
                    const QPSettings& settings = {});

}  // namespace contactrb::solve
