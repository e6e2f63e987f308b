#pragma once
// Settings and result record shared by the dual RB cone builders (Section 5): CPG
// (Algorithm 2, cpg.hpp), angle-greedy (angle_greedy.hpp) and NMF (Appendix A, nmf.hpp).
// The Lambda norm is |v|_Lambda^2 = sum_r w_r v_r^2 with w_r = |I_r| (L2(Gamma^c)) or w = 1.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/offline/greedy.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"

namespace contactrb::offline {

// Rows: one generator per kept constraint row (the unit vectors: every non-negative pressure on
// the rows active in training is in the cone; the rows' HF constraints hold exactly online).
// Registered: the rows' arrays plus CPG generators of the registered pressures
// (offline/registration.hpp), mapped onto the rows at each mu.
enum class DualConeMethod { CPG, AngleGreedy, NMF, Rows, Registered };
const char* to_string(DualConeMethod method);
DualConeMethod dual_cone_method_from_string(const std::string& name);  // throws contactrb::Error

struct DualConeSettings {
  // tolerance = eps_DU of (58) (absolute, or relative when greedy.relative), max_size = a fixed R
  // (-1: none). The criterion is always the cone projection error onto the cone built (CPG: its
  // own; angle-greedy: of span+ of its selection, the linear error only steers it; NMF: span+{W}).
  GreedySettings greedy;
  Eigen::VectorXd weights;  // Lambda-norm weights (size R_hf, >= 0); empty: identity
  solve::QPSettings qp;     // for the cone projections
  // Angle-greedy only: compute the true cone-projection errors (Fig. 19), which its stopping
  // test reads; their cost is reported apart (history_seconds) and not counted in `seconds`.
  // false (timing only) requires greedy.tolerance = 0.
  bool cone_history = true;
};

struct DualConeResult {
  DualConeMethod method = DualConeMethod::CPG;
  GreedyStatus status = GreedyStatus::Exhausted;
  Eigen::MatrixXd generators;  // R_hf x R, entries >= 0 (greedies: the selected snapshots themselves)
  std::vector<int> selected;   // greedies: snapshot indices in selection order; rows: row_cone.hpp; NMF: empty
  // errors[R] = max_mu |lambda(mu) - Pi_{K_R}(lambda(mu))|_Lambda for R = 0 .. (R of the generators),
  // K_R the cone of the first R selected snapshots (greedies) or of an NMF of rank R;
  // errors[0] = max_mu |lambda(mu)|_Lambda. Angle-greedy: filled only when cone_history. NMF:
  // every rank tried, which may go beyond the R kept (an exhausted NMF keeps its best rank):
  // the error of the cone returned is errors[generators.cols()].
  std::vector<double> errors;
  std::vector<double> relative_errors;  // same, each mu's error divided by |lambda(mu)|_Lambda
  std::vector<double> linear_errors;    // angle-greedy: its steering linear-projection errors; else empty
  double seconds = 0.0;          // time of the algorithm proper (NMF: the factorizations)
  double history_seconds = 0.0;  // angle-greedy: the true cone errors; NMF: the cone projections
  int qp_failures = 0;                  // cone projections whose QP was not Solved (0 expected)
};

// Checks the snapshot matrix (R_hf x P, finite, entries >= 0 up to -0) and the weights; throws
// contactrb::Error naming the argument and the sizes.
void check_dual_snapshots(const char* who, const Eigen::MatrixXd& snapshots, const Eigen::VectorXd& weights);

}  // namespace contactrb::offline
