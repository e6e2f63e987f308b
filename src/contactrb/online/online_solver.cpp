#include "contactrb/online/online_solver.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <limits>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <chrono>
#include <string>

#include "contactrb/cases/unit_box.hpp"
#include "contactrb/cases/geometric_map.hpp"
#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/lac_integration.hpp"
#include "contactrb/contact/projection.hpp"
#include "contactrb/online/model_check.hpp"
#include "contactrb/online/registered_basis.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::online {

using model::ReducedModel;

namespace {
// |D|_F below this fraction of its cancellation-free bound: the reduced constraints are blind.
constexpr double kBlindContactTolerance = 1e-10;
// The relative inf-sup constant (OnlineSolver::relative_inf_sup) at or below which a truncation
// that cuts supremizers leaves lambda_hat undetermined: the round-off of a rank-deficient
// L^-1 D'. A determined but ill-conditioned pair stays an answer: on hertz-a (N_max 22 = 10 POD
// modes + 12 supremizers, R 12) the constant is 4e-5-7e-5 at N 22, 2e-6-5e-6 at N 13 and
// 3e-8 at N 12, with the energy and force of the full model to 1e-5.
constexpr double kInfSupTolerance = 1e-12;
// R up to which the triangle of Q = D Y is formed by inner products rather than a blocked
// triangular product. Measured (N, R): (51, 15) 1.9 us against 2.1-2.5 us; (100, 60) 46-48 us
// against 36-39 us; (170, 139) 430 us against 280-315 us (the full product: 3.0, 32-63, 585 us).
constexpr int kInnerProductRows = 32;
}  // namespace

namespace {
using Clock = std::chrono::steady_clock;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }

int resolve(int requested, int maximum, int minimum, const char* name) {
  const int v = requested < 0 ? maximum : requested;
  require(v >= minimum && v <= maximum, std::string("OnlineSolver: ") + name + " = " + std::to_string(v) +
                                            " outside [" + std::to_string(minimum) + ", " + std::to_string(maximum) +
                                            "] (the model's maximum)");
  return v;
}

// Row r of a row-major sparse matrix dotted with v.
double row_dot(const RowSparse& K, int r, const Eigen::VectorXd& v) {
  double s = 0.0;
  for (RowSparse::InnerIterator it(K, r); it; ++it) s += it.value() * v(it.col());
  return s;
}
}  // namespace

OnlineSolver::OnlineSolver(const ReducedModel& model, const OnlineSizes& sizes) {
  check_model(model);
  N_ = resolve(sizes.N, model.N_max, 1, "N");
  registered_ = !model.registration.empty();
  const int R_model = registered_ ? model.registration.R() : model.R_max;
  R_ = resolve(sizes.R, R_model, R_model > 0 ? 1 : 0, "R");
  Mk_ = resolve(sizes.Mk, model.Mk_max, model.Mk_max > 0 ? 1 : 0, "Mk");
  Mg_ = resolve(sizes.Mg, model.Mg_max, model.Mg_max > 0 ? 1 : 0, "Mg");
  N_max_ = model.N_max;
  N_supremizers_ = model.N_supremizers;
  check_inf_sup_ = model.N_supremizers > 0 && R_ > 0 && N_ < model.N_max;
  row_cone_ = model.dual_method == model::kRowCone;
  parameters_ = model.parameters;
  {
    // p = 1: sorted values (linear interpolation); p > 1: the points scaled to [0, 1] per
    // parameter (nearest point), so that parameters of different units weigh alike.
    const int p_dim = model.num_parameters();
    std::vector<int> order(static_cast<std::size_t>(model.training_mu.cols()));
    for (std::size_t p = 0; p < order.size(); ++p) order[p] = static_cast<int>(p);
    if (p_dim == 1) {
      std::stable_sort(order.begin(), order.end(),
                       [&](int a, int b) { return model.training_mu(0, a) < model.training_mu(0, b); });
    }
    guess_.resize(N_ + R_, static_cast<Eigen::Index>(order.size()));
    guess_points_.resize(p_dim, static_cast<Eigen::Index>(order.size()));
    guess_mu_points_.resize(p_dim, static_cast<Eigen::Index>(order.size()));
    const cases::UnitBox box = cases::unit_box(parameters_);
    guess_offset_ = box.offset;
    guess_scale_ = box.scale;
    for (std::size_t p = 0; p < order.size(); ++p) {
      if (p_dim == 1) guess_mu_.push_back(model.training_mu(0, order[p]));
      guess_mu_points_.col(static_cast<Eigen::Index>(p)) = model.training_mu.col(order[p]);
      guess_points_.col(static_cast<Eigen::Index>(p)) =
          (model.training_mu.col(order[p]) - guess_offset_).cwiseProduct(guess_scale_);
      guess_.col(static_cast<Eigen::Index>(p)) << model.training_u_hat.col(order[p]).head(N_),
          model.training_lambda_hat.col(order[p]).head(R_);
    }
    set_preconditioners(model, order);
  }
  thetas_ = model.thetas;
  kacanov_alpha_ = model.kacanov_alpha;
  kacanov_tolerance_ = model.kacanov_tolerance;
  kacanov_max_iterations_ = model.kacanov_max_iterations;
  for (const auto& A : model.A_hat) A_hat_.push_back(A.topLeftCorner(N_, N_));
  for (const auto& f : model.f_hat) f_hat_.push_back(f.head(N_));
  for (const auto& f : model.A_lift_hat) A_lift_hat_.push_back(f.head(N_));
  lift_AA_ = model.lift_AA;
  lift_f_ = model.lift_f;
  // Column j = C_j' (N x R) stored column-major: D' = sum_j phi_j C_j' is one matrix-vector product.
  Ct_.resize(static_cast<Eigen::Index>(N_) * R_, Mk_);
  for (int j = 0; j < Mk_; ++j) {
    Eigen::Map<Eigen::MatrixXd>(Ct_.col(j).data(), N_, R_) = model.C_kappa[sz(j)].topLeftCorner(R_, N_).transpose();
  }
  // The leading M x M block of B is the B of the first M EIM functions (B is lower triangular).
  if (Mk_ > 0) B_kappa_lu_.compute(model.B_kappa.topLeftCorner(Mk_, Mk_));
  if (Mg_ > 0) B_gamma_lu_.compute(model.B_gamma.topLeftCorner(Mg_, Mg_));
  XiQ_gamma_ = model.XiQ_gamma.topLeftCorner(R_, Mg_);
  if (registered_) {  // Xi(mu), set by prepare
    registration_ = model.registration;
    Xi_.setZero(model.R_kept(), R_);
  } else {
    Xi_ = model.Xi.leftCols(R_);
    xi_is_identity_ = Xi_.rows() >= R_ && Xi_.topRows(R_).isIdentity(0.0) &&
                      (Xi_.rows() == R_ || Xi_.bottomRows(Xi_.rows() - R_).isZero(0.0));
  }
  kept_rows_ = model.kept_rows;
  for (int i = 0; i < Mk_; ++i) {
    kappa_row_.push_back(model.kept_rows[sz(model.kappa_row[sz(i)])]);
    kappa_dof_.push_back(model.kappa_dof[sz(i)]);
  }
  for (int i = 0; i < Mg_; ++i) gamma_row_.push_back(model.kept_rows[sz(model.gamma_row[sz(i)])]);
  surface_ = model.surface;
  Theta_c_ = model.Theta_c.leftCols(N_);
  lift_c_ = model.lift_c;

  // Contact-surface-only mesh: the chain nodes and the two boundary groups, no triangles
  // (projection, quadrature and rows need only nodes and chains).
  mesh_.nodes = surface_.reference_nodes;
  auto edges = [](const std::vector<int>& chain) {
    std::vector<mesh::Edge> e;
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) e.push_back({chain[k], chain[k + 1]});
    return e;
  };
  mesh_.boundaries[mesh::kSlaveBoundary] = edges(surface_.slave);
  mesh_.boundaries[mesh::kMasterBoundary] = edges(surface_.master);
  pair_.slave = surface_.slave;
  pair_.master = surface_.master;
  magic_.setup(surface_, kappa_row_, kappa_dof_, gamma_row_, Theta_c_);
  kept_.setup(surface_, {}, {}, kept_rows_, Theta_c_);
  whitening_.setup(A_hat_);
  if (whitening_.diagonal_available()) kept_.set_whitening_basis(whitening_.basis());
  {
    std::vector<int> every_row(sz(surface_.num_constraints));
    for (int r = 0; r < surface_.num_constraints; ++r) every_row[sz(r)] = r;
    all_rows_.setup(surface_, {}, {}, every_row, Theta_c_);
  }
  lambda_rows_.resize(surface_.num_constraints);
  slack_rows_.resize(surface_.num_constraints);
  exact_.load.resize(Theta_c_.rows());
  KTheta_.resize(static_cast<Eigen::Index>(kept_rows_.size()), N_);
  KE_.resize(static_cast<Eigen::Index>(kept_rows_.size()), N_);
  gamma_kept_.resize(static_cast<Eigen::Index>(kept_rows_.size()));
  lac_rows_ = kappa_row_;
  lac_rows_.insert(lac_rows_.end(), gamma_row_.begin(), gamma_row_.end());
  std::sort(lac_rows_.begin(), lac_rows_.end());
  lac_rows_.erase(std::unique(lac_rows_.begin(), lac_rows_.end()), lac_rows_.end());
  lac_positions_ = contact::lac_slave_positions(lac_rows_, static_cast<int>(surface_.slave.size()));
  lac_kept_positions_ = contact::lac_slave_positions(kept_rows_, static_cast<int>(surface_.slave.size()));
  setup_kept_pair();
  // Upper bound of |D|_F without cancellation per unit |phi|_1: |Xi| |Q_j| |Theta_c| with |q_j|_inf = 1.
  d_bound_ = Xi_.norm() * Theta_c_.norm();

  // Workspaces (see the header).
  const Eigen::Index n_c = Theta_c_.rows();
  A_.resize(N_, N_);
  f_.resize(N_);
  z_.resize(N_);
  lift_mu_.resize(n_c);
  movable_.assign(sz(static_cast<int>(n_c)), 1);
  w_.resize(n_c);
  kappa_hat_.resize(Mk_);
  gamma_hat_.resize(Mg_);
  phi_.resize(Mk_);
  phi_gamma_.resize(Mg_);
  dg_.resize(R_);
  c_.resize(R_);
  zl_.resize(N_);
  t_.resize(N_);
  Et_.resize(N_, R_);
  Dt_.resize(N_, R_);
  Q_.resize(R_, R_);
  warm_.reserve(sz(R_));
  for (Eigen::VectorXd* v : {&u_, &u_prev_, &r_, &r_prev_}) v->resize(N_);
  lambda_prev_.resize(R_);
  estimator_.setup(model, N_, R_, Mk_, Mg_);
  weight_kept_.resize(static_cast<Eigen::Index>(kept_rows_.size()));
}

void OnlineSolver::evaluate_magic(const Eigen::VectorXd& w, const Eigen::VectorXd& lift_c, bool restricted,
                                  Eigen::VectorXd& kappa_hat, Eigen::VectorXd& gamma_hat) const {
  const bool lac_subset = restricted && surface_.discretization == contact::Discretization::LAC;
  const contact::PointwiseContact pw = lac_subset ? contact::project_slave_nodes(mesh_, pair_, w, lac_positions_)
                                                  : contact::project_slave_nodes(mesh_, pair_, w);
  const contact::ConstraintRows rows = lac_subset
                                           ? contact::integrate_lac_rows(mesh_, pair_, quadrature_, pw, w, lac_rows_)
                                           : contact::constraint_rows(mesh_, pair_, quadrature_, pw, w);
  require(rows.K.rows() == surface_.num_constraints,
          "OnlineSolver: the contact surface gives " + std::to_string(rows.K.rows()) + " constraints, the model " +
              std::to_string(surface_.num_constraints));
  kappa_hat.resize(Mk_);
  for (int i = 0; i < Mk_; ++i) kappa_hat(i) = rows.K.coeff(kappa_row_[sz(i)], kappa_dof_[sz(i)]);
  // gamma = g - K u_D(mu) (the lift's contact term moved into the gap).
  gamma_hat.resize(Mg_);
  for (int i = 0; i < Mg_; ++i) {
    const int r = gamma_row_[sz(i)];
    gamma_hat(i) = rows.g(r) - row_dot(rows.K, r, lift_c);
  }
}

OnlineSolver::SurfaceGap OnlineSolver::surface_gap(const cases::Mu& mu, const OnlineSolution& s) const {
  require(prepared_ && prepared_mu_.size() == mu.size() && prepared_mu_ == mu,
          "surface_gap: not the mu of this solver's last solve (or that solve stopped before its first step)");
  require(s.u_hat.size() == N_, "surface_gap: u_hat has " + std::to_string(s.u_hat.size()) + " entries, N = " +
                                    std::to_string(N_));
  Eigen::VectorXd w = lift_mu_;
  w.noalias() += Theta_c_ * s.u_hat;
  const contact::PointwiseContact pw = contact::project_slave_nodes(mesh_, pair_, w);
  const Eigen::VectorXd gap = pw.g - pw.K * w;  // (28) - (27) at the displacement itself
  require(gap.size() > 0, "surface_gap: the contact surface has no slave node");
  return {gap.maxCoeff(), gap.minCoeff()};
}

bool OnlineSolver::prepare(const cases::Mu& mu, bool restricted, bool exact_rows, std::string& message) {
  prepared_ = false;
  // Omega(mu) on the contact surface: h_body(mu) applied to the reference chain nodes.
  const std::array<cases::AffineMap, 2> maps = cases::geometric_maps(parameters_, mu);
  for (std::size_t i = 0; i < mesh_.nodes.size(); ++i) {
    mesh_.nodes[i] = maps[sz(surface_.body[i])](surface_.reference_nodes[i]);
  }
  // The quadrature reads the slave chain only: rebuilt when the slave nodes moved (a mapped slave
  // body), kept otherwise (a mapped master body, an imposed displacement).
  bool slave_moved = quadrature_slave_.size() != surface_.slave.size();
  for (std::size_t k = 0; k < surface_.slave.size() && !slave_moved; ++k) {
    slave_moved = quadrature_slave_[k] != mesh_.nodes[sz(surface_.slave[k])];
  }
  if (slave_moved) {
    quadrature_ = contact::make_quadrature(mesh_, pair_, surface_.discretization);
    restrict_quadrature();
    quadrature_slave_.clear();
    for (int v : surface_.slave) quadrature_slave_.push_back(mesh_.nodes[sz(v)]);
  }
  require(quadrature_.W.rows() == surface_.num_constraints,
          "OnlineSolver: the contact surface gives " + std::to_string(quadrature_.W.rows()) +
              " constraints, the model " + std::to_string(surface_.num_constraints));
  restricted_ = restricted;
  exact_rows_ = exact_rows;
  if (registered_) set_registered_basis(mu);
  // Collocation and LAC-Simpson rows: the allocation-free evaluator (online_magic.hpp).
  pointwise_magic_ = restricted && surface_.discretization != contact::Discretization::LAC;
  // (49)
  const Eigen::VectorXd ta = cases::evaluate(thetas_.a, mu);
  const Eigen::VectorXd tf = cases::evaluate(thetas_.f, mu);
  const Eigen::VectorXd tl = cases::evaluate(thetas_.lift, mu);
  const int Ja = static_cast<int>(A_hat_.size()), Jf = static_cast<int>(f_hat_.size());
  const int JD = static_cast<int>(tl.size());
  A_.setZero();
  f_.setZero();
  E_D_ = 0.0;
  for (int j = 0; j < Ja; ++j) {
    A_ += ta(j) * A_hat_[sz(j)];
    for (int k = 0; k < JD; ++k) {
      f_ -= ta(j) * tl(k) * A_lift_hat_[sz(j * JD + k)];
      for (int l = 0; l < JD; ++l) E_D_ += 0.5 * ta(j) * tl(k) * tl(l) * lift_AA_[sz((j * JD + k) * JD + l)];
    }
  }
  for (int j = 0; j < Jf; ++j) {
    f_ += tf(j) * f_hat_[sz(j)];
    for (int k = 0; k < JD; ++k) E_D_ -= tf(j) * tl(k) * lift_f_[sz(j * JD + k)];
  }
  // Once per query: the factor A_hat(mu) = L L' serves every step (affine_whitening.hpp).
  // The simultaneous diagonalization where the touched rows of Theta_c L^-T come pre-solved.
  if (!whitening_.factor(ta, A_, pointwise_magic_ && exact_rows_ && !registered_)) {
    message = "A_hat(mu) is not positive definite";
    return false;
  }
  zl_ = f_;
  whitening_.solve_factor(zl_);  // L^-1 f_hat: c = E' L^-1 f_hat with the exact rows (solve_reduced_qp)
  z_ = zl_;
  whitening_.solve_factor_transpose(z_);  // A_hat^-1 f_hat
  if (JD > 0) {
    lift_mu_.noalias() = lift_c_ * tl;
  } else {
    lift_mu_.setZero();
  }
  if (pointwise_magic_) (exact_rows_ ? kept_ : magic_).prepare(mesh_.nodes, quadrature_, lift_mu_);
  if (pointwise_magic_ && exact_rows_ && registered_) {
    // Only the rows Xi(mu) weighs; Y = A^-1 D' from D' itself (R columns, not the rows'
    // nodes: R is small and does not grow with the mesh).
    kept_.select_rows(xi_rows_);
    KTheta_.resize(static_cast<Eigen::Index>(xi_rows_.size()), N_);
    gamma_kept_.resize(static_cast<Eigen::Index>(xi_rows_.size()));
  } else if (pointwise_magic_ && exact_rows_) {
    kept_.prepare_solved(whitening_);
  }
  warm_.clear();
  blind_checked_ = false;
  prepared_mu_ = mu;
  prepared_ = true;
  return true;
}

void OnlineSolver::set_registered_basis(const cases::Mu& mu) {
  registered_basis(registration_, predicted_support(registration_, mu), R_, Xi_);
  d_bound_ = Xi_.norm() * Theta_c_.norm();
  xi_rows_.clear();
  for (Eigen::Index r = 0; r < Xi_.rows(); ++r) {
    if (!Xi_.row(r).isZero(0.0)) xi_rows_.push_back(static_cast<int>(r));
  }
  Xi_rows_.resize(static_cast<Eigen::Index>(xi_rows_.size()), R_);
  for (std::size_t j = 0; j < xi_rows_.size(); ++j) Xi_rows_.row(static_cast<Eigen::Index>(j)) = Xi_.row(xi_rows_[j]);
}

bool OnlineSolver::exact_rows(ContactRows choice) const {
  return choice == ContactRows::Exact || (choice == ContactRows::Automatic && (row_cone_ || registered_));
}

void OnlineSolver::exact_operators(const Eigen::VectorXd& u_hat, bool with_d) {
  if (pointwise_magic_ && registered_) {  // the rows Xi(mu) weighs, from their own slave nodes
    kept_.evaluate_rows(u_hat, KTheta_, gamma_kept_);
    Dt_.noalias() = KTheta_.transpose() * Xi_rows_;
    dg_.noalias() = Xi_rows_.transpose() * gamma_kept_;
    return;
  }
  if (pointwise_magic_) {  // collocation and LAC-Simpson rows: from the slaves under the kept rows only
    if (with_d) {
      kept_.evaluate_rows(u_hat, KTheta_, gamma_kept_, KE_);
    } else {
      kept_.evaluate_solved_rows(u_hat, gamma_kept_, KE_);
    }
    if (xi_is_identity_) {  // the row cone: generator r is kept row r
      if (with_d) Dt_ = KTheta_.topRows(R_).transpose();
      Et_ = KE_.topRows(R_).transpose();
      dg_ = gamma_kept_.head(R_);
    } else {
      if (with_d) Dt_.noalias() = KTheta_.transpose() * Xi_;
      Et_.noalias() = KE_.transpose() * Xi_;
      dg_.noalias() = Xi_.transpose() * gamma_kept_;
    }
    return;
  }
  w_ = lift_mu_;
  w_.noalias() += Theta_c_ * u_hat;
  // LAC rows: the kept macro-segments only, from their own slave nodes (restricted_rows).
  const bool lac_subset = restricted_ && surface_.discretization == contact::Discretization::LAC;
  const contact::PointwiseContact pw = lac_subset ? contact::project_slave_nodes(mesh_, pair_, w_, lac_kept_positions_)
                                                  : contact::project_slave_nodes(mesh_, pair_, w_);
  const contact::ConstraintRows rows =
      lac_subset ? contact::integrate_lac_rows(mesh_, pair_, quadrature_, pw, w_, kept_rows_)
                 : contact::constraint_rows(mesh_, pair_, quadrature_, pw, w_);
  const Eigen::Index kept = static_cast<Eigen::Index>(kept_rows_.size());
  KTheta_.setZero(kept, N_);
  gamma_kept_.resize(kept);
  for (Eigen::Index i = 0; i < kept; ++i) {
    const int r = kept_rows_[sz(static_cast<int>(i))];
    double kl = 0.0;
    for (RowSparse::InnerIterator it(rows.K, r); it; ++it) {
      KTheta_.row(i) += it.value() * Theta_c_.row(it.col());
      kl += it.value() * lift_mu_(it.col());
    }
    gamma_kept_(i) = rows.g(r) - kl;
  }
  Dt_.noalias() = KTheta_.transpose() * Xi_;
  dg_.noalias() = Xi_.transpose() * gamma_kept_;
}

contact::ConstraintRows OnlineSolver::hf_rows_at(const Eigen::VectorXd& u_hat) {
  w_ = lift_mu_;
  w_.noalias() += Theta_c_ * u_hat;
  const contact::PointwiseContact pw = contact::project_slave_nodes(mesh_, pair_, w_);
  return contact::constraint_rows(mesh_, pair_, quadrature_, pw, w_);
}

const ErrorEstimator::ExactContact& OnlineSolver::exact_contact(const Eigen::VectorXd& u_hat,
                                                                const Eigen::VectorXd& lambda_hat) {
  lambda_rows_.setZero();
  for (std::size_t i = 0; i < kept_rows_.size(); ++i) {
    lambda_rows_(kept_rows_[i]) = Xi_.row(static_cast<Eigen::Index>(i)).dot(lambda_hat);
  }
  if (pointwise_magic_) {
    all_rows_.prepare(mesh_.nodes, quadrature_, lift_mu_);
    all_rows_.evaluate_slack(u_hat, lambda_rows_, slack_rows_, exact_.load);
    // The sparse rows only when the complementary bound asks for them, from the projections
    // evaluate_slack made.
    exact_.rows = [this]() -> const ComplementaryCorrection::RowSparse& {
      all_rows_.assemble_rows(Theta_c_.rows(), estimate_rows_.K);
      return estimate_rows_.K;
    };
  } else {
    estimate_rows_ = hf_rows_at(u_hat);
    exact_.load.noalias() = estimate_rows_.K.transpose() * lambda_rows_;
    slack_rows_ = estimate_rows_.g - estimate_rows_.K * w_;  // (28) - (27): >= 0 where the constraint holds
    exact_.rows = [this]() -> const ComplementaryCorrection::RowSparse& { return estimate_rows_.K; };
  }
  exact_.slack = &slack_rows_;
  exact_.lambda = &lambda_rows_;
  const ConstraintMeasures m = constraint_measures(slack_rows_, lambda_rows_, quadrature_.weight);
  exact_.violation = m.violation;
  exact_.multiplier_norm = m.multiplier_norm;
  exact_.complementarity = m.complementarity;
  return exact_;
}

bool OnlineSolver::step(const Eigen::VectorXd& u_hat, Eigen::VectorXd& u_bar, Eigen::VectorXd& lambda_bar, int& inner,
                        std::string& message) {
  if (exact_rows_) {
    const bool e_given = pointwise_magic_ && !registered_;  // exact_operators set Et_ = L^-1 D' from the solved rows
    // With E given, D' itself serves only the blind test and the inf-sup check of a truncated
    // basis: whether V_N sees the contact does not change between the steps of a query, so the
    // test is made at its first step (check_inf_sup_: at every step, relative_inf_sup reads D').
    const bool with_d = !e_given || check_inf_sup_ || !blind_checked_;
    exact_operators(u_hat, with_d);
    // |D'|_F <= |Theta_c|_F |Xi|_F max_r |K_r| and |K_r| <= 2 |I_r| (a unit normal on the slave
    // node and a partition of unity on the master): the bound of the blind test below.
    if (with_d) {
      const double d_norm = Dt_.norm();
      if (R_ > 0 && d_norm <= kBlindContactTolerance * 2.0 * d_bound_ * quadrature_.weight.maxCoeff()) {
        message = blind_contact_message(d_norm);
        return false;
      }
      blind_checked_ = true;
    }
    return solve_reduced_qp(u_bar, lambda_bar, inner, message, e_given);
  }
  if (pointwise_magic_) {
    magic_.evaluate(u_hat, kappa_hat_, gamma_hat_);
  } else {
    w_ = lift_mu_;
    w_.noalias() += Theta_c_ * u_hat;
    evaluate_magic(w_, lift_mu_, restricted_, kappa_hat_, gamma_hat_);
  }
  // (54): D^kappa = sum_j phi_j C_j, B^kappa phi = kappa_hat; assembled transposed (N x R).
  double d_scale = 0.0;
  if (Mk_ > 0) {
    phi_ = B_kappa_lu_.solve(kappa_hat_);
    Eigen::Map<Eigen::VectorXd>(Dt_.data(), Dt_.size()).noalias() = Ct_ * phi_;
    d_scale = d_bound_ * phi_.cwiseAbs().sum();
  } else {
    Dt_.setZero();
  }
  // When the primal basis does not see the contact (K Theta = 0, e.g. the only POD mode
  // of a patch test has no interface jump), D vanishes and the reduced multipliers are
  // not determined by (53): the QP would return round-off over round-off. Fail instead.
  const double d_norm = Dt_.norm();
  if (R_ > 0 && d_norm <= kBlindContactTolerance * d_scale) {
    message = blind_contact_message(d_norm);
    return false;
  }
  if (Mg_ > 0) {
    phi_gamma_ = B_gamma_lu_.solve(gamma_hat_);
    dg_.noalias() = XiQ_gamma_ * phi_gamma_;
  } else {
    dg_.setZero();
  }
  return solve_reduced_qp(u_bar, lambda_bar, inner, message);
}

bool OnlineSolver::solve_reduced_qp(Eigen::VectorXd& u_bar, Eigen::VectorXd& lambda_bar, int& inner,
                                    std::string& message, bool e_given) {
  // Reduced dual QP with A = L L'. The exact rows: E = L^-1 D' (given from the rows of Theta_c
  // L^-T, or one triangular solve), Q = E'E, c = E' L^-1 f - dg, u_bar = L^-T (L^-1 f - E lambda):
  // one triangular solve per touched contact DOF and query instead of two (docs/offline-online.md,
  // "Cost of a query with the exact rows"). The EIM rows: Y = A^-1 D' (two triangular solves),
  // Q = D Y, c = D A^-1 f - dg (Q = E'E there made the untruncated tests at eps_KA = 1e-10 stall
  // on the multipliers, whose QP is ill-conditioned).
  const bool one_sided = exact_rows_;
  if (!e_given) {
    Et_ = Dt_;
    whitening_.solve_factor(Et_);
    if (!one_sided) whitening_.solve_factor_transpose(Et_);
  }
  const Eigen::MatrixXd& left = one_sided ? Et_ : Dt_;
  // One triangle of Q, mirrored: half the flops of the full product. Small R by inner
  // products: there a blocked product spends its time packing.
  if (R_ <= kInnerProductRows) {
    for (int j = 0; j < R_; ++j) {
      for (int i = j; i < R_; ++i) Q_(i, j) = Q_(j, i) = left.col(i).dot(Et_.col(j));
    }
  } else {
    Q_.triangularView<Eigen::Lower>() = left.transpose() * Et_;
    Q_.triangularView<Eigen::StrictlyUpper>() = Q_.transpose();
  }
  c_.noalias() = left.transpose() * (one_sided ? zl_ : z_);
  c_ -= dg_;
  const solve::QPResult& qp = qp_.solve(Q_, c_, warm_);
  inner = qp.iterations;
  if (qp.status != solve::QPStatus::Solved) {
    message = std::string("reduced contact QP ") + solve::to_string(qp.status) + ": " + qp.message;
    return false;
  }
  warm_ = qp.passive;
  lambda_bar = qp.x;
  if (one_sided) {  // u_bar = L^-T (L^-1 f - E lambda)
    u_bar = zl_;
    u_bar.noalias() -= Et_ * lambda_bar;
    whitening_.solve_factor_transpose(u_bar);
  } else {  // u_bar = A^-1 (f - D' lambda) = z - Y lambda
    u_bar = z_;
    u_bar.noalias() -= Et_ * lambda_bar;
  }
  return true;
}

double OnlineSolver::relative_inf_sup() const {
  // The singular values of L^-1 D' (N x R, A_hat = L L'), not the eigenvalues of Q = D A^-1 D':
  // those would square the condition and put the round-off floor at sqrt(eps) instead of eps.
  if (R_ > N_) return 0.0;
  Eigen::MatrixXd E = Dt_;
  whitening_.solve_factor(E);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(E);
  const Eigen::VectorXd& sigma = svd.singularValues();
  if (!(sigma(0) > 0.0)) return 0.0;
  return sigma(sigma.size() - 1) / sigma(0);
}

std::string OnlineSolver::blind_contact_message(double d_norm) const {
  return std::string("the reduced contact operator ") + (exact_rows_ ? "D" : "D^kappa") + " vanishes (|D| = " +
         number_text(d_norm) +
         "): the primal basis does not see the contact constraints, so the reduced multipliers are undetermined; "
         "rebuild the model with a larger N or with supremizers";
}

std::string OnlineSolver::undetermined_message(double beta) const {
  std::ostringstream os;
  os << std::setprecision(3) << "the reduced pressure is not determined at N = " << N_ << ", R = " << R_ << ": "
     << (R_ > N_ ? "R > N" : "the reduced inf-sup constant is ");
  if (R_ <= N_) os << beta;
  os << " once the N truncation cuts " << N_max_ - N_ << " of the model's " << N_supremizers_
     << " supremizers; use a larger N (the model's is " << N_max_ << ") or R <= N";
  return os.str();
}

void OnlineSolver::set_preconditioners(const ReducedModel& model, const std::vector<int>& order) {
  preconditioner_.clear();
  preconditioner_state_.clear();
  sensitivity_.resize(0, 0);
  const int R_model = registered_ ? model.registration.R() : model.R_max;
  // The Jacobians are those of the map at the maximal sizes; a truncated model's map is another.
  if (model.training_jacobian.size() == 0 || N_ != model.N_max || R_ != R_model) return;
  const Eigen::Index n = N_;
  // Factored here rather than at a point's first query: a query then costs the same whichever
  // queries came before it (one factor costs about five steps).
  preconditioner_.resize(order.size());
  preconditioner_state_.assign(order.size(), 0);
  for (std::size_t p = 0; p < order.size(); ++p) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Eigen::MatrixXd::Identity(n, n) -
                                                  model.training_jacobian.middleCols(order[p] * n, n));
    preconditioner_[p] = lu.inverse();
    // G'_p with an eigenvalue at 1 (I - G'_p singular): no preconditioner at that point.
    preconditioner_state_[p] = preconditioner_[p].allFinite() ? 1 : 2;
  }
  const Eigen::Index p_dim = model.num_parameters();
  if (model.training_u_sensitivity.size() == 0 || p_dim < 2) return;
  sensitivity_.resize(n, p_dim * static_cast<Eigen::Index>(order.size()));
  for (std::size_t p = 0; p < order.size(); ++p) {
    sensitivity_.middleCols(static_cast<Eigen::Index>(p) * p_dim, p_dim) =
        model.training_u_sensitivity.middleCols(order[p] * p_dim, p_dim);
  }
}

const Eigen::MatrixXd* OnlineSolver::preconditioner(Eigen::Index p) const {
  if (preconditioner_.empty() || p < 0) return nullptr;
  const std::size_t k = sz(static_cast<int>(p));
  return preconditioner_state_[k] == 1 ? &preconditioner_[k] : nullptr;
}

Eigen::Index OnlineSolver::nearest_training(const cases::Mu& point) const {
  if (guess_.cols() == 0) return -1;
  // A plain loop: a colwise expression over p = 2-3 rows spends its time in per-column reductions.
  const Eigen::Index P = guess_points_.cols(), p = guess_points_.rows();
  const Eigen::VectorXd x = (point - guess_offset_).cwiseProduct(guess_scale_);
  const double* xs = x.data();
  Eigen::Index best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (Eigen::Index c = 0; c < P; ++c) {
    const double* g = guess_points_.col(c).data();
    double d2 = 0.0;
    for (Eigen::Index k = 0; k < p; ++k) d2 += (g[k] - xs[k]) * (g[k] - xs[k]);
    if (d2 < best_d2) {  // ties: the first
      best_d2 = d2;
      best = c;
    }
  }
  return best;
}

Eigen::MatrixXd OnlineSolver::fixed_point_jacobian(const cases::Mu& mu, const Eigen::VectorXd& u_hat) {
  cases::check_mu(parameters_, mu, "the reduced model");
  require(u_hat.size() == N_, "OnlineSolver::fixed_point_jacobian: u_hat has size " + std::to_string(u_hat.size()) +
                                  ", expected N = " + std::to_string(N_));
  require(exact_rows(ContactRows::Automatic),
          "OnlineSolver::fixed_point_jacobian: the model's dual cone is not solved on the exact contact rows");
  std::string message;
  require(prepare(mu, true, true, message), "OnlineSolver::fixed_point_jacobian: " + message);
  Eigen::VectorXd base(N_), shifted(N_), lambda(R_), u = u_hat;
  int inner = 0;
  const auto take_step = [&](const Eigen::VectorXd& at, Eigen::VectorXd& out, const std::vector<int>& start) {
    warm_ = start;
    require(step(at, out, lambda, inner, message), "OnlineSolver::fixed_point_jacobian: " + message);
  };
  take_step(u, base, {});
  const std::vector<int> passive = warm_;
  // Forward differences: the step is exact (a QP solved to round-off), so h = 1e-7 |u_hat|
  // leaves about 1e-9 relative error, far below what a preconditioner needs.
  const double h = 1e-7 * std::max(1.0, u_hat.norm());
  Eigen::MatrixXd J(N_, N_);
  for (int i = 0; i < N_; ++i) {
    u(i) += h;
    take_step(u, shifted, passive);
    u(i) = u_hat(i);
    J.col(i) = (shifted - base) / h;
  }
  prepared_ = false;  // surface_gap refers to the last solve, not to these steps
  return J;
}

Eigen::VectorXd OnlineSolver::interpolated_guess(const cases::Mu& point) const {
  const Eigen::Index P = guess_.cols();
  if (P == 0) return Eigen::VectorXd::Zero(N_ + R_);
  if (point.size() > 1) {  // the nearest point (ties: the first), to first order where the model has S
    const Eigen::Index i = nearest_training(point);
    Eigen::VectorXd guess = guess_.col(i);
    if (sensitivity_.size() > 0) {
      const Eigen::Index p = point.size();
      guess.head(N_).noalias() += sensitivity_.middleCols(i * p, p) * (point - guess_mu_points_.col(i));
    }
    return guess;
  }
  const double mu = point(0);
  const auto hi = static_cast<Eigen::Index>(std::upper_bound(guess_mu_.begin(), guess_mu_.end(), mu) - guess_mu_.begin());
  if (hi == 0) return guess_.col(0);
  if (hi == P) return guess_.col(P - 1);
  const double a = guess_mu_[sz(static_cast<int>(hi - 1))], b = guess_mu_[sz(static_cast<int>(hi))];
  const double t = b > a ? (mu - a) / (b - a) : 0.0;
  return (1.0 - t) * guess_.col(hi - 1) + t * guess_.col(hi);
}

solve::KacanovResult OnlineSolver::iterate_accelerated(const solve::KacanovSettings& ks, int depth,
                                                       const Eigen::VectorXd& u_start,
                                                       const Eigen::VectorXd& lambda_start,
                                                       const Eigen::MatrixXd* pre) {
  solve::KacanovResult result;
  if (dU_.cols() < depth) {
    dU_.resize(N_, depth);
    dR_.resize(N_, depth);
    dL_.resize(R_, depth);
  }
  // Safeguard floor: the damping the HF snapshots needed.
  const double beta_min = std::min(1.0, kacanov_alpha_);
  double beta = 1.0;
  int m = 0;     // history columns in use
  int next = 0;  // circular position of the next column
  double r_prev_norm = 0.0;
  u_ = u_start;
  lambda_prev_ = lambda_start;
  // Zero, not uninitialized: a first step that fails leaves them as they are, and they are
  // returned (a model with M^k = 0 printed heap garbage as lambda_hat and contact_force).
  result.u_bar.setZero(N_);
  result.lambda_bar.setZero(R_);
  for (int k = 1; k <= ks.max_iterations; ++k) {
    solve::KacanovIteration it;
    std::string message;
    if (!step(u_, result.u_bar, result.lambda_bar, it.step_iterations, message)) {
      result.status = solve::KacanovStatus::StepFailed;
      result.iterations = k;
      result.message = "Kacanov iteration " + std::to_string(k) + " failed: " + message;
      return result;
    }
    if (!result.u_bar.allFinite() || !result.lambda_bar.allFinite()) {  // a NaN passes no test: stop here
      result.status = solve::KacanovStatus::NonFinite;
      result.iterations = k;
      result.message = "Kacanov iteration " + std::to_string(k) + ": the reduced solution is not finite";
      return result;
    }
    r_ = result.u_bar - u_;
    // (63) at alpha = 1 (see OnlineIteration::Accelerated).
    it.du = solve::relative_increment(result.u_bar, u_);
    it.dlambda = solve::relative_increment(result.lambda_bar, lambda_prev_);
    result.history.push_back(it);
    if (std::max(it.du, it.dlambda) <= ks.tolerance) {
      result.status = solve::KacanovStatus::Converged;
      result.iterations = k;
      result.u = result.u_bar;
      result.lambda = result.lambda_bar;
      return result;
    }
    // Newton-like steps: u + (I - G'_p)^-1 (G(u) - u) is Newton's step on G(u) - u = 0 with the
    // Jacobian of the nearest training point (OnlineSettings::preconditioned).
    if (pre != nullptr) {
      pr_.noalias() = *pre * r_;
      r_.swap(pr_);
    }
    double r_norm = r_.norm();
    if (k > 1) {
      if (r_norm >= r_prev_norm) {
        // Safeguard: no decrease of the residual. Forget the history (and the preconditioner,
        // which does not fit this point), damp more.
        if (pre != nullptr) {
          pre = nullptr;
          r_ = result.u_bar - u_;
          r_norm = r_.norm();
        }
        m = 0;
        next = 0;
        beta = std::max(0.5 * beta, beta_min);
      } else if (depth > 0) {
        dU_.col(next) = u_ - u_prev_;
        dR_.col(next) = r_ - r_prev_;
        dL_.col(next) = result.lambda_bar - lambda_prev_;
        next = (next + 1) % depth;
        m = std::min(m + 1, depth);
      }
    }
    u_prev_ = u_;
    r_prev_ = r_;
    r_prev_norm = r_norm;
    lambda_prev_ = result.lambda_bar;
    // Anderson (type II): gamma = argmin |r - dR gamma|, u <- u + beta r - (dU + beta dR) gamma.
    u_ += beta * r_;
    if (m > 0) {
      using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 8, 8>;
      using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 8, 1>;
      Small G(m, m);
      SmallVec b(m);
      for (int i = 0; i < m; ++i) {
        b(i) = dR_.col(i).dot(r_);
        for (int j = 0; j <= i; ++j) G(i, j) = G(j, i) = dR_.col(i).dot(dR_.col(j));
      }
      // Normal equations of at most 8 columns; a relative ridge keeps a nearly dependent
      // history harmless (its columns then get small coefficients).
      G.diagonal().array() += 1e-12 * G.diagonal().maxCoeff();
      const Eigen::LLT<Small> small(G);
      if (small.info() == Eigen::Success) {
        const SmallVec gamma = small.solve(b);
        for (int i = 0; i < m; ++i) u_ -= gamma(i) * (dU_.col(i) + beta * dR_.col(i));
      }
    }
  }
  result.status = solve::KacanovStatus::MaxIterations;
  result.iterations = ks.max_iterations;
  const solve::KacanovIteration& last = result.history.back();
  result.message = "Kacanov (accelerated) did not converge in " + std::to_string(ks.max_iterations) +
                   " iterations (last relative residuals: displacement " + number_text(last.du) +
                   ", multipliers " + number_text(last.dlambda) + ", tolerance " + number_text(ks.tolerance) + ")";
  return result;
}

OnlineSolution OnlineSolver::solve(const cases::Mu& mu, const OnlineSettings& settings) {
  const auto t0 = Clock::now();
  cases::check_mu(parameters_, mu, "the reduced model");
  const solve::KacanovSettings ks =
      settings.kacanov ? *settings.kacanov
                       : solve::KacanovSettings{kacanov_alpha_,
                                                exact_rows(settings.contact_rows) ? kExactRowsTolerance
                                                                                  : kacanov_tolerance_,
                                                kacanov_max_iterations_};
  solve::check_settings(ks);
  require(settings.anderson_depth >= 0 && settings.anderson_depth <= 8,
          "OnlineSettings::anderson_depth must be in [0, 8] (got " + std::to_string(settings.anderson_depth) + ")");
  if (settings.start && (settings.start->size() != N_ + R_ || !settings.start->allFinite())) {
    throw Error("OnlineSettings::start must be a finite [u_hat; lambda_hat] of size N + R = " + std::to_string(N_) +
                " + " + std::to_string(R_) + " = " + std::to_string(N_ + R_) + " (got " +
                std::to_string(settings.start->size()) + " entries" +
                (settings.start->size() == N_ + R_ ? ", not all finite)" : ")"));
  }
  const bool accelerated = settings.iteration == OnlineIteration::Accelerated ||
                           (settings.iteration == OnlineIteration::Automatic && !settings.kacanov);
  qp_.set_settings(settings.qp);

  // The EIM arrays of a registered model are those of its rows, not of Xi(mu); a model without
  // an EIM of kappa (M^k = 0: the row and registered cones) has no EIM contact operator (54).
  require(exact_rows(settings.contact_rows) || (!registered_ && Mk_ > 0),
          registered_ ? "OnlineSolver: a registered-cone model is solved on the exact contact rows only (ContactRows::Eim asked)"
                      : "OnlineSolver: a model without an EIM of kappa (M^k = 0: the row cone) is solved on the exact "
                        "contact rows only (ContactRows::Eim asked)");
  OnlineSolution sol;
  if (!prepare(mu, settings.restricted_rows, exact_rows(settings.contact_rows), sol.message)) {
    sol.u_hat = Eigen::VectorXd::Zero(N_);
    sol.lambda_hat = Eigen::VectorXd::Zero(R_);
    sol.energy = E_D_;  // of u_hat = 0 (prepare sets E_D_ before the factorization)
    sol.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return sol;
  }

  // [u_hat; lambda_hat] to start from; lambda only enters the first stopping test.
  const Eigen::VectorXd start = settings.start                                          ? *settings.start
                                : settings.initial_guess == InitialGuess::Interpolated ? interpolated_guess(mu)
                                                                                       : Eigen::VectorXd::Zero(N_ + R_);
  const Eigen::VectorXd u_start = start.head(N_), lambda_start = start.tail(R_);
  // The first reduced QP starts from the guess's support (the QP is exact from any start).
  for (int i = 0; i < R_; ++i) {
    if (lambda_start(i) > 0.0) warm_.push_back(i);
  }
  solve::KacanovResult kr;
  try {
    if (settings.iteration == OnlineIteration::Newton) {
      require(exact_rows_, "OnlineSolver: the Newton iteration needs the exact contact rows (ContactRows::Exact)");
      kr = iterate_newton(ks, u_start, lambda_start);
    } else if (accelerated) {
      const Eigen::MatrixXd* pre =
          settings.preconditioned && exact_rows_ && !preconditioner_.empty() ? preconditioner(nearest_training(mu)) : nullptr;
      kr = iterate_accelerated(ks, settings.anderson_depth, u_start, lambda_start, pre);
    } else {
      const solve::KacanovStep step_fn = [this](const Eigen::VectorXd& u_hat, const Eigen::VectorXd&,
                                                Eigen::VectorXd& u_bar, Eigen::VectorXd& lambda_bar, int& inner,
                                                std::string& message) {
        return step(u_hat, u_bar, lambda_bar, inner, message);
      };
      kr = solve::kacanov(step_fn, u_start, lambda_start, ks);
    }
  } catch (const Error& e) {  // e.g. a degenerate deformed master segment
    kr.status = solve::KacanovStatus::StepFailed;
    kr.message = e.what();
  }
  sol.status = kr.status;
  sol.message = kr.message;
  sol.iterations = kr.iterations;
  sol.u_hat = kr.u_bar.size() == N_ && kr.u_bar.allFinite() ? kr.u_bar : Eigen::VectorXd::Zero(N_);
  sol.lambda_hat =
      kr.lambda_bar.size() == R_ && kr.lambda_bar.allFinite() ? kr.lambda_bar : Eigen::VectorXd::Zero(R_);
  sol.energy = 0.5 * sol.u_hat.dot(A_ * sol.u_hat) - f_.dot(sol.u_hat) + E_D_;
  double force = 0.0;  // sum_r |I_r|(mu) (Xi lambda_hat)_r
  for (std::size_t i = 0; i < kept_rows_.size(); ++i) {
    weight_kept_(static_cast<Eigen::Index>(i)) = quadrature_.weight(kept_rows_[i]);
    force += weight_kept_(static_cast<Eigen::Index>(i)) * Xi_.row(static_cast<Eigen::Index>(i)).dot(sol.lambda_hat);
  }
  sol.contact_force = force;
  // A finite reduced solution can still overflow the energy: not an answer, never "converged".
  if (sol.converged() && (!std::isfinite(sol.energy) || !std::isfinite(sol.contact_force))) {
    sol.status = solve::KacanovStatus::NonFinite;
    sol.message = "the energy or the contact force of the reduced solution is not finite (energy " +
                  number_text(sol.energy) + ", contact force " + number_text(sol.contact_force) + ")";
  }
  if (check_inf_sup_ && sol.converged()) {
    const double beta = relative_inf_sup();
    if (!(beta > kInfSupTolerance)) {
      sol.status = solve::KacanovStatus::StepFailed;
      sol.message = undetermined_message(beta);
    }
  }
  // The EIM estimate at the last linearization (phi_, phi_gamma_ of the last step), as the
  // returned pair is that linearization's solution; the exact one at the returned u_hat's rows.
  if (settings.error_estimate && sol.converged()) {
    sol.estimate = exact_rows_ ? estimator_.evaluate_exact(mu, sol.u_hat, exact_contact(sol.u_hat, sol.lambda_hat))
                               : estimator_.evaluate(mu, sol.u_hat, sol.lambda_hat, phi_, phi_gamma_, weight_kept_);
  }
  sol.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return sol;
}

const char* to_string(OnlineIteration value) {
  switch (value) {
    case OnlineIteration::Automatic: return "automatic";
    case OnlineIteration::Relaxed: return "relaxed";
    case OnlineIteration::Accelerated: return "accelerated";
    case OnlineIteration::Newton: return "newton";
  }
  return "unknown";
}

OnlineIteration online_iteration_from_string(const std::string& name) {
  using enum OnlineIteration;
  return enum_from_string(name, "online iteration", std::array{Automatic, Relaxed, Accelerated, Newton});
}

const char* to_string(InitialGuess value) {
  switch (value) {
    case InitialGuess::Interpolated: return "interpolated";
    case InitialGuess::Zero: return "zero";
  }
  return "unknown";
}

InitialGuess initial_guess_from_string(const std::string& name) {
  return enum_from_string(name, "initial guess", std::array{InitialGuess::Interpolated, InitialGuess::Zero});
}

}  // namespace contactrb::online
