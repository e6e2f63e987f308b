#include "contactrb/rb/online_solver.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "contactrb/cases/geometric_map.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/projection.hpp"

namespace contactrb::rb {

namespace {
// |D|_F below this fraction of its cancellation-free bound: the reduced constraints are blind.
constexpr double kBlindContactTolerance = 1e-10;
}  // namespace

namespace {
using Clock = std::chrono::steady_clock;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using WRow = RowSparse::InnerIterator;  // rows of the quadrature W (R x S, row-major)
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
  R_ = resolve(sizes.R, model.R_max, model.R_max > 0 ? 1 : 0, "R");
  Mk_ = resolve(sizes.Mk, model.Mk_max, model.Mk_max > 0 ? 1 : 0, "Mk");
  Mg_ = resolve(sizes.Mg, model.Mg_max, model.Mg_max > 0 ? 1 : 0, "Mg");
  parameter_ = model.parameter;
  thetas_ = model.thetas;
  kacanov_alpha_ = model.kacanov_alpha;
  kacanov_tolerance_ = model.kacanov_tolerance;
  kacanov_max_iterations_ = model.kacanov_max_iterations;
  for (const auto& A : model.A_hat) A_hat_.push_back(A.topLeftCorner(N_, N_));
  for (const auto& f : model.f_hat) f_hat_.push_back(f.head(N_));
  for (const auto& f : model.A_lift_hat) A_lift_hat_.push_back(f.head(N_));
  lift_AA_ = model.lift_AA;
  lift_f_ = model.lift_f;
  for (int j = 0; j < Mk_; ++j) C_.push_back(model.C_kappa[sz(j)].topLeftCorner(R_, N_));
  // The leading M x M block of B is the B of the first M EIM functions (B is lower triangular).
  if (Mk_ > 0) B_kappa_lu_.compute(model.B_kappa.topLeftCorner(Mk_, Mk_));
  if (Mg_ > 0) B_gamma_lu_.compute(model.B_gamma.topLeftCorner(Mg_, Mg_));
  XiQ_gamma_ = model.XiQ_gamma.topLeftCorner(R_, Mg_);
  Xi_ = model.Xi.leftCols(R_);
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
  needed_rows_ = kappa_row_;
  needed_rows_.insert(needed_rows_.end(), gamma_row_.begin(), gamma_row_.end());
  std::sort(needed_rows_.begin(), needed_rows_.end());
  needed_rows_.erase(std::unique(needed_rows_.begin(), needed_rows_.end()), needed_rows_.end());
}

void OnlineSolver::prepare_restriction() {
  // Slave positions s with W(r, s) != 0 for a needed row r (the pattern of W; its values
  // depend on mu through the edge lengths).
  std::vector<int> slave_positions;
  for (int r : needed_rows_) {
    for (WRow it(quadrature_.W, r); it; ++it) {
      slave_positions.push_back(static_cast<int>(it.col()));
    }
  }
  std::sort(slave_positions.begin(), slave_positions.end());
  slave_positions.erase(std::unique(slave_positions.begin(), slave_positions.end()), slave_positions.end());
  restricted_pair_.master = pair_.master;
  restricted_pair_.slave.clear();
  restricted_slave_position_ = slave_positions;
  for (int s : slave_positions) restricted_pair_.slave.push_back(pair_.slave[sz(s)]);
}

void OnlineSolver::evaluate_magic_restricted(const Eigen::VectorXd& w, const Eigen::VectorXd& lift_c,
                                             Eigen::VectorXd& kappa_hat, Eigen::VectorXd& gamma_hat) const {
  // Few slave nodes: all-pairs search beats building the segment tree every iteration (both
  // return the same projection, projection.hpp).
  contact::ProjectionOptions options;
  options.search = contact::SearchMethod::AllPairs;
  const contact::PointwiseContact pw = contact::project_slave_nodes(mesh_, restricted_pair_, w, options);
  // Position of each slave chain entry in the restricted pair.
  auto local = [&](int s) {
    const auto it = std::lower_bound(restricted_slave_position_.begin(), restricted_slave_position_.end(), s);
    return static_cast<int>(it - restricted_slave_position_.begin());
  };
  // K[r, dof] = sum_s W(r, s) K_pt[s, dof] (collocation and LAC-Simpson rows, (10)-(11)).
  auto K_entry = [&](int r, int dof) {
    double v = 0.0;
    for (WRow it(quadrature_.W, r); it; ++it) {
      v += it.value() * pw.K.coeff(local(static_cast<int>(it.col())), dof);
    }
    return v;
  };
  kappa_hat.resize(Mk_);
  for (int i = 0; i < Mk_; ++i) kappa_hat(i) = K_entry(kappa_row_[sz(i)], kappa_dof_[sz(i)]);
  gamma_hat.resize(Mg_);
  for (int i = 0; i < Mg_; ++i) {
    const int r = gamma_row_[sz(i)];
    double g = 0.0;
    for (WRow it(quadrature_.W, r); it; ++it) {
      const int l = local(static_cast<int>(it.col()));
      g += it.value() * (pw.g(l) - row_dot(pw.K, l, lift_c));
    }
    gamma_hat(i) = g;
  }
}

void OnlineSolver::evaluate_magic(const Eigen::VectorXd& w, const Eigen::VectorXd& lift_c, Eigen::VectorXd& kappa_hat,
                                  Eigen::VectorXd& gamma_hat) const {
  const contact::PointwiseContact pw = contact::project_slave_nodes(mesh_, pair_, w);
  const contact::ConstraintRows rows = contact::constraint_rows(mesh_, pair_, quadrature_, pw, w);
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

OnlineSolution OnlineSolver::solve(double mu, const OnlineSettings& settings) {
  const auto t0 = Clock::now();
  parameter_.check(mu, "reduced model online solve");
  const solve::KacanovSettings ks =
      settings.kacanov ? *settings.kacanov
                       : solve::KacanovSettings{kacanov_alpha_, kacanov_tolerance_, kacanov_max_iterations_};
  solve::check_settings(ks);
  qp_.set_settings(settings.qp);

  // Omega(mu) on the contact surface: h_body(mu) applied to the reference chain nodes.
  const std::array<cases::AffineMap, 2> maps = cases::geometric_maps(parameter_, mu);
  for (std::size_t i = 0; i < mesh_.nodes.size(); ++i) {
    mesh_.nodes[i] = maps[sz(surface_.body[i])](surface_.reference_nodes[i]);
  }
  quadrature_ = contact::make_quadrature(mesh_, pair_, surface_.discretization);
  require(quadrature_.W.rows() == surface_.num_constraints,
          "OnlineSolver: the contact surface gives " + std::to_string(quadrature_.W.rows()) +
              " constraints, the model " + std::to_string(surface_.num_constraints));
  const bool restricted = settings.restricted_rows && surface_.discretization != contact::Discretization::LAC;
  if (restricted) prepare_restriction();

  // (49)
  const Eigen::VectorXd ta = cases::evaluate(thetas_.a, mu);
  const Eigen::VectorXd tf = cases::evaluate(thetas_.f, mu);
  const Eigen::VectorXd tl = cases::evaluate(thetas_.lift, mu);
  const int Ja = static_cast<int>(A_hat_.size()), Jf = static_cast<int>(f_hat_.size());
  const int JD = static_cast<int>(tl.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N_, N_);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(N_);
  double E_D = 0.0;
  for (int j = 0; j < Ja; ++j) {
    A += ta(j) * A_hat_[sz(j)];
    for (int k = 0; k < JD; ++k) {
      f -= ta(j) * tl(k) * A_lift_hat_[sz(j * JD + k)];
      for (int l = 0; l < JD; ++l) E_D += 0.5 * ta(j) * tl(k) * tl(l) * lift_AA_[sz((j * JD + k) * JD + l)];
    }
  }
  for (int j = 0; j < Jf; ++j) {
    f += tf(j) * f_hat_[sz(j)];
    for (int k = 0; k < JD; ++k) E_D -= tf(j) * tl(k) * lift_f_[sz(j * JD + k)];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(A);
  OnlineSolution sol;
  if (llt.info() != Eigen::Success) {
    sol.message = "A_hat(mu) is not positive definite";
    sol.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return sol;
  }
  const Eigen::VectorXd z = llt.solve(f);  // A_hat^-1 f_hat
  const Eigen::VectorXd lift_c = JD > 0 ? Eigen::VectorXd(lift_c_ * tl) : Eigen::VectorXd::Zero(lift_c_.rows());

  std::vector<int> warm;
  Eigen::VectorXd kappa_hat, gamma_hat, w;
  Eigen::MatrixXd D(R_, N_), Y, Q;
  solve::KacanovStep step = [&](const Eigen::VectorXd& u_hat, const Eigen::VectorXd&, Eigen::VectorXd& u_bar,
                                Eigen::VectorXd& lambda_bar, int& inner, std::string& message) {
    w = lift_c + Theta_c_ * u_hat;
    if (restricted) {
      evaluate_magic_restricted(w, lift_c, kappa_hat, gamma_hat);
    } else {
      evaluate_magic(w, lift_c, kappa_hat, gamma_hat);
    }
    // (54): D^kappa = sum_j phi_j C_j, B^kappa phi = kappa_hat.
    D.setZero();
    double d_scale = 0.0;
    if (Mk_ > 0) {
      const Eigen::VectorXd phi = B_kappa_lu_.solve(kappa_hat);
      for (int j = 0; j < Mk_; ++j) D += phi(j) * C_[sz(j)];
      // Upper bound of |D|_F without cancellation: |Xi| |Q_j| |Theta_c| with |q_j|_inf = 1.
      d_scale = Xi_.norm() * Theta_c_.norm() * phi.cwiseAbs().sum();
    }
    // When the primal basis does not see the contact (K Theta = 0, e.g. the only POD mode
    // of a patch test has no interface jump), D vanishes and the reduced multipliers are
    // not determined by (53): the QP would return round-off over round-off. Fail instead.
    if (R_ > 0 && D.norm() <= kBlindContactTolerance * d_scale) {
      message = "the reduced contact operator D^kappa vanishes (|D| = " + std::to_string(D.norm()) +
                "): the primal basis does not see the contact constraints, so the reduced multipliers "
                "are undetermined; rebuild the model with a larger N";
      return false;
    }
    Eigen::VectorXd dg = Eigen::VectorXd::Zero(R_);
    if (Mg_ > 0) dg = XiQ_gamma_ * B_gamma_lu_.solve(gamma_hat);
    // Reduced dual QP: Q = D A^-1 D', c = D A^-1 f - D^gamma gamma_hat.
    Y = llt.solve(D.transpose());
    Q = D * Y;
    Q = 0.5 * (Q + Q.transpose()).eval();
    const Eigen::VectorXd c = D * z - dg;
    const solve::QPResult& qp = qp_.solve(Q, c, warm);
    inner = qp.iterations;
    if (qp.status != solve::QPStatus::Solved) {
      message = std::string("reduced contact QP ") + solve::to_string(qp.status) + ": " + qp.message;
      return false;
    }
    warm = qp.passive;
    lambda_bar = qp.x;
    u_bar = z - Y * lambda_bar;
    return true;
  };
  solve::KacanovResult kr;
  try {
    kr = solve::kacanov(step, Eigen::VectorXd::Zero(N_), Eigen::VectorXd::Zero(R_), ks);
  } catch (const Error& e) {  // e.g. a degenerate deformed master segment
    kr.status = solve::KacanovStatus::StepFailed;
    kr.message = e.what();
  }
  sol.status = kr.status;
  sol.message = kr.message;
  sol.iterations = kr.iterations;
  sol.u_hat = kr.u_bar.size() == N_ ? kr.u_bar : Eigen::VectorXd::Zero(N_);
  sol.lambda_hat = kr.lambda_bar.size() == R_ ? kr.lambda_bar : Eigen::VectorXd::Zero(R_);
  sol.energy = 0.5 * sol.u_hat.dot(A * sol.u_hat) - f.dot(sol.u_hat) + E_D;
  Eigen::VectorXd w_kept(static_cast<Eigen::Index>(kept_rows_.size()));
  for (std::size_t i = 0; i < kept_rows_.size(); ++i) w_kept(static_cast<Eigen::Index>(i)) = quadrature_.weight(kept_rows_[i]);
  sol.contact_force = (Xi_.transpose() * w_kept).dot(sol.lambda_hat);
  sol.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return sol;
}

}  // namespace contactrb::rb
