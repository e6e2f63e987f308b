#pragma once
// The online stage (Evaluation, in rbOOmit's terms): paper Algorithm 1, the reduced Kacanov
// iteration on (53). Per mu: A_hat(mu), f_hat(mu) from (49); per iteration: kappa_hat and
// gamma_hat at the EIM magic points from the contact-surface data only (the chain nodes mapped
// to Omega(mu), the displacement u_D,c(mu) + Theta_c u_hat on the contact DOFs), D^kappa (54),
// the reduced non-negative QP in dual form, u_hat = A_hat^-1 (f_hat - D' lambda_hat).
// Nothing of HF size is touched. Sizes N <= N_max, R <= R_max, Mk <= Mk_max, Mg <= Mg_max use
// the leading sub-blocks of the model's arrays.
//
// Magic-point evaluation: collocation and LAC-Simpson rows are weighted sums of pointwise rows
// of a few slave nodes, so only the slave nodes under the magic rows are projected (the
// "restricted operator", online_magic.hpp; the deformed master chain positions are still
// computed whole, O(master nodes)). Exactly integrated LAC rows integrate over their
// macro-segment against the deformed master: only the slave nodes of the magic rows'
// macro-segments are projected and only those rows are integrated
// (contact::integrate_lac_rows with a row list), then the magic entries are picked
// (docs/offline-online.md).
//
// Cost per query (docs/performance.md, "Online query"): A_hat(mu) and its factor A_hat = L L' once
// (affine_whitening.hpp: a simultaneous diagonalization of at most two terms, or Cholesky); per
// step the magic points, D' (N x R) assembled and solved against A (exact rows: E = L^-1 D', for
// pointwise rows assembled from the rows of Theta_c L^-T of the nodes they touch, made once per
// query; Q = E'E), Q = D A^-1 D', the QP warm started from the previous step's passive set; no
// allocation of size N or R per step.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/online/affine_whitening.hpp"
#include "contactrb/online/error_estimator.hpp"
#include "contactrb/online/online_magic.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/solve/kacanov.hpp"
#include "contactrb/solve/nonnegative_qp.hpp"

namespace contactrb::online {

// -1: the model's maximum.
struct OnlineSizes {
  int N = -1;
  int R = -1;
  int Mk = -1;
  int Mg = -1;
};

// How the reduced Kacanov fixed point u_hat = G(u_hat) (G: one linearized step (53)) is reached.
// The fixed point is the same; only the path and the number of steps differ.
enum class OnlineIteration {
  // Accelerated when OnlineSettings::kacanov is empty (the default), Relaxed when it is set
  // (an explicit alpha is honoured, e.g. `contactrb online --alpha`).
  Automatic,
  // Paper (12): u^k = alpha u_bar + (1 - alpha) u^{k-1}, stopping test (63) (solve::kacanov, the
  // HF snapshots' iteration).
  Relaxed,
  // alpha is not used: undamped steps (alpha = 1) with Anderson mixing of depth anderson_depth,
  // safeguarded (a step whose residual |G(u) - u| does not decrease clears the history and
  // halves the damping, down to the model's alpha). Stopping test (63) on the fixed-point
  // residual: |G(u^k) - u^k| <= eps_KA |u^k| and |lambda_bar^k - lambda_bar^{k-1}| <= eps_KA
  // |lambda_bar^{k-1}|, i.e. (63) on the unrelaxed step as in the Relaxed iteration
  // (solve/kacanov.hpp), so both stop at the same distance from the fixed point. Measured:
  // 4-8 steps against 18-42 for the relaxed iteration at alpha = 0.3 (docs/performance.md, "Why the defaults are what they are",
  // "Online: accelerated iteration").
  Accelerated,
  // Semi-smooth Newton on the reduced equilibrium and complementarity with the exact contact rows
  // and their consistent linearization (contact::linearize_contact: the motion of the projection
  // and of the normal, and the geometric stiffness of the contact forces), as the HF Newton
  // (docs/solvers.md) on the reduced unknowns (u_hat, lambda_hat). Needs ContactRows::Exact.
  // Stops when the relative increments of u_hat and lambda_hat are below the tolerance with an
  // unchanged active set: the returned pair satisfies the equilibrium at its own rows.
  Newton,
};
const char* to_string(OnlineIteration value);  // "automatic" | "relaxed" | "accelerated" | "newton"
OnlineIteration online_iteration_from_string(const std::string& name);  // throws contactrb::Error

// Where the reduced Kacanov iteration starts. The fixed point and the stopping test are the same;
// a start near the answer needs fewer steps.
enum class InitialGuess {
  // The reduced solutions at the training values (ReducedModel::training_u_hat and
  // training_lambda_hat, their leading N and R entries), interpolated linearly in mu between the
  // two nearest training values (the nearest one outside their range); with p > 1 parameters the
  // nearest training point's, u_hat to first order in mu (training_u_sensitivity) at the model's
  // maximal sizes. Reduced-size data only.
  Interpolated,
  // u_hat = 0 (the paper's Algorithm 1).
  Zero,
};
const char* to_string(InitialGuess value);  // "interpolated" | "zero"
InitialGuess initial_guess_from_string(const std::string& name);  // throws contactrb::Error

// How each step evaluates the reduced contact operator D = Xi' K(w) Theta_c and Xi' gamma(w):
// Eim, the paper's (54)-(55) from the magic points; Exact, from the HF contact rows of the
// whole contact surface at the reduced displacement w = u_D + Theta_c u_hat (no EIM error: a
// cost of n_c N per step). Automatic: Exact for a model whose dual cone is the row cone
// (dual_method "rows": its constraints are HF rows, exactly), Eim otherwise.
enum class ContactRows { Automatic, Eim, Exact };

// The default tolerance of the reduced iteration with the exact contact rows. The snapshots'
// eps_KA (1e-3) stops the fixed point where the kept rows still miss their constraints by about
// 1e-8 of the gap scale, and the estimate's square-root term (violation times pressure) then
// dominates it 10-20x (docs/offline-online.md, "Error estimate"); at 1e-8 the kept rows hold to
// round-off for 4-8 more accelerated steps.
inline constexpr double kExactRowsTolerance = 1e-8;

struct OnlineSettings {
  // Empty: the tolerance and iteration cap of the HF snapshots the model was built from (and
  // their alpha, for the Relaxed iteration); with the exact contact rows the tolerance is
  // kExactRowsTolerance.
  std::optional<solve::KacanovSettings> kacanov;
  solve::QPSettings qp;
  // false: recompute every row of the contact-surface mesh (the reference path of the tests).
  // true: only the magic rows (from the slave nodes under them).
  bool restricted_rows = true;
  ContactRows contact_rows = ContactRows::Automatic;
  OnlineIteration iteration = OnlineIteration::Automatic;
  // Accelerated: number of previous steps mixed (0: plain undamped steps, still safeguarded).
  int anderson_depth = 3;
  InitialGuess initial_guess = InitialGuess::Interpolated;
  // An explicit start [u_hat; lambda_hat] of size N + R (the solver's sizes), used in place of
  // initial_guess: e.g. the answer at mu of an earlier model whose basis this one extends (the
  // greedy's sweep, offline/greedy_sweep.hpp). The fixed point and the stopping test are the same.
  // Another size or a non-finite entry is refused (contactrb::Error).
  std::optional<Eigen::VectorXd> start;
  // Compute OnlineSolution::estimate (error_estimate.hpp); false only to time the solve without it.
  bool error_estimate = true;
  // Accelerated iteration with the exact contact rows, at the model's maximal N and R: mix the
  // steps preconditioned by (I - G'_p)^-1, G'_p the Jacobian of the reduced Kacanov map at the
  // nearest training point (ReducedModel::training_jacobian; docs/offline-online.md, "Online:
  // the preconditioned iteration"). The fixed point and the stopping test are those of the plain
  // iteration; only the number of steps changes. Ignored when the model holds no Jacobians.
  bool preconditioned = true;
};

struct OnlineSolution {
  solve::KacanovStatus status = solve::KacanovStatus::StepFailed;
  std::string message;  // why it stopped, when not converged
  int iterations = 0;
  // Last linearized solution (as the HF solver returns). Always sized N and R and finite: when
  // no step succeeded (StepFailed at the first step, A_hat(mu) not SPD) they are zero, and
  // energy and contact_force are those of that zero solution.
  Eigen::VectorXd u_hat;
  Eigen::VectorXd lambda_hat;  // >= 0
  double energy = 0.0;         // 1/2 u'A(mu)u - f(mu)'u of u = u_D(mu) + Theta u_hat (exact: (49) + lift terms)
  double contact_force = 0.0;  // sum_r |I_r|(mu) (Xi lambda_hat)_r
  double time_s = 0.0;
  // A posteriori estimate of |u_hf - u_rb|_A(mu) and its parts (docs/offline-online.md); available
  // when the solve converged and the model holds the estimate data. Included in time_s.
  ErrorEstimate estimate;
  bool converged() const { return status == solve::KacanovStatus::Converged; }
};

class OnlineSolver {
 public:
  // Borrows nothing: copies the leading blocks. Throws contactrb::Error for an inconsistent
  // model or sizes outside [1, max] (R, Mk, Mg may be 0 only when their maximum is 0).
  explicit OnlineSolver(const contactrb::model::ReducedModel& model, const OnlineSizes& sizes = {});

  // Throws contactrb::Error for mu of the wrong size or outside the parameter domain, or invalid
  // settings; non-convergence is a status. The double overload is for one-parameter models.
  OnlineSolution solve(const cases::Mu& mu, const OnlineSettings& settings = {});
  OnlineSolution solve(double mu, const OnlineSettings& settings = {}) {
    return solve(cases::Mu::Constant(1, mu), settings);
  }

  // The deformed normal gap of a reduced solution on the whole slave boundary: at every slave
  // node s, g(w)_s - k(w; w)_s (paper (27)-(28), contact/projection.hpp: > 0 open, 0 in contact,
  // < 0 penetration; a node beyond the master's end: its distance to the master), with
  // w = u_D,c(mu) + Theta_c u_hat on the model's contact surface in Omega(mu); its maximum and
  // minimum over the nodes. The solve evaluates the EIM magic rows only; this projects every
  // slave node once (the model holds the whole contact surface and Theta_c). `s` must be this
  // solver's answer to its last solve, at `mu`: throws contactrb::Error for another mu, a solve
  // that stopped before its first step, or a u_hat of the wrong size.
  struct SurfaceGap {
    double max = 0.0;
    double min = 0.0;
  };
  SurfaceGap surface_gap(const cases::Mu& mu, const OnlineSolution& s) const;

  // The Jacobian G'(u_hat) (N x N) of the reduced Kacanov map G at mu with the exact contact rows
  // (one linearized step (53): u_hat -> u_bar), by forward differences, each step's QP started
  // from the same passive set (the result does not depend on earlier solves). Offline data of
  // ReducedModel::training_jacobian. Throws contactrb::Error for a model without exact rows (EIM
  // cones), a mu or u_hat of the wrong size, or a step that fails.
  Eigen::MatrixXd fixed_point_jacobian(const cases::Mu& mu, const Eigen::VectorXd& u_hat);
  // The same Jacobian at a fixed point (u_hat, lambda_hat) of G, from the linearization of the
  // contact rows the reduced Newton uses (online_newton.cpp): with the active generators
  // lambda_hat > 0 kept active, one KKT system [A_hat B_a'; B_a 0] with N right-hand sides
  // [-Theta_c' H Theta_c; G_a + B_a] (H the geometric stiffness, G the gap rows' derivative)
  // instead of N + 1 steps. Agrees with fixed_point_jacobian to its difference error where no
  // generator is degenerate (tests/offline/test_preconditioned_iteration.cpp).
  Eigen::MatrixXd linearized_fixed_point_jacobian(const cases::Mu& mu, const Eigen::VectorXd& u_hat,
                                                  const Eigen::VectorXd& lambda_hat);

  int N() const { return N_; }
  int R() const { return R_; }
  int Mk() const { return Mk_; }
  int Mg() const { return Mg_; }

 private:
  // Per mu: A_hat(mu) (49) and its factor (whitening_), z = A_hat^-1 f_hat(mu), the lift on the contact
  // surface, the quadrature at mu. Returns false (message set) when A_hat(mu) is not SPD.
  bool prepare(const cases::Mu& mu, bool restricted, bool exact_rows, std::string& message);
  // D' and Xi'gamma of the step from the HF rows at w = u_D + Theta_c u_hat (OnlineSettings::exact_rows).
  // with_d false: Et_ and dg_ only (pointwise rows, not registered), Dt_ left as it is.
  void exact_operators(const Eigen::VectorXd& u_hat, bool with_d = true);
  bool exact_rows(ContactRows choice) const;
  // Xi(mu) of the registered cone at mu, and the kept rows where it is not zero (xi_rows_, Xi_rows_).
  void set_registered_basis(const cases::Mu& mu);
  // The HF contact rows at the returned solution, for ErrorEstimator::evaluate_exact (pointwise
  // rows: from all_rows_, allocation-free; exactly integrated LAC rows: the contact library's).
  const ErrorEstimator::ExactContact& exact_contact(const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat);
  // The contact library's HF rows at w = u_D + Theta_c u_hat (w_ is left at w).
  contact::ConstraintRows hf_rows_at(const Eigen::VectorXd& u_hat);
  // The reduced dual QP of the step's D and Xi'gamma, and u_bar = A^-1 (f - D' lambda).
  // The exact rows: Et_ = E = L^-1 D' (A_hat = L L'); the EIM rows: Et_ = Y = A^-1 D'.
  // e_given: Et_ is already set (the exact pointwise rows, from the solved rows of Theta_c L^-T);
  // otherwise it is solved here from Dt_.
  bool solve_reduced_qp(Eigen::VectorXd& u_bar, Eigen::VectorXd& lambda_bar, int& inner, std::string& message,
                        bool e_given = false);
  // One linearized step (53) at u_hat: writes u_bar = G(u_hat) and lambda_bar.
  bool step(const Eigen::VectorXd& u_hat, Eigen::VectorXd& u_bar, Eigen::VectorXd& lambda_bar, int& inner,
            std::string& message);
  // The Accelerated iteration from u_start (see OnlineIteration).
  solve::KacanovResult iterate_newton(const solve::KacanovSettings& ks, const Eigen::VectorXd& u_start,
                                      const Eigen::VectorXd& lambda_start);
  // One Newton linearization at u_hat, lambda_hat (online_newton.cpp).
  struct NewtonSystem;
  void newton_system(const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat, NewtonSystem& sys);
  void add_geometric_stiffness(const Eigen::SparseMatrix<double>& H, Eigen::MatrixXd& J) const;
  // kept_pair_ and kept_column_ from the sparsity of the rows (constructor), kept_quadrature_
  // from quadrature_ (whenever quadrature_ is rebuilt).
  void setup_kept_pair();
  void restrict_quadrature();
  // pre: the preconditioner (I - G'_p)^-1 of the step's residual, or null.
  solve::KacanovResult iterate_accelerated(const solve::KacanovSettings& ks, int depth,
                                           const Eigen::VectorXd& u_start, const Eigen::VectorXd& lambda_start,
                                           const Eigen::MatrixXd* pre = nullptr);
  // The column of guess_ (training point) nearest to mu in the scaled coordinates of
  // interpolated_guess (p = 1: the nearer of the two it interpolates between); -1 without any.
  Eigen::Index nearest_training(const cases::Mu& mu) const;
  // preconditioner_ and sensitivity_ from the model's Jacobians and sensitivities (constructor;
  // guess_'s column order).
  void set_preconditioners(const contactrb::model::ReducedModel& model, const std::vector<int>& order);
  // (I - G'_p)^-1 of guess_'s column p; null when I - G'_p is singular or the model has none.
  const Eigen::MatrixXd* preconditioner(Eigen::Index p) const;
  // InitialGuess::Interpolated at mu: [u_hat; lambda_hat] (N + R; zero when the model holds no
  // training values): p = 1, linear between the two nearest training values; p > 1, the nearest
  // training point in coordinates scaled to [0, 1] per parameter, its u_hat to first order in
  // mu where the model holds the sensitivities (ReducedModel::training_u_sensitivity).
  Eigen::VectorXd interpolated_guess(const cases::Mu& mu) const;
  // The relative inf-sup constant of the last step's reduced pair, sqrt(lambda_min(Q) /
  // lambda_max(Q)) with Q = D A_hat^-1 D' (R x R): 0 when some pressure generator is invisible to
  // V_N (R > N, or the supremizer that sees it cut by the N truncation).
  double relative_inf_sup() const;
  std::string undetermined_message(double beta) const;
  // D vanishes: the primal basis has no component the contact rows see (K Theta_c = 0).
  std::string blind_contact_message(double d_norm) const;

  // Contact-surface mesh at mu (chain nodes only, no triangles) and the EIM values at the
  // magic points for the contact-DOF displacement w.
  // restricted: only the magic rows (LAC: lac_rows_ from the slave nodes lac_positions_).
  void evaluate_magic(const Eigen::VectorXd& w, const Eigen::VectorXd& lift_c, bool restricted,
                      Eigen::VectorXd& kappa_hat, Eigen::VectorXd& gamma_hat) const;

  int N_ = 0, R_ = 0, Mk_ = 0, Mg_ = 0;
  std::vector<cases::ParameterSpec> parameters_;
  std::vector<double> guess_mu_;  // p = 1: training values, increasing
  Eigen::MatrixXd guess_points_;  // p x P: training points scaled to [0, 1] per parameter
  Eigen::MatrixXd guess_mu_points_;  // p x P: the same points unscaled
  Eigen::VectorXd guess_offset_, guess_scale_;  // x = (mu - offset) .* scale
  Eigen::MatrixXd guess_;         // (N + R) x P: their [u_hat; lambda_hat], in the same order
  Eigen::MatrixXd sensitivity_;                   // N x (p P), same order: d u_hat / d mu; empty: none
  std::vector<Eigen::MatrixXd> preconditioner_;  // P, guess_'s order: (I - G'_p)^-1; empty: no preconditioner
  std::vector<char> preconditioner_state_;       // P: 1 factored, 2 singular
  cases::AffineThetas thetas_;
  double kacanov_alpha_ = 0.3, kacanov_tolerance_ = 1e-3;
  int kacanov_max_iterations_ = 500;
  std::vector<Eigen::MatrixXd> A_hat_;
  std::vector<Eigen::VectorXd> f_hat_, A_lift_hat_;
  std::vector<double> lift_AA_, lift_f_;
  Eigen::MatrixXd Ct_;                   // (N R) x Mk: column j = C_j' (N x R, column-major); vec(D') = Ct_ phi
  Eigen::PartialPivLU<Eigen::MatrixXd> B_kappa_lu_, B_gamma_lu_;  // leading blocks (Remark 4)
  Eigen::MatrixXd XiQ_gamma_;            // R x Mg
  Eigen::MatrixXd Xi_;                   // R_kept x R
  bool xi_is_identity_ = false;          // Xi_ = the first R unit vectors (the row cone): products skipped
  bool registered_ = false;              // Xi_ = Xi(mu) of the registered cone (model/registration.hpp)
  std::vector<int> xi_rows_;             // registered: the kept rows (positions) where Xi(mu) is not zero
  Eigen::MatrixXd Xi_rows_;              // registered: those rows of Xi(mu)
  contactrb::model::Registration registration_;
  double d_bound_ = 0.0;                 // |Xi|_F |Theta_c|_F (bound of |D|_F per unit |phi|_1)
  // N below the model's N_max cuts supremizers (they are the last basis vectors): the pair
  // (V_N, span Xi_R) may then lose its inf-sup stability, and lambda_hat its uniqueness.
  bool check_inf_sup_ = false;
  int N_max_ = 0, N_supremizers_ = 0;
  std::vector<int> kept_rows_;
  std::vector<int> kappa_row_, kappa_dof_, gamma_row_;  // constraint rows (R_hf numbering), DOFs
  std::vector<int> lac_rows_, lac_positions_;           // LAC: the magic rows, their slave chain positions
  std::vector<int> lac_kept_positions_;                 // LAC: the slave chain positions of the kept rows
  contactrb::model::ContactSurface surface_;
  Eigen::MatrixXd Theta_c_;              // n_c x N
  Eigen::MatrixXd lift_c_;               // n_c x J^D
  mesh::Mesh mesh_;                      // contact nodes in Omega(mu) (positions set per solve)
  contact::ContactPair pair_;
  contact::ContactQuadrature quadrature_;
  // Pointwise rows (collocation, LAC-Simpson): the slave nodes of the kept rows and the whole
  // master chain, and the kept rows of quadrature_ over those nodes. The reduced Newton
  // linearizes these rows only (online_newton.cpp); empty for LAC rows.
  contact::ContactPair kept_pair_;
  contact::ContactQuadrature kept_quadrature_;
  std::vector<int> kept_column_;          // slave position -> column of kept_quadrature_.W (-1: none)
  std::vector<char> movable_;             // every contact-surface DOF moves with u_hat
  std::vector<Eigen::Vector2d> quadrature_slave_;  // the slave node positions quadrature_ was built at
  MagicPointEvaluator magic_;             // the restricted evaluation (online_magic.hpp)
  MagicPointEvaluator kept_;              // the kept rows whole (ContactRows::Exact, pointwise rows)
  MagicPointEvaluator all_rows_;          // every row's slack and the load (the exact-rows estimate, pointwise rows)
  Eigen::VectorXd lambda_rows_, slack_rows_;  // R_hf: Xi lambda_hat (0 on the dropped rows), g(w) - K(w) w
  ErrorEstimator::ExactContact exact_;    // exact_contact's answer (its load: n_c)
  contact::ConstraintRows estimate_rows_; // the rows behind exact_.rows()
  solve::NonnegativeQPSolver qp_;

  // Workspaces, sized in the constructor: a query allocates nothing of size N, R per step
  // (the contact-surface projection and the QP's message aside).
  Eigen::MatrixXd A_;                    // A_hat(mu)
  AffineWhitening whitening_;            // A_hat(mu) = L L'
  Eigen::VectorXd f_, z_, zl_;           // f_hat(mu), A_hat(mu)^-1 f_hat(mu), L^-1 f_hat(mu)
  double E_D_ = 0.0;
  bool restricted_ = true;
  bool exact_rows_ = false;              // this solve's ContactRows, resolved
  bool row_cone_ = false;                // the model's dual cone is the row cone
  RowMatrix KTheta_;                     // R_kept x N: K(w) Theta_c on the kept rows (exact_rows_; registered:
                                         // on xi_rows_)
  RowMatrix KE_;                         // R_kept x N: K(w) Theta_c L^-T (exact pointwise rows)
  Eigen::VectorXd gamma_kept_;           // R_kept: g(w) - K(w) u_D on the kept rows (exact_rows_; registered: xi_rows_)
  cases::Mu prepared_mu_;                // the mu of the last successful prepare (surface_gap)
  bool prepared_ = false;
  bool blind_checked_ = false;           // this query's D' passed the blind test (step)
  bool pointwise_magic_ = true;          // restricted_ and rows that are W * pointwise rows
  Eigen::VectorXd lift_mu_;              // u_D,c(mu) on the contact DOFs
  Eigen::VectorXd w_, kappa_hat_, gamma_hat_, phi_, phi_gamma_, dg_, c_, t_;
  Eigen::MatrixXd Dt_;                   // N x R: D'
  Eigen::MatrixXd Et_;                   // N x R: E = L^-1 D' (exact rows) or Y = A^-1 D' (EIM)
  Eigen::MatrixXd Q_;                    // R x R: D A^-1 D'
  std::vector<int> warm_;                // the previous step's QP passive set
  // Accelerated iteration: current and previous iterates, residuals, history columns.
  Eigen::VectorXd u_, u_prev_, r_, r_prev_, lambda_prev_, pr_;
  Eigen::MatrixXd dU_, dR_, dL_;         // differences of u, of r = G(u) - u, of lambda_bar
  ErrorEstimator estimator_;             // the leading blocks of the estimate's data
  Eigen::VectorXd weight_kept_;          // |I_r|(mu) on the kept rows
};

}  // namespace contactrb::online
