#pragma once
// A posteriori error estimate of an online answer, from reduced quantities only, in the spirit
// of Haasdonk, Salomon, Wohlmuth (SINUM 2012) for variational inequalities: the dual norm of
// the primal residual (Riesz representers of the affine terms, offline), the constraint
// violation and the complementarity of the EIM-reconstructed constraints on the kept rows,
// combined into an estimate of the energy-norm error |u_hf - u_rb|_A(mu). Formulas, and which
// parts are bounded and which are estimated: docs/offline-online.md, "Error estimate".
//
// Offline (build_estimate_data): the residual terms on the free DOFs, whitened by the Cholesky
// factor of X = A_00(mu_ref), then one column-pivoted QR: ||r||_{X'} = |T y| with T the R factor
// (Buhr, Engwer, Ohlberger, Rave 2014: no sum of large terms of opposite signs online, so the
// accuracy floor is that of T y, about 1e-15 |T| |y|, not the square root of it).
// Online: ErrorEstimator (online/error_estimator.hpp).
#include <Eigen/Core>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <vector>

#include "contactrb/cases/theta.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/model/error_estimate_data.hpp"
#include "contactrb/online/error_estimator.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::cases {
struct AffineTerms;
}

namespace contactrb::offline {

// Inputs of the offline construction (all borrowed).
struct EstimateInputs {
  const cases::AffineTerms* terms = nullptr;  // global A_j, f_j, lift_k of the reference mesh
  const cases::AffineThetas* thetas = nullptr;
  Eigen::VectorXd reference_mu;               // X = A_00(reference_mu)
  const std::vector<int>* free_dofs = nullptr;
  const std::vector<int>* contact_dofs = nullptr;  // global DOF of each contact-surface DOF
  const Eigen::MatrixXd* Theta = nullptr;          // n_free x N_max
  const Eigen::MatrixXd* Theta_c = nullptr;        // n_c x N_max
  const Eigen::MatrixXd* Xi = nullptr;             // R_kept x R_max
  const Eigen::MatrixXd* Q_kappa = nullptr;        // (R_kept n_c) x Mk_max, flattened row-major (eim_flatten.hpp)
  const Eigen::MatrixXd* Q_gamma = nullptr;        // R_kept x Mg_max
  // The EIM calibration on the training snapshots: magic points (flattened rows of the kappa
  // snapshot matrix, rows of gamma's), B matrices, the kept rows, the lift on the contact DOFs,
  // the row weights |I_r| on the kept rows.
  const io::SnapshotSet* set = nullptr;
  const std::vector<int>* kept_rows = nullptr;
  const Eigen::MatrixXd* lift_c = nullptr;         // n_c x J^D
  const Eigen::VectorXd* weights_kept = nullptr;   // R_kept
  const std::vector<int>* kappa_magic = nullptr;   // Mk_max
  const Eigen::MatrixXd* B_kappa = nullptr;
  const std::vector<int>* gamma_magic = nullptr;   // Mg_max
  const Eigen::MatrixXd* B_gamma = nullptr;
  const model::ContactSurface* surface = nullptr;  // its chains give the margin of exact_dofs
  // The basis-free parts, shared by successive builds (nullptr, or not built yet: built here).
  struct EstimateBase* base = nullptr;
  // Extension builds (OfflineSettings::extend_basis): Theta's column n is basis vector
  // extension_order[n] in the order the basis grew, of which the first extension_reused are those
  // of the base's previous build: their split columns are kept and the new ones appended (a QR
  // update), and the residual factor is left unpivoted. nullptr: the whole basis block is factored.
  const std::vector<int>* extension_order = nullptr;
  int extension_reused = 0;
};

// The parts of the estimate's offline data that depend on the problem only, not on the bases:
// X = A_00(reference_mu) factored, and the whitened load, lift and contact-DOF columns
// L^-1 P [f_j | -A_j u_D,k] and L^-1 P E_c'.
//
// X is factored with the contact DOFs `contact_columns` eliminated last (the others in AMD
// order), so that L^-1 P E_c' = [0; L_cc^-1] with L_cc the trailing n_u x n_u block of L: the
// whitened contact columns take n_u^2 numbers, not n_free n_u (hertz-a level 6: 2 200 contact
// columns, 5.5 GB as dense n_free-columns). With the rows split into the interior (first n_i)
// and the contact (last n_u) ones,
//     [W_fixed | W_contact] = blockdiag(Q_i, Q_c) R_fixed,
//     R_fixed = [[Q_c' W_fixed,contact, R_c], [R_i, 0]]   ((n_u + n_fixed) x (n_fixed + n_u))
// with L_cc^-1 = Q_c R_c and W_fixed,interior = Q_i R_i (Householder): an orthonormal row frame,
// so |W y| = |R_fixed y| for every y.
struct EstimateBase {
  bool factored = false;       // global_to_free
  bool columns_built = false;  // the factor and the rest
  std::vector<Eigen::Index> global_to_free;  // -1 on a Dirichlet DOF
  // P X P' = L L', P the contact_columns last (in their order), the other free DOFs before them.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> llt;
  int n_fixed = 0;  // J^f + J^a J^D
  // The free contact DOFs (indices into contact_dofs, ascending) whose unit loads the estimate
  // uses: the exact rows' DOFs and the support of the EIM contact columns, over the builds so far.
  std::vector<Eigen::Index> contact_columns;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_interior;  // of W_fixed's interior rows
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_contact;   // of L_cc^-1
  Eigen::MatrixXd R_fixed;
  // Extension builds: with Z = H' L^-1 P (-A_j,00 theta_i) for the first `extended` basis vectors
  // in growth order (column J^a i + j), its rows in R_fixed's frame (Z_fixed, R_fixed.rows() rows:
  // all the residual factor reads of them) and the thin QR of its rows below, Q_t R_t (Q_t
  // orthonormal, its first q_t columns used: the rest is room to grow without copying; R_t gains
  // a row only for a column that leaves Q_t's span). Reset when the fixed columns are refactored.
  Eigen::MatrixXd Z_fixed, Q_t, R_t;
  Eigen::Index q_t = 0;
  int extended = 0;
  // Chain nodes of margin around the needed contact DOFs when the fixed columns are factored again
  // for a later build (ensure_estimate_base): doubled at each such refactor.
  int pad_nodes = 0;
};

// Throws contactrb::Error for inconsistent sizes or an X that is not positive definite.
model::EstimateData build_estimate_data(const EstimateInputs& in);

}  // namespace contactrb::offline
