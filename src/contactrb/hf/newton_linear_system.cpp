#include "contactrb/hf/newton_linear_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "contactrb/solve/blas_threads.hpp"
#include "contactrb/solve/dense_lu.hpp"
#include "contactrb/solve/gmres.hpp"

namespace contactrb::hf {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }

Eigen::Map<Eigen::MatrixXd> reuse(std::vector<double>& storage, int rows, int cols) {
  const std::size_t size = sz(rows) * sz(cols);
  if (storage.capacity() < size) {
    storage = std::vector<double>();
    storage.reserve(size + size / 4);
  }
  storage.resize(size);
  return Eigen::Map<Eigen::MatrixXd>(storage.data(), rows, cols);
}

// lambda = lambda_A on the active rows, 0 elsewhere.
void scatter(const std::vector<int>& active, const Eigen::VectorXd& x, Eigen::Index offset, Eigen::VectorXd& lambda) {
  lambda.setZero();
  for (std::size_t a = 0; a < active.size(); ++a) lambda(active[a]) = x(offset + static_cast<Eigen::Index>(a));
}

// Symmetric equilibration of the frozen-geometry dual matrix Q = K_E G K_E' (rows of K carry the
// units of the constraint weights).
Eigen::VectorXd dual_scale(const Eigen::MatrixXd& Q) {
  Eigen::VectorXd scale(Q.rows());
  for (Eigen::Index a = 0; a < Q.rows(); ++a) scale(a) = Q(a, a) > 0.0 ? 1.0 / std::sqrt(Q(a, a)) : 1.0;
  return scale;
}

}  // namespace

// The reduced system on E: G, H_E, K_E, the constraint rows R_E (K_E frozen, -D_E consistent)
// and the right-hand side [z_E - u_0,E; d_A]. H_E, K_E and R_E stay sparse: G H_E and G K_E'
// cost |E| x nnz.
struct NewtonLinearSystem::Reduced {
  std::vector<int> E;
  Eigen::Map<const Eigen::MatrixXd> G;
  Eigen::SparseMatrix<double> HE, KE, RE;
  Eigen::VectorXd rhs;
  int e = 0, m = 0;
};

NewtonLinearSystem::NewtonLinearSystem(const NewtonAlgebra& p, const NewtonSettings& s, int dimension)
    : p_(p),
      s_(s),
      dimension_(dimension),
      solver_(resolved_linear_solver(s, dimension, p.dofs->num_free())),
      schur_(solver_ == NewtonLinearSolver::ActiveSchur),
      blas_threads_(s.tuning.blas_threads > 0 && p.dofs->num_free() >= s.tuning.blas_threads_from ? s.tuning.blas_threads
                                                                                                  : 0),
      rows_block_(schur_ && dimension >= s.tuning.frozen_rows_from_dimension),
      lu_(s.lu),
      e_position_(sz(p.dofs->num_free()), -1) {
  if (solver_ == NewtonLinearSolver::SaddleLU) {
    a_trip_.reserve(static_cast<std::size_t>(p.A00->nonZeros()));
    for (int j = 0; j < p.A00->outerSize(); ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator a(*p.A00, j); a; ++a) a_trip_.emplace_back(a.row(), a.col(), a.value());
    }
  }
}

bool NewtonLinearSystem::factorize(NewtonTimings& timings, std::string& message) {
  timings.linear_solver = solver_;
  if (solver_ == NewtonLinearSolver::Amg) return factorize_amg(timings, message);
  if (!schur_) return true;
  const int n = p_.dofs->num_free();
  solve::SelectedInverseStatus status;
  double ahead_seconds = 0.0;
  {
    const solve::ScopedBlasThreads threads(blas_threads_);
    timings.blas_threads = solve::blas_threads();
    const auto t_wait = Clock::now();
    const solve::FactorAnalysis* ahead = p_.a00_analysis ? p_.a00_analysis() : nullptr;
    timings.analysis_wait_s = seconds_since(t_wait);
    const solve::FactorOrdering ordering =
        s_.ordering == solve::FactorOrdering::Auto ? solve::auto_ordering(n) : s_.ordering;
    if (ahead != nullptr && ahead->requested() == ordering) {
      status = inverse_.compute(*p_.A00, *ahead);  // falls back to its own analysis if the pattern differs
      timings.analysis_ahead = inverse_.used_analysis();
      ahead_seconds = ahead->seconds();
    } else {
      status = inverse_.compute(*p_.A00, s_.ordering);
    }
  }
  if (status != solve::SelectedInverseStatus::Success) {
    message = std::string("semi-smooth Newton: the stiffness A_00 (") + std::to_string(n) +
              " free DOFs) cannot be factorized: " + solve::to_string(status);
    return false;
  }
  // Two threads for the full substitutions too (the BLAS is single-threaded there).
  if (blas_threads_ >= 2) inverse_.set_substitution_threads(2);
  timings.analyze_s = timings.analysis_ahead ? ahead_seconds : inverse_.analyze_seconds();
  timings.numeric_s = inverse_.factorize_seconds();
  timings.factor_nonzeros = inverse_.factor_nonzeros();
  const auto t_rhs = Clock::now();
  z_ = inverse_.solve(*p_.b);
  timings.rhs_s = seconds_since(t_rhs);
  return true;
}

std::shared_ptr<solve::SelectedInverse> NewtonLinearSystem::release_inverse() {
  if (!schur_ || inverse_.rows() == 0 || inverse_.status() != solve::SelectedInverseStatus::Success) return nullptr;
  return std::make_shared<solve::SelectedInverse>(std::move(inverse_));
}

void NewtonLinearSystem::set_read_dofs(const RowSparse& K0, NewtonLinearization& lin) {
  lin.read_dofs.clear();
  if (!schur_) return;
  inverse_.forget_rows();  // K_0 changed
  for (const RowSparse* rows : {&K0, static_cast<const RowSparse*>(&lin.D0)}) {
    for (int r = 0; r < rows->outerSize(); ++r) {
      for (RowSparse::InnerIterator kk(*rows, r); kk; ++kk) {
        int& mark = e_position_[sz(static_cast<int>(kk.col()))];
        if (mark < 0) {
          mark = 0;
          lin.read_dofs.push_back(static_cast<int>(kk.col()));
        }
      }
    }
  }
  for (int fi : lin.read_dofs) e_position_[sz(fi)] = -1;
}

void NewtonLinearSystem::set_step(const std::vector<int>& E, const Eigen::VectorXd& yE,
                                  const std::vector<int>& read_dofs, const SystemPoint& at, NewtonStep& step) const {
  step.E = E;
  step.yE = yE;
  step.complete = false;
  const Eigen::VectorXd x = inverse_.solve_sparse(E, yE, &read_dofs);
  step.du.setZero();
  for (int fi : read_dofs) step.du(fi) = (*at.z)(fi) - x(fi) - (*at.u0)(fi);
}

void NewtonLinearSystem::complete(NewtonStep& step, const SystemPoint& at) const {
  if (step.complete) return;
  step.du = *at.z - inverse_.solve_sparse(step.E, step.yE) - *at.u0;
  step.complete = true;
}

bool NewtonLinearSystem::solve(const std::vector<int>& active, bool frozen, const RowSparse& K0,
                               const NewtonLinearization& lin, const SystemPoint& at, NewtonStep& step,
                               NewtonIteration& it, std::string& message) {
  if (solver_ == NewtonLinearSolver::Amg) return solve_saddle_amg(active, frozen, K0, lin, at, step, it, message);
  if (!schur_) return solve_saddle_lu(active, frozen, K0, lin, at, step, message);
  const Reduced sys = reduce(active, frozen, K0, lin, at, it);
  Eigen::VectorXd yE;
  bool solved = false;
  if (frozen) {
    solved = solve_frozen_dual(sys, active, K0, yE, step.lambda, it, message);
  } else {
    solved = solve_krylov(sys, active, at, yE, step.lambda, it) || solve_dense(sys, active, yE, step.lambda, message);
  }
  if (solved) set_step(sys.E, yE, lin.read_dofs, at, step);
  return solved;
}

void NewtonLinearSystem::begin_iteration(int k, double forcing) {
  rows_now_ = rows_block_ && k == 0;
  forcing_ = forcing;
  warm_at_ = nullptr;
  if (!rows_now_) inverse_.forget_rows();
}

// Q = K_E G K_E' of the frozen dual system (solve_frozen_dual): from the rows of K_0 directly in
// the first iteration (docs/performance.md, "Why the defaults are what they are", "Newton: the
// first frozen systems on the constraint rows"), else from G.
Eigen::MatrixXd NewtonLinearSystem::frozen_dual_matrix(const Reduced& sys, const std::vector<int>& active,
                                                       const RowSparse& K0, NewtonIteration& it) {
  if (rows_now_) {
    const auto t_block = Clock::now();
    const solve::ScopedBlasThreads threads(blas_threads_);
    Eigen::MatrixXd Q = inverse_.row_block(active, K0, q_storage_);
    it.block_s += seconds_since(t_block);
    return Q;
  }
  Eigen::Map<Eigen::MatrixXd> GKt = reuse(gkt_storage_, sys.e, sys.m);
  GKt.noalias() = sys.G * sys.KE.transpose();
  return sys.KE * GKt;
}

NewtonLinearSystem::Reduced NewtonLinearSystem::reduce(const std::vector<int>& active, bool frozen, const RowSparse& K0,
                                                       const NewtonLinearization& lin, const SystemPoint& at,
                                                       NewtonIteration& it) {
  // E: the free DOFs the active rows (K_A, D_A) and H touch, ascending.
  std::vector<int> E;
  auto add = [&](int fi) {
    if (e_position_[sz(fi)] < 0) {
      e_position_[sz(fi)] = 0;
      E.push_back(fi);
    }
  };
  for (int r : active) {
    for (RowSparse::InnerIterator kk(K0, r); kk; ++kk) add(static_cast<int>(kk.col()));
    if (!frozen) {
      for (RowSparse::InnerIterator dd(lin.D0, r); dd; ++dd) add(static_cast<int>(dd.col()));
    }
  }
  if (!frozen) {
    for (const auto& t : lin.H) {
      add(t.row());
      add(t.col());
    }
  }
  std::sort(E.begin(), E.end());
  const int e = static_cast<int>(E.size());
  const int m = static_cast<int>(active.size());
  for (int a = 0; a < e; ++a) e_position_[sz(E[sz(a)])] = a;
  it.reduced_size = e;
  const auto t_block = Clock::now();
  const Eigen::Map<const Eigen::MatrixXd> G = [&] {
    if (frozen && rows_now_) return Eigen::Map<const Eigen::MatrixXd>(nullptr, 0, 0);  // Q from the rows
    const solve::ScopedBlasThreads threads(blas_threads_);  // the first block: all columns new
    return inverse_.block(E, g_storage_);
  }();
  it.block_s += seconds_since(t_block);
  std::vector<Eigen::Triplet<double>> h_trip, k_trip, r_trip;
  if (!frozen) {
    for (const auto& t : lin.H) h_trip.emplace_back(e_position_[sz(t.row())], e_position_[sz(t.col())], t.value());
  }
  Eigen::VectorXd rhs(e + m);
  for (int a = 0; a < m; ++a) {
    const int r = active[sz(a)];
    for (RowSparse::InnerIterator kk(K0, r); kk; ++kk) {
      k_trip.emplace_back(a, e_position_[sz(static_cast<int>(kk.col()))], kk.value());
      if (frozen) r_trip.emplace_back(a, e_position_[sz(static_cast<int>(kk.col()))], kk.value());
    }
    if (!frozen) {
      for (RowSparse::InnerIterator dd(lin.D0, r); dd; ++dd) r_trip.emplace_back(a, e_position_[sz(static_cast<int>(dd.col()))], -dd.value());
    }
    rhs(e + a) = (*at.d)(r);
  }
  Reduced sys{std::move(E), G, Eigen::SparseMatrix<double>(e, e), Eigen::SparseMatrix<double>(m, e),
              Eigen::SparseMatrix<double>(m, e), std::move(rhs), e, m};
  sys.HE.setFromTriplets(h_trip.begin(), h_trip.end());
  sys.KE.setFromTriplets(k_trip.begin(), k_trip.end());
  sys.RE.setFromTriplets(r_trip.begin(), r_trip.end());
  for (int a = 0; a < e; ++a) {
    const int fi = sys.E[sz(a)];
    sys.rhs(a) = (*at.z)(fi) - (*at.u0)(fi);
  }
  for (int fi : sys.E) e_position_[sz(fi)] = -1;
  return sys;
}

// Frozen geometry, H = 0, D = -K: w = r_E - G K_E' lambda_A with r_E = z_E - u_0,E, and
// K_E w = d_A gives the SPD system of the active rows alone (Kacanov's dual system, paper (12)):
//   (K_E G K_E') lambda_A = K_E r_E - d_A,
// of size |A| instead of |E| + |A|.
bool NewtonLinearSystem::solve_frozen_dual(const Reduced& sys, const std::vector<int>& active, const RowSparse& K0,
                                           Eigen::VectorXd& yE, Eigen::VectorXd& lambda, NewtonIteration& it,
                                           std::string& message) {
  const int e = sys.e, m = sys.m;
  Eigen::MatrixXd Q = frozen_dual_matrix(sys, active, K0, it);
  const Eigen::VectorXd rE = sys.rhs.head(e);
  const Eigen::VectorXd q = sys.KE * rE - sys.rhs.tail(m);
  const Eigen::VectorXd scale = dual_scale(Q);
  Q = scale.asDiagonal() * Q * scale.asDiagonal();
  solve::DenseLU dense;
  const bool finite_system = dense.compute(std::move(Q));
  const double rcond = dense.rcond();
  if (!finite_system || !(rcond >= s_.tuning.min_rcond) || rcond == 0.0) {
    std::ostringstream os;
    os << "the frozen-geometry system of the active rows (" << m << " rows) is singular (reciprocal condition "
       << rcond << " < min_rcond " << s_.tuning.min_rcond << ")";
    message = os.str();
    return false;
  }
  const Eigen::VectorXd lambda_A = scale.cwiseProduct(dense.solve(scale.cwiseProduct(q)));
  yE = sys.KE.transpose() * lambda_A;
  scatter(active, lambda_A, 0, lambda);
  return true;
}

// Newton phase: GMRES on the reduced system, preconditioned by the frozen-geometry one (H = 0,
// D = -K; solved through its SPD dual matrix Q = K_E G K_E' of size |A|). The Newton phase
// starts where the frozen steps contract fast, so the preconditioned operator is near the
// identity: a few tens of products with G (|E|^2 each) instead of the dense LU of size
// |E| + |A| (docs/performance.md, "Why the defaults are what they are", "Newton: GMRES in the
// Newton phase"). False without convergence in krylov_max_iterations: the dense LU then.
bool NewtonLinearSystem::solve_krylov(const Reduced& sys, const std::vector<int>& active, const SystemPoint& at,
                                      Eigen::VectorXd& yE, Eigen::VectorXd& lambda, NewtonIteration& it) {
  const int e = sys.e, m = sys.m;
  if (s_.tuning.krylov_max_iterations <= 0 || m <= 0) return false;
  const Eigen::Map<const Eigen::MatrixXd>& G = sys.G;
  Eigen::Map<Eigen::MatrixXd> GKt = reuse(gkt_storage_, e, m);  // |E| x |A|
  GKt.noalias() = G * sys.KE.transpose();
  Eigen::MatrixXd Q = sys.KE * GKt;
  const Eigen::VectorXd q_scale = dual_scale(Q);
  Q = q_scale.asDiagonal() * Q * q_scale.asDiagonal();
  solve::DenseLU frozen_lu;
  if (!(frozen_lu.compute(std::move(Q)) && frozen_lu.rcond() >= s_.tuning.min_rcond && frozen_lu.rcond() > 0.0)) {
    return false;
  }
  // Equilibration as for the dense LU: the constraint rows by their largest entry, the
  // multiplier columns by the largest entry of G K_E'.
  Eigen::VectorXd row_scale = Eigen::VectorXd::Ones(e + m), col_scale = Eigen::VectorXd::Ones(e + m);
  const RowSparse RErow = sys.RE;
  for (int a = 0; a < m; ++a) {
    double rmax = 0.0;
    for (RowSparse::InnerIterator rr(RErow, a); rr; ++rr) rmax = std::max(rmax, std::abs(rr.value()));
    const double cmax = GKt.col(a).cwiseAbs().maxCoeff();
    if (rmax > 0.0) row_scale(e + a) = 1.0 / rmax;
    if (cmax > 0.0) col_scale(e + a) = 1.0 / cmax;
  }
  const Eigen::SparseMatrix<double> KEt = sys.KE.transpose();
  auto apply = [&](const Eigen::VectorXd& xs) -> Eigen::VectorXd {
    const Eigen::VectorXd x = col_scale.cwiseProduct(xs);
    Eigen::VectorXd out(e + m);
    const Eigen::VectorXd y = sys.HE * x.head(e) + KEt * x.tail(m);
    out.head(e).noalias() = G * y;
    out.head(e) += x.head(e);
    out.tail(m) = sys.RE * x.head(e);
    return row_scale.cwiseProduct(out);
  };
  // P [a; b] = [f; g], P = [I, G K_E'; K_E, 0]: b = Q^-1 (K_E f - g), a = f - G K_E' b.
  auto precondition = [&](const Eigen::VectorXd& vs) -> Eigen::VectorXd {
    const Eigen::VectorXd v = vs.cwiseQuotient(row_scale);
    Eigen::VectorXd out(e + m);
    const Eigen::VectorXd rhs_b = sys.KE * v.head(e) - v.tail(m);
    out.tail(m) = q_scale.cwiseProduct(frozen_lu.solve(q_scale.cwiseProduct(rhs_b)));
    out.head(e) = v.head(e) - GKt * out.tail(m);
    return out.cwiseQuotient(col_scale);
  };
  // From the iterate itself (w = 0, lambda_A = lambda at u): rhs - M x0 vanishes at the
  // solution, so the tolerance applies to the correction, not to u (the reduced unknowns are
  // the new iterate, whose size is the load's).
  Eigen::VectorXd x0s = Eigen::VectorXd::Zero(e + m);
  for (int a = 0; a < m; ++a) x0s(e + a) = (*at.lambda)(active[sz(a)]) / col_scale(e + a);
  const Eigen::VectorXd r0s = row_scale.cwiseProduct(sys.rhs) - apply(x0s);
  const solve::GmresResult kr =
      solve::gmres(apply, precondition, r0s, s_.tuning.krylov_tolerance, s_.tuning.krylov_max_iterations);
  it.krylov += kr.iterations;
  if (!kr.converged) return false;
  const Eigen::VectorXd x = col_scale.cwiseProduct(x0s + kr.x);
  yE = sys.HE * x.head(e) + KEt * x.tail(m);
  scatter(active, x, e, lambda);
  return true;
}

// The dense LU of the reduced system of size |E| + |A|, which also judges singularity
// (min_rcond).
bool NewtonLinearSystem::solve_dense(const Reduced& sys, const std::vector<int>& active, Eigen::VectorXd& yE,
                                     Eigen::VectorXd& lambda, std::string& message) {
  const int e = sys.e, m = sys.m;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(e + m, e + m);
  M.topLeftCorner(e, e) = sys.G * sys.HE;
  M.topLeftCorner(e, e).diagonal().array() += 1.0;
  M.topRightCorner(e, m) = sys.G * sys.KE.transpose();
  M.bottomLeftCorner(m, e) = Eigen::MatrixXd(sys.RE);
  // Equilibration (the blocks carry different units: gaps, displacements, pressures), so that
  // min_rcond judges the problem and not its units.
  Eigen::VectorXd row_scale = Eigen::VectorXd::Ones(e + m), col_scale = Eigen::VectorXd::Ones(e + m);
  for (int a = 0; a < m; ++a) {
    const double rmax = M.row(e + a).cwiseAbs().maxCoeff();
    const double cmax = M.col(e + a).cwiseAbs().maxCoeff();
    if (rmax > 0.0) row_scale(e + a) = 1.0 / rmax;
    if (cmax > 0.0) col_scale(e + a) = 1.0 / cmax;
  }
  M = row_scale.asDiagonal() * M * col_scale.asDiagonal();
  solve::DenseLU dense;  // LAPACK (OpenBLAS)
  const bool finite_system = dense.compute(std::move(M));
  const double rcond = dense.rcond();
  if (!finite_system || !(rcond >= s_.tuning.min_rcond) || rcond == 0.0) {
    std::ostringstream os;
    os << "the reduced Newton system (" << e << " contact DOFs, " << m
       << " active rows) is singular (reciprocal condition " << rcond << " < min_rcond " << s_.tuning.min_rcond << ")";
    message = os.str();
    return false;
  }
  const Eigen::VectorXd x = col_scale.cwiseProduct(dense.solve(row_scale.cwiseProduct(sys.rhs)));
  yE = sys.HE * x.head(e) + sys.KE.transpose() * x.tail(m);
  scatter(active, x, e, lambda);
  return true;
}

// [A_00 + H, K_A'; -D_A, 0] [du; lambda_A] = [b - A_00 u_0; d_A] (frozen: H = 0, D = -K).
bool NewtonLinearSystem::solve_saddle_lu(const std::vector<int>& active, bool frozen, const RowSparse& K0,
                                         const NewtonLinearization& lin, const SystemPoint& at, NewtonStep& step,
                                         std::string& message) {
  const int n = p_.dofs->num_free();
  const int m = static_cast<int>(active.size());
  std::vector<Eigen::Triplet<double>> trip = a_trip_;
  if (!frozen) trip.insert(trip.end(), lin.H.begin(), lin.H.end());
  Eigen::VectorXd rhs(n + m);
  rhs.head(n) = *at.top;
  for (int a = 0; a < m; ++a) {
    const int r = active[sz(a)];
    for (RowSparse::InnerIterator kk(K0, r); kk; ++kk) trip.emplace_back(kk.col(), n + a, kk.value());
    if (frozen) {
      for (RowSparse::InnerIterator kk(K0, r); kk; ++kk) trip.emplace_back(n + a, kk.col(), kk.value());
    } else {
      for (RowSparse::InnerIterator dd(lin.D0, r); dd; ++dd) trip.emplace_back(n + a, dd.col(), -dd.value());
    }
    rhs(n + a) = (*at.d)(r);
  }
  Eigen::SparseMatrix<double> J(n + m, n + m);
  J.setFromTriplets(trip.begin(), trip.end());
  if (lu_.compute(J) != solve::SparseLUStatus::Success) {
    message = "the Newton system (" + std::to_string(n) + " free DOFs, " + std::to_string(m) + " active rows) is " +
              solve::to_string(lu_.status());
    return false;
  }
  const Eigen::VectorXd x = lu_.solve(rhs);
  step.du = x.head(n);
  scatter(active, x, n, step.lambda);
  return true;
}

// The hierarchy of A_00, each free DOF with its displacement component (BoomerAMG's systems
// coarsening; docs/solvers.md, "AMG-preconditioned Krylov solve").
bool NewtonLinearSystem::factorize_amg(NewtonTimings& timings, std::string& message) {
  const int n = p_.dofs->num_free();
  std::vector<int> component(sz(n));
  for (int i = 0; i < n; ++i) component[sz(i)] = p_.dofs->free_dofs()[sz(i)] % dimension_;
  const solve::AmgStatus status = amg_.compute(*p_.A00, component, dimension_, s_.amg);
  if (status != solve::AmgStatus::Success) {
    message = std::string("semi-smooth Newton: the AMG hierarchy of the stiffness A_00 (") + std::to_string(n) +
              " free DOFs) cannot be built: " + solve::to_string(status);
    return false;
  }
  timings.numeric_s = amg_.setup_seconds();
  timings.amg_levels = amg_.levels();
  return true;
}

// The saddle point of solve_saddle_lu by GMRES (solve/saddle_point_krylov.hpp), from the iterate
// (du = 0, lambda_A = lambda at u). A GMRES that does not reach its tolerance is a failed system
// (message set), never a step.
bool NewtonLinearSystem::solve_saddle_amg(const std::vector<int>& active, bool frozen, const RowSparse& K0,
                                          const NewtonLinearization& lin, const SystemPoint& at, NewtonStep& step,
                                          NewtonIteration& it, std::string& message) {
  const int n = p_.dofs->num_free();
  const int m = static_cast<int>(active.size());
  std::vector<Eigen::Triplet<double>> b_trip, c_trip;
  Eigen::VectorXd rhs(n + m), x_iterate = Eigen::VectorXd::Zero(n + m);
  const bool warm = warm_at_ == at.u0;
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n + m);
  if (warm) x0.head(n) = warm_du_;
  rhs.head(n) = *at.top;
  for (int a = 0; a < m; ++a) {
    const int r = active[sz(a)];
    for (RowSparse::InnerIterator kk(K0, r); kk; ++kk) {
      b_trip.emplace_back(a, kk.col(), kk.value());
      if (frozen) c_trip.emplace_back(a, kk.col(), kk.value());
    }
    if (!frozen) {
      for (RowSparse::InnerIterator dd(lin.D0, r); dd; ++dd) c_trip.emplace_back(a, dd.col(), -dd.value());
    }
    rhs(n + a) = (*at.d)(r);
    x_iterate(n + a) = (*at.lambda)(r);
    x0(n + a) = warm ? warm_lambda_(r) : (*at.lambda)(r);
  }
  RowSparse B(m, n), C(m, n);
  B.setFromTriplets(b_trip.begin(), b_trip.end());
  C.setFromTriplets(c_trip.begin(), c_trip.end());
  Eigen::SparseMatrix<double> consistent;  // A_00 + H
  if (!frozen && !lin.H.empty()) {
    Eigen::SparseMatrix<double> H(n, n);
    H.setFromTriplets(lin.H.begin(), lin.H.end());
    consistent = *p_.A00 + H;
  }
  const Eigen::SparseMatrix<double>& F = frozen || lin.H.empty() ? *p_.A00 : consistent;
  solve::SaddlePointKrylovSettings krylov = s_.krylov;
  krylov.tolerance = forcing_;
  const solve::SaddlePointKrylovResult kr = solve::solve_saddle_point(F, B, C, amg_, rhs, x0, krylov, &x_iterate);
  it.krylov += kr.iterations;
  if (kr.status != solve::SaddlePointKrylovStatus::Converged) {
    std::ostringstream os;
    os << "the Newton system (" << n << " free DOFs, " << m
       << " active rows) was not solved by AMG-preconditioned GMRES: "
       << solve::to_string(kr.status) << " after " << kr.iterations << " products (relative residual "
       << kr.relative_residual << ", tolerance " << krylov.tolerance << ")";
    message = os.str();
    return false;
  }
  step.du = kr.x.head(n);
  scatter(active, kr.x, n, step.lambda);
  warm_du_ = step.du;
  warm_lambda_ = step.lambda;
  warm_at_ = at.u0;
  return true;
}

}  // namespace contactrb::hf
