#include "contactrb/offline/pod.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

namespace {

std::string dims(Eigen::Index r, Eigen::Index c) { return std::to_string(r) + "x" + std::to_string(c); }

// The singular values and leading left singular vectors of a matrix B: for a tall B, those of
// the R factor of B = Q R, the vectors mapped back by Q.
class ThinSVD {
 public:
  // B is overwritten by its QR factor (no copy of an n_free x P matrix).
  explicit ThinSVD(Eigen::MatrixXd&& B) : factor_(std::move(B)) {
    if (factor_.rows() <= factor_.cols()) {
      direct_.compute(factor_, Eigen::ComputeThinU);
      singular_values = direct_.singularValues();
      return;
    }
    qr_.emplace(factor_);
    const Eigen::MatrixXd R = qr_->matrixQR().topRows(factor_.cols()).triangularView<Eigen::Upper>();
    small_.compute(R, Eigen::ComputeFullU);
    singular_values = small_.singularValues();
  }
  Eigen::MatrixXd left_vectors(Eigen::Index n) const {
    if (!qr_) return direct_.matrixU().leftCols(n);
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(factor_.rows(), n);
    U.topRows(small_.rows()) = small_.matrixU().leftCols(n);
    U.applyOnTheLeft(qr_->householderQ());
    return U;
  }
  ThinSVD(const ThinSVD&) = delete;
  ThinSVD& operator=(const ThinSVD&) = delete;
  Eigen::VectorXd singular_values;

 private:
  Eigen::MatrixXd factor_;
  std::optional<Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>>> qr_;  // in place in factor_
  Eigen::JacobiSVD<Eigen::MatrixXd> direct_, small_;
};

// One Cholesky re-orthonormalization Phi <- Phi L^-T with Phi' M Phi = L L' (L lower
// triangular, so span{phi_1..phi_k} is kept for every k): removes the round-off of the modes'
// construction (about 1e-16 cond(W) for W^-1) from the M-orthonormality. MPhi = M Phi.
void reorthonormalize(Eigen::MatrixXd& Phi, const Eigen::MatrixXd& MPhi) {
  if (Phi.cols() == 0) return;
  Eigen::MatrixXd G = Phi.transpose() * MPhi;
  G = 0.5 * (G + G.transpose()).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(G);
  if (llt.info() != Eigen::Success) return;
  const Eigen::MatrixXd Lt = llt.matrixU();
  Phi = Lt.triangularView<Eigen::Upper>().solve<Eigen::OnTheRight>(Phi);
}

// Truncation, given the singular values sigma (decreasing) and the numerical rank.
int truncated_size(const Eigen::VectorXd& sigma, int rank, const PODSettings& settings, double& threshold) {
  const Eigen::Index P = sigma.size();
  if (settings.max_modes >= 0) {
    threshold = 0.0;
    return std::min(settings.max_modes, rank);
  }
  int N = 0;
  if (settings.truncation == PODTruncation::SingularValue) {
    threshold = settings.relative ? settings.tolerance * (P > 0 ? sigma(0) : 0.0) : settings.tolerance;
    while (N < rank && sigma(N) > threshold) ++N;
    return N;
  }
  threshold = settings.relative ? settings.tolerance * sigma.norm() : settings.tolerance;
  // Smallest N with sqrt(sum_{i>=N} sigma_i^2) <= threshold (tail sums from the end).
  double tail = 0.0;
  N = static_cast<int>(P);
  for (Eigen::Index i = P - 1; i >= 0; --i) {
    if (std::sqrt(tail + sigma(i) * sigma(i)) > threshold) break;
    tail += sigma(i) * sigma(i);
    N = static_cast<int>(i);
  }
  return std::min(N, rank);
}

// POD from the weighted snapshots B = W S (W' W = M, W = L' P for a Cholesky factor, W = I for
// the Euclidean product): B = U Sigma V' (thin SVD), phi_i = W^-1 u_i. Then |B x| = |S x|_M,
// so Sigma are the M-singular values of S and Phi' M Phi = U' U = I.
// to_modes(U_N) = W^-1 U_N; apply_M(X) = M X (for the re-orthonormalization).
template <class ToModes, class ApplyM>
PODResult pod_impl(Eigen::MatrixXd B, const PODSettings& settings, const ToModes& to_modes,
                   const ApplyM& apply_M) {
  const auto t0 = std::chrono::steady_clock::now();
  PODResult result;
  const Eigen::Index P = B.cols();
  // B = Q R (blocked Householder, backward stable), then two-sided Jacobi on the P x P R:
  // singular values accurate to about 1e-16 sigma_1, the small ones included (the correlation
  // matrix S' M S would square the condition number and lose them below about 1e-8 sigma_1).
  // JacobiSVD on B itself does the same with an unblocked pivoted QR, 5-10 times slower for
  // P in the hundreds.
  const ThinSVD svd(std::move(B));
  const Eigen::VectorXd& sv = svd.singular_values;
  result.singular_values = Eigen::VectorXd::Zero(P);
  result.singular_values.head(sv.size()) = sv;
  const Eigen::VectorXd& sigma = result.singular_values;
  const double largest = P > 0 ? sigma(0) : 0.0;
  int rank = 0;
  while (rank < sv.size() && sigma(rank) > 0.0 && sigma(rank) > settings.rank_tolerance * largest) ++rank;
  result.rank = rank;
  const int N = truncated_size(sigma, rank, settings, result.threshold);
  result.N = N;
  result.discarded_energy = sigma.tail(P - N).squaredNorm();

  if (settings.basis) {
    Eigen::MatrixXd basis = to_modes(svd.left_vectors(N));
    reorthonormalize(basis, apply_M(basis));
    result.basis = std::move(basis);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace

void check_settings(const PODSettings& s) {
  require(std::isfinite(s.tolerance) && s.tolerance >= 0.0,
          "pod: tolerance (eps_POD) must be finite and >= 0, got " + number_text(s.tolerance));
  require(s.max_modes >= -1, "pod: max_modes must be >= -1 (-1: truncate by tolerance), got " +
                                 std::to_string(s.max_modes));
  require(std::isfinite(s.rank_tolerance) && s.rank_tolerance >= 0.0 && s.rank_tolerance < 1.0,
          "pod: rank_tolerance must lie in [0, 1), got " + number_text(s.rank_tolerance));
}

// P M P' = L L' (AMD ordering), so u' M u = |L' P u|^2: W = L' P.
struct PODWeight::Impl {
  explicit Impl(const Eigen::SparseMatrix<double>& matrix) : M(matrix), llt(matrix) {}
  Eigen::SparseMatrix<double> M;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt;
};

PODWeight::PODWeight(const Eigen::SparseMatrix<double>& M) : impl_(std::make_unique<Impl>(M)) {
  require(impl_->llt.info() == Eigen::Success, "pod: the inner-product matrix M is not symmetric positive definite");
}
PODWeight::~PODWeight() = default;

PODResult pod(const Eigen::MatrixXd& snapshots, const Eigen::SparseMatrix<double>& M, const PODSettings& settings) {
  check_settings(settings);
  require(M.rows() == snapshots.rows() && M.cols() == snapshots.rows(),
          "pod: the inner-product matrix M is " + dims(M.rows(), M.cols()) + " but the snapshots are " +
              dims(snapshots.rows(), snapshots.cols()) + " (M must be N_hf x N_hf)");
  require(snapshots.allFinite(), "pod: the snapshots have non-finite entries");
  return pod(snapshots, PODWeight(M), settings);
}

PODResult pod(const Eigen::MatrixXd& snapshots, const PODWeight& weight, const PODSettings& settings) {
  check_settings(settings);
  const Eigen::SparseMatrix<double>& M = weight.impl().M;
  const auto& llt = weight.impl().llt;
  require(M.rows() == snapshots.rows(), "pod: the inner-product matrix M is " + dims(M.rows(), M.cols()) +
                                            " but the snapshots are " + dims(snapshots.rows(), snapshots.cols()) +
                                            " (M must be N_hf x N_hf)");
  require(snapshots.allFinite(), "pod: the snapshots have non-finite entries");
  Eigen::MatrixXd B = llt.permutationP() * snapshots;
  B = llt.matrixU() * B;
  const auto to_modes = [&](const Eigen::MatrixXd& U) {
    const Eigen::MatrixXd X = llt.matrixU().solve(U);  // L' X = U
    return Eigen::MatrixXd(llt.permutationPinv() * X);
  };
  return pod_impl(std::move(B), settings, to_modes, [&](const Eigen::MatrixXd& X) { return Eigen::MatrixXd(M * X); });
}

PODResult pod_by_correlation(const Eigen::MatrixXd& snapshots, const Eigen::SparseMatrix<double>& M,
                             const PODSettings& settings) {
  check_settings(settings);
  require(M.rows() == snapshots.rows() && M.cols() == snapshots.rows(),
          "pod: the inner-product matrix M is " + dims(M.rows(), M.cols()) + " but the snapshots are " +
              dims(snapshots.rows(), snapshots.cols()) + " (M must be N_hf x N_hf)");
  require(snapshots.allFinite(), "pod: the snapshots have non-finite entries");
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index P = snapshots.cols();
  constexpr Eigen::Index kBlock = 64;
  Eigen::MatrixXd G(P, P);
  for (Eigen::Index b = 0; b < P; b += kBlock) {
    const Eigen::Index nb = std::min(kBlock, P - b);
    const Eigen::MatrixXd MS = M * snapshots.middleCols(b, nb);
    G.middleCols(b, nb) = snapshots.transpose() * MS;
  }
  G = 0.5 * (G + G.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  require(eig.info() == Eigen::Success, "pod: the correlation matrix's eigenvalue problem did not converge");
  PODResult result;
  result.singular_values.resize(P);
  Eigen::MatrixXd V(P, P);  // decreasing order
  for (Eigen::Index i = 0; i < P; ++i) {
    result.singular_values(i) = std::sqrt(std::max(0.0, eig.eigenvalues()(P - 1 - i)));
    V.col(i) = eig.eigenvectors().col(P - 1 - i);
  }
  const Eigen::VectorXd& sigma = result.singular_values;
  const double largest = P > 0 ? sigma(0) : 0.0;
  const double rank_tolerance = std::max(settings.rank_tolerance, kCorrelationRankTolerance);
  int rank = 0;
  while (rank < P && sigma(rank) > 0.0 && sigma(rank) > rank_tolerance * largest) ++rank;
  result.rank = rank;
  const int N = truncated_size(sigma, rank, settings, result.threshold);
  result.N = N;
  result.discarded_energy = sigma.tail(P - N).squaredNorm();
  // phi_i = S v_i / sigma_i.
  Eigen::MatrixXd basis = snapshots * (V.leftCols(N) * sigma.head(N).cwiseInverse().asDiagonal());
  reorthonormalize(basis, M * basis);
  result.basis = std::move(basis);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

PODResult pod(const Eigen::MatrixXd& snapshots, const PODSettings& settings) {
  check_settings(settings);
  require(snapshots.allFinite(), "pod: the snapshots have non-finite entries");
  return pod_impl(
      Eigen::MatrixXd(snapshots), settings, [](const Eigen::MatrixXd& U) { return U; }, [](const Eigen::MatrixXd& X) { return X; });
}

const char* to_string(PODTruncation value) {
  switch (value) {
    case PODTruncation::SingularValue: return "singular-value";
    case PODTruncation::ProjectionError: return "projection-error";
  }
  return "unknown";
}

PODTruncation pod_truncation_from_string(const std::string& name) {
  using enum PODTruncation;
  return enum_from_string(name, "POD truncation", std::array{SingularValue, ProjectionError});
}

}  // namespace contactrb::offline
