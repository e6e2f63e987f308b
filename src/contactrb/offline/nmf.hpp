#pragma once
// Non-negative matrix factorization T ~ W H, W >= 0 (R_hf x R), H >= 0 (R x P), minimizing
// the Frobenius objective (68)-(69) by the Lee-Seung multiplicative updates (70) (paper
// Appendix A), and the dual cone built from it (span+ of the columns of W).
// Initialization (deterministic): NNDSVDa (Boutsidis & Gallopoulos 2008). For each leading
// singular triple (s_j, u_j, v_j) of T, keep the positive or the negative parts of (u_j, v_j),
// whichever pair has the larger product of norms (independent of the SVD's sign choice; the
// first pair uses |u_1|, |v_1|); zero entries, and the ranks beyond min(R_hf, P), are filled
// with the mean of T so that the multiplicative updates can move them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/offline/dual_cone.hpp"

namespace contactrb::offline {

enum class NMFStatus { Converged, MaxIterations };
const char* to_string(NMFStatus status);
NMFStatus nmf_status_from_string(const std::string& name);  // throws contactrb::Error

struct NMFSettings {
  int max_iterations = 2000;
  // Converged when the objective's relative decrease over one iteration, (f_{k-1} - f_k) / f_{k-1},
  // is <= tolerance, or when f_k <= (tolerance |T|_F)^2.
  double tolerance = 1e-7;
  // Added to the numerators and denominators of (70): H <- H (W'T + eps) / (W'WH + eps). This is
  // still the exact minimizer of a Lee-Seung majorizer, so the objective stays non-increasing; it
  // only guards 0/0.
  double epsilon = 1e-16;
};
// Throws contactrb::Error unless max_iterations >= 1, tolerance >= 0 and epsilon > 0 (finite).
void check_settings(const NMFSettings& settings);

struct NMFResult {
  NMFStatus status = NMFStatus::MaxIterations;
  Eigen::MatrixXd W;  // R_hf x R, >= 0, columns scaled to unit Euclidean norm (H rescaled; W H unchanged)
  Eigen::MatrixXd H;  // R x P, >= 0
  std::vector<double> objective;  // |T - W H|_F^2: [0] at the initialization, then after each iteration
  int iterations = 0;
  double seconds = 0.0;
};

// T: R_hf x P, finite, >= 0; 1 <= R. Throws contactrb::Error otherwise.
NMFResult nmf(const Eigen::MatrixXd& T, int R, const NMFSettings& settings = {});

// Dual cone from NMFs: for R = 1, 2, ... one separate NMF(S_DU, R) run each (the paper's
// procedure (67) takes R as input), recording errors[R] = max_mu |lambda - Pi_{span+ W_R} lambda|_Lambda;
// stops as the greedies do: tolerance on that error (settings.greedy: absolute or relative),
// max_size (a fixed R: "truncated NMF"; the runs R < max_size are still made, for the history)
// or R = min(R_hf, P) (Exhausted). generators = W of the last run, except for Exhausted: then
// the W with the smallest criterion over all ranks tried (smallest R on ties), since a larger
// rank may fit worse (errors[] still lists every rank tried; the chosen R is generators.cols()).
// Cost: one NMF per R.
// qp settings and weights serve the cone projections only: the NMF itself is in the Frobenius
// norm (69), as in the paper.
DualConeResult build_nmf_cone(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings = {},
                              const NMFSettings& nmf_settings = {});

}  // namespace contactrb::offline
