#pragma once
// Proper orthogonal decomposition (paper Section 5, task (T2); singular values as in Figs. 11
// and 19, truncation as in Table 4) in the inner product (u, v)_M = u' M v with M sparse SPD
// (energy or H1 Gram matrix) or the identity. Computed by a thin SVD of the weighted
// snapshots L' P S (M = P' L L' P, sparse Cholesky), not by the method of snapshots: the
// eigenvalues of S' M S lose every singular value below about 1e-8 sigma_1 to round-off,
// the SVD keeps them down to about 1e-15 sigma_1 (tests/offline/test_pod.cpp).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

namespace contactrb::offline {

enum class PODTruncation {
  // Keep every mode with sigma_i > threshold (our reading of the paper's eps_POD).
  SingularValue,
  // Keep the fewest modes such that the discarded energy sqrt(sum_{i>N} sigma_i^2) <= threshold
  // (= the Frobenius M-norm of the snapshots' projection error).
  ProjectionError
};
const char* to_string(PODTruncation value);  // "singular-value" | "projection-error"
PODTruncation pod_truncation_from_string(const std::string& name);  // throws contactrb::Error

struct PODSettings {
  // eps_POD. Absolute (relative = false): the threshold is the tolerance itself, in the units
  // of the M-norm of a snapshot. Relative: the threshold is tolerance * sigma_1 (SingularValue:
  // keep sigma_i / sigma_1 > tolerance) or tolerance * sqrt(sum_i sigma_i^2) (ProjectionError:
  // the discarded energy relative to the total), invariant under a scaling of the snapshots or M.
  double tolerance = 1e-2;
  bool relative = false;
  PODTruncation truncation = PODTruncation::SingularValue;
  // >= 0: fixed N = min(max_modes, numerical rank), the tolerance is then ignored; -1: by tolerance.
  int max_modes = -1;
  // Singular values <= rank_tolerance * sigma_1 are round-off (the SVD's accuracy is about
  // 1e-16 sigma_1 times a small factor): those modes are never kept (numerical rank).
  double rank_tolerance = 1e-13;
  // false: the singular values, rank, N, threshold and discarded energy only, the basis left
  // empty (the N_hf x N modes and their re-orthonormalization not computed), for a caller whose
  // basis comes from elsewhere (a greedy's extended basis, offline_builder.hpp).
  bool basis = true;
};
// Throws contactrb::Error for a negative or non-finite tolerance, max_modes < -1 or a bad rank_tolerance.
void check_settings(const PODSettings& settings);

struct PODResult {
  Eigen::MatrixXd basis;            // N_hf x N, M-orthonormal, modes by decreasing singular value
  Eigen::VectorXd singular_values;  // all P singular values, decreasing (zeros beyond N_hf)
  int N = 0;                        // modes kept
  int rank = 0;                     // numerical rank (singular values above rank_tolerance * sigma_1)
  double threshold = 0.0;           // the absolute threshold the truncation used (see PODSettings)
  double discarded_energy = 0.0;    // sum_{i>N} sigma_i^2 = sum_p |s_p - Pi_N s_p|_M^2 (exact arithmetic)
  double seconds = 0.0;
};

// snapshots: N_hf x P (one snapshot per column); M: N_hf x N_hf sparse SPD (only M * vector is used).
PODResult pod(const Eigen::MatrixXd& snapshots, const Eigen::SparseMatrix<double>& M,
              const PODSettings& settings = {});

// The weight of the M-product, P M P' = L L' (W = L' P, W'W = M), factored once for several PODs
// on one M (a greedy's builds): pod(S, weight) is pod(S, M) bitwise.
class PODWeight {
 public:
  // Throws contactrb::Error when M is not symmetric positive definite.
  explicit PODWeight(const Eigen::SparseMatrix<double>& M);
  ~PODWeight();
  PODWeight(const PODWeight&) = delete;
  PODWeight& operator=(const PODWeight&) = delete;
  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};
PODResult pod(const Eigen::MatrixXd& snapshots, const PODWeight& weight, const PODSettings& settings = {});
// Euclidean inner product (M = identity).
PODResult pod(const Eigen::MatrixXd& snapshots, const PODSettings& settings = {});

// The method of snapshots: the eigenvalues of the correlation matrix S' M S, formed a block of
// columns at a time, so no second N_hf x P matrix is made (pod() makes two: W S and its QR).
// The singular values are accurate to about 1e-8 sigma_1 only (the square root of round-off), so
// the numerical rank is taken at kCorrelationRankTolerance: for truncations well above it (the
// registered supremizers' 1e-3 of offline_builder.cpp, P in the hundreds on meshes of 1e6 DOFs).
inline constexpr double kCorrelationRankTolerance = 1e-7;
PODResult pod_by_correlation(const Eigen::MatrixXd& snapshots, const Eigen::SparseMatrix<double>& M,
                             const PODSettings& settings = {});

}  // namespace contactrb::offline
