#pragma once
// Projection onto a convex cone K = span+{xi_1, ..., xi_R} (the operator Pi_K of (57)):
//     Pi_K(x) = Xi c*,  c* = argmin_{c >= 0} |x - Xi c|_M,
// M = diag(w) (the L2(Gamma^c) norm of the multipliers, w_r = |I_r|) or the identity (w empty),
// through the exact non-negative QP of solve/ (Q = Xi' M Xi, c = Xi' M x).
#include <Eigen/Core>
#include <vector>

#include "contactrb/solve/nonnegative_qp.hpp"

namespace contactrb::offline {

struct ConeProjection {
  solve::QPStatus status = solve::QPStatus::Solved;
  Eigen::VectorXd coefficients;  // c* >= 0, size R
  Eigen::VectorXd projection;    // Pi_K(x) = Xi c*
  double error = 0.0;            // |x - Pi_K(x)|_M
  std::vector<int> passive;      // generators with c*_r > 0 (a warm start for a nearby x)
  int iterations = 0;            // QP iterations
};

// One projection, through solve::solve_nnls. Throws contactrb::Error for mismatched sizes,
// non-finite input or negative weights.
ConeProjection project_onto_cone(const Eigen::MatrixXd& generators, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& weights = {}, const solve::QPSettings& qp = {});

// Condition number of the generators in the M norm: sqrt(cond(Xi' M Xi)) = sigma_max / sigma_min
// of diag(sqrt(w)) Xi (singular values). +infinity when the generators are linearly dependent
// (sigma_min = 0) and 1 for an empty family.
double generator_condition_number(const Eigen::MatrixXd& generators, const Eigen::VectorXd& weights = {});

// |v|_M with M = diag(weights) (empty: identity).
double weighted_norm(const Eigen::VectorXd& v, const Eigen::VectorXd& weights);

// Projector onto a cone that grows one generator at a time: keeps M Xi and Q = Xi' M Xi and a
// reusable QP workspace, so projecting many vectors (a greedy's evaluate step) costs one
// c = (M Xi)' x, one small QP and one residual each.
class ConeProjector {
 public:
  // dimension: length of the vectors (R_hf); weights: empty (identity) or size `dimension`, >= 0.
  explicit ConeProjector(Eigen::Index dimension, const Eigen::VectorXd& weights = {},
                         const solve::QPSettings& qp = {});
  void add_generator(const Eigen::VectorXd& xi);
  Eigen::Index dimension() const { return dimension_; }
  Eigen::Index size() const { return generators_.cols(); }
  const Eigen::MatrixXd& generators() const { return generators_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  // warm_passive: a guess of the generators with c*_r > 0 (e.g. a previous result's passive set).
  ConeProjection project(const Eigen::VectorXd& x, const std::vector<int>& warm_passive = {});

 private:
  Eigen::Index dimension_;
  Eigen::VectorXd weights_;
  Eigen::MatrixXd generators_;  // Xi, dimension x R
  Eigen::MatrixXd weighted_;    // M Xi
  Eigen::MatrixXd gram_;        // Q = Xi' M Xi, exactly symmetric
  solve::NonnegativeQPSolver solver_;
};

// |lambda_p - Pi_K(lambda_p)|_M for every column of `snapshots`, K = span+{generators}.
// qp_failures (optional) receives the number of projections whose QP status was not Solved.
Eigen::VectorXd cone_projection_errors(const Eigen::MatrixXd& snapshots, const Eigen::MatrixXd& generators,
                                       const Eigen::VectorXd& weights = {}, const solve::QPSettings& qp = {},
                                       int* qp_failures = nullptr);

}  // namespace contactrb::offline
