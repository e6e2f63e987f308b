#include "contactrb/rb/pod.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::rb {

namespace {

std::string dims(Eigen::Index r, Eigen::Index c) { return std::to_string(r) + "x" + std::to_string(c); }

// Method of snapshots given S, MS = M S (identity: MS = S) and v -> M v.
template <class ApplyM>
PODResult pod_impl(const Eigen::MatrixXd& S, const Eigen::MatrixXd& MS, const PODSettings& settings,
                   const ApplyM& apply_M) {
  const auto t0 = std::chrono::steady_clock::now();
  PODResult result;
  const Eigen::Index P = S.cols();
  // Correlation matrix C = S' M S (P x P), symmetrized against round-off.
  Eigen::MatrixXd C = S.transpose() * MS;
  C = 0.5 * (C + C.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(C);
  require(eig.info() == Eigen::Success, "pod: the eigen-decomposition of the correlation matrix failed");
  // Eigen sorts ascending: reverse to decreasing order.
  const Eigen::VectorXd values = eig.eigenvalues().reverse();
  const Eigen::MatrixXd vectors = eig.eigenvectors().rowwise().reverse();
  result.singular_values = values.cwiseMax(0.0).cwiseSqrt();
  const double largest = P > 0 ? values(0) : 0.0;
  int rank = 0;
  while (rank < P && values(rank) > 0.0 && values(rank) > settings.rank_tolerance * largest) ++rank;
  result.rank = rank;

  int N = 0;
  const Eigen::VectorXd& sigma = result.singular_values;
  if (settings.max_modes >= 0) {
    N = std::min(settings.max_modes, rank);
  } else if (settings.truncation == PODTruncation::SingularValue) {
    while (N < rank && sigma(N) > settings.tolerance) ++N;
  } else {
    // Smallest N with sqrt(sum_{i>=N} sigma_i^2) <= tolerance (tail sums from the end).
    double tail = 0.0;
    N = static_cast<int>(P);
    for (Eigen::Index i = P - 1; i >= 0; --i) {
      if (std::sqrt(tail + sigma(i) * sigma(i)) > settings.tolerance) break;
      tail += sigma(i) * sigma(i);
      N = static_cast<int>(i);
    }
    N = std::min(N, rank);
  }
  result.N = N;
  result.discarded_energy = sigma.tail(P - N).squaredNorm();

  // Modes phi_i = S v_i / sigma_i, then two Cholesky re-orthonormalizations ("CholQR2")
  // Phi <- Phi L^-T with Phi' M Phi = L L' (L lower triangular, so span{phi_1..phi_k} is kept for
  // every k): restores the M-orthonormality lost to round-off in modes of small singular value.
  Eigen::MatrixXd basis = S * vectors.leftCols(N);
  for (int i = 0; i < N; ++i) basis.col(i) /= sigma(i);
  for (int pass = 0; pass < 2 && N > 0; ++pass) {
    const Eigen::MatrixXd Mbasis = apply_M(basis);
    Eigen::MatrixXd G = basis.transpose() * Mbasis;
    G = 0.5 * (G + G.transpose()).eval();
    Eigen::LLT<Eigen::MatrixXd> llt(G);
    if (llt.info() != Eigen::Success) break;
    const Eigen::MatrixXd Lt = llt.matrixU();
    basis = Lt.triangularView<Eigen::Upper>().solve<Eigen::OnTheRight>(basis);
  }
  result.basis = std::move(basis);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace

void check_settings(const PODSettings& s) {
  require(std::isfinite(s.tolerance) && s.tolerance >= 0.0,
          "pod: tolerance (eps_POD) must be finite and >= 0, got " + std::to_string(s.tolerance));
  require(s.max_modes >= -1, "pod: max_modes must be >= -1 (-1: truncate by tolerance), got " +
                                 std::to_string(s.max_modes));
  require(std::isfinite(s.rank_tolerance) && s.rank_tolerance >= 0.0 && s.rank_tolerance < 1.0,
          "pod: rank_tolerance must lie in [0, 1), got " + std::to_string(s.rank_tolerance));
}

PODResult pod(const Eigen::MatrixXd& snapshots, const Eigen::SparseMatrix<double>& M, const PODSettings& settings) {
  check_settings(settings);
  require(M.rows() == snapshots.rows() && M.cols() == snapshots.rows(),
          "pod: the inner-product matrix M is " + dims(M.rows(), M.cols()) + " but the snapshots are " +
              dims(snapshots.rows(), snapshots.cols()) + " (M must be N_hf x N_hf)");
  require(snapshots.allFinite(), "pod: the snapshots have non-finite entries");
  const Eigen::MatrixXd MS = M * snapshots;
  return pod_impl(snapshots, MS, settings, [&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(M * X); });
}

PODResult pod(const Eigen::MatrixXd& snapshots, const PODSettings& settings) {
  check_settings(settings);
  require(snapshots.allFinite(), "pod: the snapshots have non-finite entries");
  return pod_impl(snapshots, snapshots, settings, [](const Eigen::MatrixXd& X) { return X; });
}

}  // namespace contactrb::rb
