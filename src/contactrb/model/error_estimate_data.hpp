#pragma once
// The reduced-size arrays of the a posteriori error estimate (docs/offline-online.md, "Error
// estimate"), stored in the ReducedModel (field `estimate`) and in the model file; built by
// build_estimate_data (offline/error_estimate.hpp), evaluated online by ErrorEstimator
// (online/error_estimator.hpp).
//
// Column layout of residual_T (the affine terms of the primal residual, (49) and the contact
// term, in this order; d_max = J^f + J^a J^D + J^a N_max + Mk_max R_max columns):
//   [ f_j,0 (j < J^f) | -(A_j lift_k)_0 (j, k) | -A_j,00 Theta_n (j, n < N_max) |
//     -E_c' Q_i' Xi_r (i < Mk_max, r < R_max) ]
// with coefficients theta^f_j; theta^a_j theta^lift_k; theta^a_j u_hat_n; phi_i lambda_hat_r.
#include <Eigen/Core>
#include <vector>

namespace contactrb::model {

// Columns of the column-pivoted QR whose pivot is below this fraction of the largest are dropped
// (their contribution to |T y| is below the rounding of the kept ones). Offline (the whole
// residual_T) and online (the columns of the leading sizes) alike.
inline constexpr double kEstimateRankTolerance = 1e-13;

// Number of columns of residual_T for the given sizes (the layout above).
inline Eigen::Index residual_columns(int Jf, int Ja, int JD, int N, int Mk, int R) {
  return static_cast<Eigen::Index>(Jf + Ja * JD + Ja * N) + static_cast<Eigen::Index>(Mk) * R;
}

struct EstimateData {
  // X = A_00(mu_ref): the energy product at the reference value (whatever the POD product).
  // theta^a_j(mu_ref), for the coercivity bound alpha(mu) = min_j theta^a_j(mu) / theta^a_j(mu_ref).
  Eigen::VectorXd theta_a_reference;
  // rho x d_max: ||r||_{X'} = |residual_T y| for every coefficient vector y (the R factor of the
  // column-pivoted QR of L^-1 [terms], X = L L', rows below the rank tolerance dropped).
  Eigen::MatrixXd residual_T;
  // EIM reconstructions on the kept rows: K Theta_c ~ sum_i phi_i QTheta_kappa[i] (R_kept x N_max
  // each, Mk_max matrices); gamma ~ Q_gamma phi^gamma (R_kept x Mg_max).
  std::vector<Eigen::MatrixXd> QTheta_kappa;
  Eigen::MatrixXd Q_gamma;
  // The EIM errors, measured offline on the training snapshots (estimated, not bounded online):
  // eim_residual(M) = max_p ||E_c' (K_p - I_M K_p)' lambda_p||_{X'} / ||lambda_p||_Lambda, M = 0..Mk_max;
  // eim_slack(M, M') = max_p ((delta s_p)^-)' lambda_p / ||lambda_p||_Lambda, with the slack error
  // delta s_p = (gamma_p - I_M' gamma_p) - (K_p - I_M K_p) u_0,c(mu_p).
  Eigen::VectorXd eim_residual;  // Mk_max + 1
  Eigen::MatrixXd eim_slack;     // (Mk_max + 1) x (Mg_max + 1)

  // The estimate with the exact contact rows (online::ContactRows::Exact): the contact term of
  // the residual is -E_c' K(w)' Xi lambda_hat, a load on the contact-surface DOFs, so its columns
  // are the unit loads E_c' e_a on the contact DOFs a of exact_dofs: rho' x d_exact with
  // d_exact = J^f + J^a J^D + J^a N_max + |exact_dofs| columns [ affine terms as above | e_a ],
  // coefficients [ as above | -(K' Xi lambda_hat)_a ]. exact_dofs: the free contact-surface DOFs
  // (indices into the n_c contact DOFs, increasing) that the kept rows touch in training, with a
  // margin of kExactDofMargin chain nodes each side; a load outside them makes the estimate
  // unavailable (not silently smaller).
  Eigen::MatrixXd residual_exact;
  std::vector<int> exact_dofs;
  // eta: the geometric term of the exact-rows estimate, max over the training snapshots of
  // -v'Hv / v'A(mu)v on the directions that keep the active rows closed
  // (offline/geometric_term.hpp); 0 when not computed (models without the row cone).
  double geometric_ratio = 0.0;
};

// Contact-chain nodes added on each side of the nodes the kept rows touch in training.
inline constexpr int kExactDofMargin = 2;

inline Eigen::Index exact_residual_columns(int Jf, int Ja, int JD, int N, int n_exact) {
  return static_cast<Eigen::Index>(Jf + Ja * JD + Ja * N) + n_exact;
}

}  // namespace contactrb::model
