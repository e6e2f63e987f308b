// The reduced semi-smooth Newton iteration (OnlineIteration::Newton, docs/offline-online.md,
// "Online"): the HF Newton's equations (docs/solvers.md, "Semi-smooth Newton") on the reduced
// unknowns, with the exact contact rows of the kept rows and their consistent linearization.
//
//   F(u_hat, lambda_hat) = A_hat u_hat + Theta_c' K(w)' Xi lambda_hat - f_hat = 0,
//   min(lambda_hat_k, c_k s_k) = 0,   s = Xi' d(w),  d(w) = g(w) - K(w) w on the kept rows,
//
// with w = u_D(mu) + Theta_c u_hat. Active generators (lambda_hat_k - c_k s_k > 0) keep s_k = 0,
// the others lambda_hat_k = 0; the step solves
//
//   [ A_hat + Theta_c' H Theta_c   B' ] [du]   = - [ F   ]      B = Xi' K Theta_c,
//   [ G_A                          0  ] [dl_A]     [ s_A ]      G = Xi' d'(w) Theta_c,
//
// H the geometric stiffness of the contact forces (contact_linearization.hpp), dl = -lambda_hat
// on the inactive generators. c_k = 1 / Q_kk with Q = B A_hat^-1 B' (a pressure per gap).
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/online/online_solver.hpp"

namespace contactrb::online {

namespace {
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }
using RowSparseW = Eigen::SparseMatrix<double, Eigen::RowMajor>;
}  // namespace

struct OnlineSolver::NewtonSystem {
  Eigen::MatrixXd J;   // N x N: A_hat + Theta_c' H Theta_c
  Eigen::MatrixXd B;   // R x N: Xi' K Theta_c (the force rows)
  Eigen::MatrixXd G;   // R x N: Xi' d' Theta_c (the gap rows' derivative)
  Eigen::VectorXd F;   // N: the equilibrium residual
  Eigen::VectorXd s;   // R: Xi' d on the kept rows
};

// J += Theta_c' H Theta_c over the contact DOFs H touches only (the nodes of the active rows and
// their master segments: a few of the n_c).
void OnlineSolver::add_geometric_stiffness(const Eigen::SparseMatrix<double>& H, Eigen::MatrixXd& J) const {
  std::vector<int> slot(sz(static_cast<int>(H.cols())), -1), dofs;
  for (Eigen::Index k = 0; k < H.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, k); it; ++it) {
      for (const Eigen::Index d : {it.row(), it.col()}) {
        if (slot[sz(static_cast<int>(d))] < 0) {
          slot[sz(static_cast<int>(d))] = static_cast<int>(dofs.size());
          dofs.push_back(static_cast<int>(d));
        }
      }
    }
  }
  if (dofs.empty()) return;
  const Eigen::Index m = static_cast<Eigen::Index>(dofs.size());
  Eigen::MatrixXd Hs = Eigen::MatrixXd::Zero(m, m), Ts(m, N_);
  for (Eigen::Index k = 0; k < H.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, k); it; ++it) {
      Hs(slot[sz(static_cast<int>(it.row()))], slot[sz(static_cast<int>(it.col()))]) += it.value();
    }
  }
  for (Eigen::Index i = 0; i < m; ++i) Ts.row(i) = Theta_c_.row(dofs[sz(static_cast<int>(i))]);
  J.noalias() += Ts.transpose() * (Hs * Ts);
}

void OnlineSolver::setup_kept_pair() {
  kept_pair_ = {};
  kept_column_.assign(surface_.slave.size(), -1);
  if (surface_.discretization == contact::Discretization::LAC) return;
  // The sparsity of W does not depend on mu: read it on the reference chain.
  const contact::ContactQuadrature reference = contact::make_quadrature(mesh_, pair_, surface_.discretization);
  for (const int r : kept_rows_) {
    for (RowSparseW::InnerIterator it(reference.W, r); it; ++it) kept_column_[sz(static_cast<int>(it.col()))] = 0;
  }
  for (std::size_t s = 0; s < kept_column_.size(); ++s) {
    if (kept_column_[s] < 0) continue;
    kept_column_[s] = static_cast<int>(kept_pair_.slave.size());
    kept_pair_.slave.push_back(surface_.slave[s]);
  }
  kept_pair_.master = surface_.master;
}

void OnlineSolver::restrict_quadrature() {
  if (kept_pair_.slave.empty()) return;
  const Eigen::Index kept = static_cast<Eigen::Index>(kept_rows_.size());
  std::vector<Eigen::Triplet<double>> t;
  kept_quadrature_.discretization = quadrature_.discretization;
  kept_quadrature_.weight.resize(kept);
  kept_quadrature_.center_node.clear();
  for (Eigen::Index i = 0; i < kept; ++i) {
    const int r = kept_rows_[sz(static_cast<int>(i))];
    for (RowSparseW::InnerIterator it(quadrature_.W, r); it; ++it) {
      t.emplace_back(static_cast<int>(i), kept_column_[sz(static_cast<int>(it.col()))], it.value());
    }
    kept_quadrature_.weight(i) = quadrature_.weight(r);
    kept_quadrature_.center_node.push_back(quadrature_.center_node[sz(r)]);
  }
  kept_quadrature_.W.resize(kept, static_cast<Eigen::Index>(kept_pair_.slave.size()));
  kept_quadrature_.W.setFromTriplets(t.begin(), t.end());
}

void OnlineSolver::newton_system(const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda_hat, NewtonSystem& sys) {
  w_ = lift_mu_;
  w_.noalias() += Theta_c_ * u_hat;
  const Eigen::VectorXd lambda_kept = Xi_ * lambda_hat;
  const Eigen::Index kept = static_cast<Eigen::Index>(kept_rows_.size());
  Eigen::MatrixXd K_Theta(kept, N_), D_Theta(kept, N_);
  Eigen::VectorXd d(kept);
  // Pointwise rows: the kept rows from their own slave nodes (row i of the linearization is
  // kept row i); LAC rows: the whole surface, then the kept rows picked.
  const bool restricted = !kept_pair_.slave.empty();
  Eigen::VectorXd lambda = lambda_kept;
  if (!restricted) {
    lambda.setZero(surface_.num_constraints);
    for (Eigen::Index i = 0; i < kept; ++i) lambda(kept_rows_[sz(static_cast<int>(i))]) = lambda_kept(i);
  }
  const contact::ContactLinearization lin =
      restricted ? contact::linearize_contact(mesh_, kept_pair_, kept_quadrature_, w_, lambda, movable_)
                 : contact::linearize_contact(mesh_, pair_, quadrature_, w_, lambda, movable_);
  for (Eigen::Index i = 0; i < kept; ++i) {
    const Eigen::Index r = restricted ? i : kept_rows_[sz(static_cast<int>(i))];
    K_Theta.row(i) = lin.maps.rows.K.row(r) * Theta_c_;
    D_Theta.row(i) = lin.D.row(r) * Theta_c_;
    d(i) = lin.maps.d(r);
  }
  sys.B.noalias() = Xi_.transpose() * K_Theta;
  sys.G.noalias() = Xi_.transpose() * D_Theta;
  sys.s.noalias() = Xi_.transpose() * d;
  sys.J = A_;
  add_geometric_stiffness(lin.H, sys.J);
  sys.F = A_ * u_hat - f_;
  sys.F.noalias() += sys.B.transpose() * lambda_hat;
}

// At the fixed point u_bar = u_hat of the step with the active generators a fixed: the step
// solves [A_hat B_a(u)'; B_a(u) 0] [u_bar; l_a] = [f_hat; gamma_a(u)], and its derivative at
// u_bar = u_hat is [A_hat B_a'; B_a 0] [du_bar; dl_a] = [-Theta_c' H Theta_c du; (G_a + B_a) du]
// (d(B'l)/du = Theta_c' H Theta_c, d(gamma - B u)/du = G at u_bar = u).
Eigen::MatrixXd OnlineSolver::linearized_fixed_point_jacobian(const cases::Mu& mu, const Eigen::VectorXd& u_hat,
                                                              const Eigen::VectorXd& lambda_hat) {
  cases::check_mu(parameters_, mu, "the reduced model");
  require(u_hat.size() == N_ && lambda_hat.size() == R_,
          "OnlineSolver::linearized_fixed_point_jacobian: u_hat and lambda_hat must have sizes N = " +
              std::to_string(N_) + " and R = " + std::to_string(R_));
  require(exact_rows(ContactRows::Automatic) && !registered_,
          "OnlineSolver::linearized_fixed_point_jacobian: the model's dual cone is not the row cone");
  std::string message;
  require(prepare(mu, true, true, message), "OnlineSolver::linearized_fixed_point_jacobian: " + message);
  NewtonSystem sys;
  newton_system(u_hat, lambda_hat, sys);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(N_ + R_, N_ + R_), rhs = Eigen::MatrixXd::Zero(N_ + R_, N_);
  M.topLeftCorner(N_, N_) = A_;
  M.topRightCorner(N_, R_) = sys.B.transpose();
  rhs.topRows(N_) = A_ - sys.J;
  for (int i = 0; i < R_; ++i) {
    if (lambda_hat(i) > 0.0) {
      M.block(N_ + i, 0, 1, N_) = sys.B.row(i);
      rhs.row(N_ + i) = sys.G.row(i) + sys.B.row(i);
    } else {
      M(N_ + i, N_ + i) = 1.0;
    }
  }
  const Eigen::MatrixXd J = Eigen::PartialPivLU<Eigen::MatrixXd>(M).solve(rhs).topRows(N_);
  require(J.allFinite(), "OnlineSolver::linearized_fixed_point_jacobian: the linearized step is singular");
  prepared_ = false;  // surface_gap refers to the last solve
  return J;
}

solve::KacanovResult OnlineSolver::iterate_newton(const solve::KacanovSettings& ks, const Eigen::VectorXd& u_start,
                                                  const Eigen::VectorXd& lambda_start) {
  solve::KacanovResult result;
  Eigen::VectorXd u = u_start, lambda = lambda_start.cwiseMax(0.0);
  result.u_bar.setZero(N_);
  result.lambda_bar.setZero(R_);
  NewtonSystem sys;
  std::vector<char> active(sz(R_), 0), previous(sz(R_), 2);
  Eigen::VectorXd c(R_);
  for (int k = 1; k <= ks.max_iterations; ++k) {
    newton_system(u, lambda, sys);
    if (k == 1) {  // c_k = 1 / Q_kk, Q = B A_hat^-1 B': a pressure per unit gap
      Eigen::MatrixXd Y = sys.B.transpose();  // A_hat^-1 B'
      whitening_.solve_factor(Y);
      whitening_.solve_factor_transpose(Y);
      for (int i = 0; i < R_; ++i) {
        const double q = sys.B.row(i).dot(Y.col(i));
        c(i) = q > 0.0 ? 1.0 / q : 1.0;
      }
    }
    for (int i = 0; i < R_; ++i) active[sz(i)] = lambda(i) - c(i) * sys.s(i) > 0.0 ? 1 : 0;
    // The step: [J B'; rows of the generators] [du; dl] = -[F; r], r_i = s_i (active) or lambda_i.
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(N_ + R_, N_ + R_);
    Eigen::VectorXd rhs(N_ + R_);
    M.topLeftCorner(N_, N_) = sys.J;
    M.topRightCorner(N_, R_) = sys.B.transpose();
    rhs.head(N_) = -sys.F;
    for (int i = 0; i < R_; ++i) {
      if (active[sz(i)]) {
        M.block(N_ + i, 0, 1, N_) = sys.G.row(i);
        rhs(N_ + i) = -sys.s(i);
      } else {
        M(N_ + i, N_ + i) = 1.0;
        rhs(N_ + i) = -lambda(i);
      }
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    const Eigen::VectorXd step = lu.solve(rhs);
    if (!step.allFinite()) {
      result.status = solve::KacanovStatus::StepFailed;
      result.iterations = k;
      result.message = "Newton iteration " + std::to_string(k) + ": the reduced Newton system is singular";
      return result;
    }
    const Eigen::VectorXd u_next = u + step.head(N_);
    const Eigen::VectorXd lambda_next = lambda + step.tail(R_);
    solve::KacanovIteration it;
    it.du = solve::relative_increment(u_next, u);
    it.dlambda = solve::relative_increment(lambda_next, lambda);
    result.history.push_back(it);
    const bool same_set = active == previous;
    previous = active;
    u = u_next;
    lambda = lambda_next;
    if (same_set && std::max(it.du, it.dlambda) <= ks.tolerance && lambda.minCoeff() >= 0.0) {
      result.status = solve::KacanovStatus::Converged;
      result.iterations = k;
      result.u = result.u_bar = u;
      result.lambda = result.lambda_bar = lambda;
      return result;
    }
  }
  result.status = solve::KacanovStatus::MaxIterations;
  result.iterations = ks.max_iterations;
  result.u_bar = u;
  result.lambda_bar = lambda.cwiseMax(0.0);
  const solve::KacanovIteration& last = result.history.back();
  result.message = "the reduced Newton iteration did not converge in " + std::to_string(ks.max_iterations) +
                   " iterations (last relative increments: displacement " + number_text(last.du) + ", multipliers " +
                   number_text(last.dlambda) + ", tolerance " + number_text(ks.tolerance) + ")";
  return result;
}

}  // namespace contactrb::online
