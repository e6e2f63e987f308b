#pragma once
// The reduced model: every array Algorithm 1 needs online (paper Section 4.3, (49), (54)-(55)),
// plus the contact-surface data that evaluates the EIM magic points of kappa and gamma without
// the HF mesh (DESIGN.md). Plain dense arrays stored at their largest sizes (N_max, R_max,
// Mk_max, Mg_max); the online stage uses leading sub-blocks (rbOOmit's rb_solve(N)).
//
// Nothing here has the HF size: the largest arrays have one row per kept constraint
// (R_kept, contact-surface rows) or per contact-surface DOF (n_c). The HF-size data needed to
// reconstruct u and lambda on the HF mesh live apart, in ReducedReconstruction (offline side).
//
// model/ holds these records only (header-only, below io/, which serializes them, and online/,
// which solves with them); their checks are online/model_check.hpp.
//
// Conventions (docs/offline-online.md):
//   u = u_D(mu) + Theta u_hat,  u_D(mu) = sum_k theta^lift_k(mu) lift_k,
//   lambda = Xi lambda_hat on the kept constraints (Remark 7), 0 on the dropped ones.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/cases/theta.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/model/error_estimate_data.hpp"
#include "contactrb/model/registration.hpp"

namespace contactrb::model {

// 3: N_supremizers, tolerance modes, the error estimate's arrays; 4: p parameters (the list, the
// training points p x P, theta monomials with one factor per parameter); 5: the self-describing
// layout (groups, attributes, matrices in their documented shape, docs/file-formats.md); 6: every
// string a fixed-length UTF-8 attribute (no variable-length data, which HDF5 1.10 cannot read
// safely from a damaged file); 8: the registered cone (/registration); 9: the training Jacobians;
// 10: the training sensitivities.
inline constexpr int kReducedModelFormatVersion = 10;
// ReducedModel::training_jacobian is built for N_max up to this size (its cost offline: a dense
// LU of size N_max + R_max per training point; its size: N_max^2 P).
inline constexpr int kMaxJacobianN = 100;

// The two contact boundaries in Omega (reference configuration), the only geometry online.
// Local contact nodes are the slave and master chain nodes in ascending global node index, so
// contact-surface DOF 2 i + c is global DOF contact_dofs[2 i + c] of the snapshot set.
struct ContactSurface {
  std::vector<Eigen::Vector2d> reference_nodes;  // X_i in Omega(reference), one per contact node
  std::vector<int> body;                         // 0 slave, 1 master (for the map h_body(mu))
  std::vector<int> slave;                        // slave chain, local node indices
  std::vector<int> master;                       // master chain (closed: first repeated at the end)
  contact::Discretization discretization = contact::Discretization::Collocation;
  int num_constraints = 0;  // R_hf: rows of the constraint discretization
  int num_dofs() const { return 2 * static_cast<int>(reference_nodes.size()); }  // n_c
};

// ReducedModel::dual_method of the row cone (offline/row_cone.hpp): its generators are HF rows,
// so the online stage evaluates them exactly (online::ContactRows).
inline constexpr const char* kRowCone = "rows";
// ReducedModel::dual_method of the registered cone (model/registration.hpp): the row cone's arrays
// (Xi = I on the kept rows) plus the registered generators, which the online stage maps onto
// the kept rows at each mu (lambda = Xi(mu) lambda_hat, R = registration.R()).
inline constexpr const char* kRegisteredCone = "registered";

struct ReducedModel {
  int format_version = kReducedModelFormatVersion;

  // Provenance.
  std::string case_name;
  std::string case_kind;  // "builtin" | "toml"
  std::string case_spec;  // name or TOML text
  int level = 0;
  std::vector<cases::ParameterSpec> parameters;  // names, units, domains, the geometric map data (kind, reference, body, center)
  cases::AffineThetas thetas;      // theta^a, theta^f, theta^lift (online-safe monomials)

  // Settings the model was built with (recorded, not used online except the Kacanov ones).
  std::string inner_product;  // "energy" | "h1"
  std::string dual_method;    // "cpg" | "angle" | "nmf" | "rows" (kRowCone)
  // The offline tolerances and whether each was relative (offline::OfflineSettings; format 3 for
  // the POD and EIM modes).
  double eps_pod = 0.0;
  bool eps_pod_relative = false;
  double eps_du = 0.0;
  bool eps_du_relative = false;  // eps_du divides each mu's error by |lambda(mu)| (format 2)
  double eps_eim_k = 0.0;
  bool eps_eim_k_relative = false;
  double eps_eim_g = 0.0;
  bool eps_eim_g_relative = false;
  bool compression = true;
  double kacanov_alpha = 0.3;  // the HF settings of the snapshots: the online defaults
  double kacanov_tolerance = 1e-3;
  int kacanov_max_iterations = 500;

  int N_max = 0;
  int N_supremizers = 0;  // the last N_supremizers of the N_max basis vectors are supremizers (format 3)
  int R_max = 0;
  int Mk_max = 0;
  int Mg_max = 0;
  Eigen::VectorXd singular_values;  // POD, all P values
  // The online initial guess, from the training points (OnlineSettings::initial_guess): at each
  // training point the reduced solution at the maximal sizes (u_hat, lambda_hat), or, where that
  // reduced solve did not converge, the M-orthogonal projection of u_0(mu_p) on the POD basis and
  // lambda_hat = 0.
  Eigen::MatrixXd training_mu;         // p x P: the training points, as in the snapshot set
  Eigen::MatrixXd training_u_hat;      // N_max x P
  Eigen::MatrixXd training_lambda_hat; // R_max x P (registered cone: the first registration.R() rows)
  // The online preconditioner (OnlineSettings::preconditioned): at each training point the
  // Jacobian G'(u_hat) of the reduced Kacanov map with the exact contact rows at the reduced
  // solution, block i = columns [i N_max, (i + 1) N_max). Empty: none (the EIM and registered
  // cones, N_max above kMaxJacobianN).
  Eigen::MatrixXd training_jacobian;   // N_max x (N_max P), or empty
  // The first-order online start (p > 1, with the Jacobians): at each training point the
  // derivative of the reduced solution u_hat with respect to mu, block i = columns [i p, (i + 1) p),
  // so that the start at mu is u_hat_i + S_i (mu - mu_i) (docs/offline-online.md, "Online: the
  // preconditioned iteration"). Empty: the nearest training point's u_hat.
  Eigen::MatrixXd training_u_sensitivity;  // N_max x (p P), or empty

  // (49): A_hat(mu) = sum_j theta^a_j A_hat[j];
  // f_hat(mu) = sum_j theta^f_j f_hat[j] - sum_{j,k} theta^a_j theta^lift_k A_lift_hat[j * J^D + k].
  std::vector<Eigen::MatrixXd> A_hat;       // J^a, N_max x N_max: Theta' A_j,00 Theta
  std::vector<Eigen::VectorXd> f_hat;       // J^f, N_max: Theta' f_j,0
  std::vector<Eigen::VectorXd> A_lift_hat;  // J^a J^D, N_max: Theta' (A_j lift_k)_0
  // Energy of the lift, so that 1/2 u'A u - f'u = 1/2 u_hat'A_hat u_hat - f_hat'u_hat + E_D(mu):
  // E_D = 1/2 sum_{j,k,l} theta^a_j theta^lift_k theta^lift_l lift_AA[(j J^D + k) J^D + l]
  //       - sum_{j,k} theta^f_j theta^lift_k lift_f[j J^D + k].
  std::vector<double> lift_AA;  // lift_k' A_j lift_l
  std::vector<double> lift_f;   // f_j' lift_k

  // Dual cone and compression (Remark 7).
  std::vector<int> kept_rows;  // constraint indices (0 .. R_hf-1) kept, increasing
  Eigen::MatrixXd Xi;          // R_kept x R_max, >= 0 (contact-surface rows)

  // EIM of kappa (50)-(52): magic pairs (kept-row index r_i, contact DOF n_i), B (lower
  // triangular, unit diagonal), C_j = Xi' Q_j Theta_c (55), R_max x N_max each.
  std::vector<int> kappa_row;  // index into kept_rows
  std::vector<int> kappa_dof;  // index into the contact-surface DOFs
  Eigen::MatrixXd B_kappa;     // Mk_max x Mk_max
  std::vector<Eigen::MatrixXd> C_kappa;  // Mk_max matrices
  std::vector<double> eim_kappa_errors;

  // EIM of gamma = g - K u_D(mu): magic rows; D^gamma = XiQ_gamma B_gamma^-1 (54), the inverse
  // applied online on the leading blocks.
  std::vector<int> gamma_row;  // index into kept_rows
  Eigen::MatrixXd B_gamma;     // Mg_max x Mg_max
  Eigen::MatrixXd XiQ_gamma;   // R_max x Mg_max: Xi' Q^gamma
  std::vector<double> eim_gamma_errors;

  // Contact-surface data for the magic points.
  ContactSurface surface;
  Eigen::MatrixXd Theta_c;  // n_c x N_max: Theta on the contact DOFs (zero rows where constrained)
  Eigen::MatrixXd lift_c;   // n_c x J^D: lift_k on the contact DOFs

  // The a posteriori error estimate's arrays (error_estimate.hpp; format 3).
  EstimateData estimate;

  // The registered cone's generators and support data; empty for the other cones (format 8).
  Registration registration;

  int J_a() const { return static_cast<int>(A_hat.size()); }
  int J_f() const { return static_cast<int>(f_hat.size()); }
  int J_lift() const { return static_cast<int>(lift_c.cols()); }
  int R_kept() const { return static_cast<int>(kept_rows.size()); }
  int num_parameters() const { return static_cast<int>(parameters.size()); }
  // The largest R of an online solve: R_max, or the registered generators' count.
  int online_R_max() const { return registration.empty() ? R_max : registration.R(); }
};

// Number of doubles held by the model's arrays (a size figure for the docs and tests).
inline long long model_doubles(const ReducedModel& m) {
  long long n = m.singular_values.size() + m.training_u_hat.size() + m.training_lambda_hat.size() + m.training_jacobian.size() +
                m.training_u_sensitivity.size() +
                m.training_mu.size() + m.Xi.size() + m.B_kappa.size() + m.B_gamma.size() + m.XiQ_gamma.size() +
                m.Theta_c.size() + m.lift_c.size() + static_cast<long long>(m.lift_AA.size() + m.lift_f.size()) +
                2 * static_cast<long long>(m.surface.reference_nodes.size());
  for (const auto& a : m.A_hat) n += a.size();
  for (const auto& f : m.f_hat) n += f.size();
  for (const auto& f : m.A_lift_hat) n += f.size();
  for (const auto& c : m.C_kappa) n += c.size();
  n += m.estimate.theta_a_reference.size() + m.estimate.residual_T.size() + m.estimate.Q_gamma.size() +
       m.estimate.eim_residual.size() + m.estimate.eim_slack.size();
  for (const auto& q : m.estimate.QTheta_kappa) n += q.size();
  n += m.registration.row_coordinate.size() + m.registration.grid.size() + m.registration.generators.size() +
       m.registration.points.size() + m.registration.support.size() + 2 * m.registration.point_scale.size();
  return n;
}

}  // namespace contactrb::model
