#pragma once
// Proper orthogonal decomposition by the method of snapshots (paper Section 5, task (T2);
// singular values as in Figs. 11 and 19, truncation as in Table 4), in the inner product
// (u, v)_M = u' M v with M sparse SPD (energy or H1 Gram matrix) or the identity.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace contactrb::rb {

enum class PODTruncation {
  // Keep every mode with sigma_i > tolerance (absolute threshold on the singular values;
  // the default, our reading of the paper's eps_POD).
  SingularValue,
  // Keep the fewest modes such that the discarded energy sqrt(sum_{i>N} sigma_i^2) <= tolerance
  // (= the Frobenius M-norm of the snapshots' projection error).
  ProjectionError
};

struct PODSettings {
  double tolerance = 1e-2;  // eps_POD (absolute, in the units of the M-norm of a snapshot)
  PODTruncation truncation = PODTruncation::SingularValue;
  // >= 0: fixed N = min(max_modes, numerical rank), the tolerance is then ignored; -1: by tolerance.
  int max_modes = -1;
  // Eigenvalues of the correlation matrix <= rank_tolerance * (largest eigenvalue) are round-off:
  // those modes are never kept (numerical rank). 1e-13 on eigenvalues ~ 3e-7 on sigma_i / sigma_1.
  double rank_tolerance = 1e-13;
};
// Throws contactrb::Error for a negative or non-finite tolerance, max_modes < -1 or a bad rank_tolerance.
void check_settings(const PODSettings& settings);

struct PODResult {
  Eigen::MatrixXd basis;            // N_hf x N, M-orthonormal, modes by decreasing singular value
  Eigen::VectorXd singular_values;  // all P values sigma_i = sqrt(max(eig_i, 0)), decreasing
  int N = 0;                        // modes kept
  int rank = 0;                     // numerical rank (eigenvalues above rank_tolerance)
  double discarded_energy = 0.0;    // sum_{i>N} sigma_i^2 = sum_p |s_p - Pi_N s_p|_M^2 (exact arithmetic)
  double seconds = 0.0;
};

// snapshots: N_hf x P (one snapshot per column); M: N_hf x N_hf sparse SPD (only M * vector is used).
PODResult pod(const Eigen::MatrixXd& snapshots, const Eigen::SparseMatrix<double>& M,
              const PODSettings& settings = {});
// Euclidean inner product (M = identity).
PODResult pod(const Eigen::MatrixXd& snapshots, const PODSettings& settings = {});

}  // namespace contactrb::rb
