#include "contactrb/hf/semismooth_newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>


#include "contactrb/common/error.hpp"
#include "contactrb/solve/blas_threads.hpp"
#include "contactrb/solve/dense_lu.hpp"
#include "contactrb/solve/gmres.hpp"
#include "contactrb/solve/selected_inverse.hpp"

namespace contactrb::hf {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Everything the method needs at one iterate (u_0, lambda).
struct State {
  Eigen::VectorXd u0, lambda, u;
  contact::ContactMaps maps;
  RowSparse K0;           // K(u) on the free columns
  Eigen::VectorXd F1;     // A_00 u_0 - b + K_0' lambda
  Eigen::VectorXd ncp;    // min(lambda_r, c_r d_r)
  double merit = 0.0;     // |(F1, |I_r| ncp_r)|
  double stationarity = 0.0, primal = 0.0, dual = 0.0, complementarity = 0.0;
  double kkt() const { return std::max({stationarity, primal, dual, complementarity}); }
};

class Evaluator {
 public:
  Evaluator(const NewtonProblem& p, const NewtonSettings& s) : p_(p), s_(s) {
    const Eigen::SparseMatrix<double>& A = *p.A00;
    const int R = static_cast<int>(p.quadrature->weight.size());
    // c_r = (stiffness at the slave nodes of I_r) / |I_r|^2: lambda_r and c_r d_r are then
    // both pressures (a slave node pushed by delta carries A_ss delta = lambda_r |I_r|, with
    // d_r = |I_r| delta), so the active-set test does not depend on units.
    const Eigen::VectorXd diag = A.diagonal();
    const double mean_diag = diag.size() > 0 ? diag.cwiseAbs().mean() : 1.0;
    std::vector<int> global_to_free(static_cast<std::size_t>(p.dofs->num_dofs()), -1);
    for (int i = 0; i < p.dofs->num_free(); ++i) global_to_free[static_cast<std::size_t>(p.dofs->free_dofs()[static_cast<std::size_t>(i)])] = i;
    c_.resize(R);
    for (int r = 0; r < R; ++r) {
      double sum = 0.0;
      int count = 0;
      for (RowSparse::InnerIterator it(p.quadrature->W, r); it; ++it) {
        const int node = p.pair->slave[static_cast<std::size_t>(it.col())];
        for (int c = 0; c < 2; ++c) {
          const int fi = global_to_free[static_cast<std::size_t>(2 * node + c)];
          if (fi >= 0) {
            sum += std::abs(diag(fi));
            ++count;
          }
        }
      }
      const double w = p.quadrature->weight(r);
      c_(r) = (count > 0 ? sum / count : mean_diag) / (w * w);
    }
  }

  const Eigen::VectorXd& c() const { return c_; }

  // Throws contactrb::Error when the geometry cannot be evaluated at u.
  State operator()(Eigen::VectorXd u0, Eigen::VectorXd lambda) const {
    State st;
    st.u0 = std::move(u0);
    st.lambda = std::move(lambda);
    st.u = p_.dofs->lift() + p_.dofs->extend(st.u0);
    st.maps = contact::evaluate_contact_maps(*p_.mesh, *p_.pair, *p_.quadrature, st.u, s_.linearization.projection);
    st.K0 = p_.dofs->restrict_columns(st.maps.rows.K);
    const Eigen::VectorXd Ktl = st.K0.transpose() * st.lambda;
    st.F1 = *p_.A00 * st.u0 - *p_.b + Ktl;
    const Eigen::VectorXd& d = st.maps.d;
    st.ncp = st.lambda.cwiseMin(c_.cwiseProduct(d));
    st.merit = std::sqrt(st.F1.squaredNorm() + st.ncp.cwiseProduct(p_.quadrature->weight).squaredNorm());
    // The report of hf_solver.hpp (HFKKT), at the geometry of u itself.
    const double force_scale = std::max({p_.b->norm(), Ktl.norm(), 1e-300});
    st.stationarity = st.F1.norm() / force_scale;
    const Eigen::VectorXd g_lift = st.maps.rows.g - st.maps.rows.K * p_.dofs->lift();
    const double row_scale = st.K0.rows() > 0 ? (st.K0.cwiseAbs() * st.u0.cwiseAbs()).maxCoeff() : 0.0;
    const double gap_scale = std::max({g_lift.size() > 0 ? g_lift.cwiseAbs().maxCoeff() : 0.0, row_scale, 1e-300});
    const double lmax = std::max(st.lambda.size() > 0 ? st.lambda.cwiseAbs().maxCoeff() : 0.0, 1e-300);
    if (d.size() > 0) {
      st.primal = std::max(0.0, -d.minCoeff()) / gap_scale;
      st.dual = std::max(0.0, -st.lambda.minCoeff()) / lmax;
      st.complementarity = st.lambda.cwiseProduct(d).cwiseAbs().maxCoeff() / (lmax * gap_scale);
    }
    return st;
  }

 private:
  const NewtonProblem& p_;
  const NewtonSettings& s_;
  Eigen::VectorXd c_;
};

bool finite(const State& st) {
  return st.u0.allFinite() && st.lambda.allFinite() && std::isfinite(st.merit);
}

std::string residual_text(const State& st) {
  std::ostringstream os;
  os << "KKT residuals: stationarity " << st.stationarity << ", primal " << st.primal << ", dual " << st.dual
     << ", complementarity " << st.complementarity;
  return os.str();
}

}  // namespace

const char* to_string(NewtonLinearSolver solver) {
  switch (solver) {
    case NewtonLinearSolver::ActiveSchur: return "schur";
    case NewtonLinearSolver::SaddleLU: return "lu";
  }
  return "unknown";
}

NewtonLinearSolver newton_linear_solver_from_string(const std::string& name) {
  if (name == "schur") return NewtonLinearSolver::ActiveSchur;
  if (name == "lu") return NewtonLinearSolver::SaddleLU;
  throw Error("unknown Newton linear solver '" + name + "' (expected schur or lu)");
}

const char* to_string(NewtonInnerPasses passes) {
  switch (passes) {
    case NewtonInnerPasses::Frozen: return "frozen";
    case NewtonInnerPasses::Consistent: return "consistent";
  }
  return "unknown";
}

NewtonInnerPasses newton_inner_passes_from_string(const std::string& name) {
  if (name == "frozen") return NewtonInnerPasses::Frozen;
  if (name == "consistent") return NewtonInnerPasses::Consistent;
  throw Error("unknown Newton inner passes '" + name + "' (expected frozen or consistent)");
}

void check_settings(const NewtonSettings& s) {
  require(s.blas_threads >= 0, "Newton blas_threads must be >= 0 (got " + std::to_string(s.blas_threads) + ")");
  require(std::isfinite(s.tolerance) && s.tolerance > 0.0,
          "Newton tolerance must be > 0 (got " + std::to_string(s.tolerance) + ")");
  require(s.max_iterations >= 1, "Newton max_iterations must be >= 1 (got " + std::to_string(s.max_iterations) + ")");
  require(std::isfinite(s.armijo) && s.armijo > 0.0 && s.armijo < 0.5,
          "Newton armijo must be in (0, 1/2) (got " + std::to_string(s.armijo) + ")");
  require(std::isfinite(s.min_step) && s.min_step > 0.0 && s.min_step <= 1.0,
          "Newton min_step must be in (0, 1] (got " + std::to_string(s.min_step) + ")");
  require(s.max_inner_iterations >= 1,
          "Newton max_inner_iterations must be >= 1 (got " + std::to_string(s.max_inner_iterations) + ")");
  require(std::isfinite(s.min_rcond) && s.min_rcond >= 0.0 && s.min_rcond < 1.0,
          "Newton min_rcond must be in [0, 1) (got " + std::to_string(s.min_rcond) + ")");
  require(s.krylov_max_iterations >= 0,
          "Newton krylov_max_iterations must be >= 0 (got " + std::to_string(s.krylov_max_iterations) + ")");
  require(std::isfinite(s.krylov_tolerance) && s.krylov_tolerance > 0.0 && s.krylov_tolerance < 1.0,
          "Newton krylov_tolerance must be in (0, 1) (got " + std::to_string(s.krylov_tolerance) + ")");
  require(s.max_free_steps >= 0, "Newton max_free_steps must be >= 0 (got " + std::to_string(s.max_free_steps) + ")");
  require(s.max_branch_passes >= 0,
          "Newton max_branch_passes must be >= 0 (got " + std::to_string(s.max_branch_passes) + ")");
  require(std::isfinite(s.kacanov_safeguard) && s.kacanov_safeguard >= 0.0,
          "Newton kacanov_safeguard must be >= 0 (got " + std::to_string(s.kacanov_safeguard) + ")");
  require(s.switch_passes >= 1, "Newton switch_passes must be >= 1 (got " + std::to_string(s.switch_passes) + ")");
  require(s.chord_steps >= 0, "Newton chord_steps must be >= 0 (got " + std::to_string(s.chord_steps) + ")");
  require(s.max_newton_passes >= 1,
          "Newton max_newton_passes must be >= 1 (got " + std::to_string(s.max_newton_passes) + ")");
  require(s.branch_passes_below >= 0.0, "Newton branch_passes_below must be >= 0 (got " + std::to_string(s.branch_passes_below) + ")");
}

NewtonResult semismooth_newton(const NewtonProblem& p, const Eigen::VectorXd& u0_start,
                               const Eigen::VectorXd& lambda_start, const NewtonSettings& s) {
  check_settings(s);
  const int n = p.dofs->num_free();
  const int N = p.dofs->num_dofs();
  const int R = static_cast<int>(p.quadrature->weight.size());
  require(u0_start.size() == n, "semismooth_newton: initial u0 has " + std::to_string(u0_start.size()) +
                                    " entries for " + std::to_string(n) + " free DOFs");
  require(lambda_start.size() == R, "semismooth_newton: initial lambda has " + std::to_string(lambda_start.size()) +
                                        " entries for " + std::to_string(R) + " constraint rows");
  std::vector<int> global_to_free(static_cast<std::size_t>(N), -1);
  std::vector<char> movable(static_cast<std::size_t>(N), 0);
  for (int i = 0; i < n; ++i) {
    const int g = p.dofs->free_dofs()[static_cast<std::size_t>(i)];
    global_to_free[static_cast<std::size_t>(g)] = i;
    movable[static_cast<std::size_t>(g)] = 1;
  }
  const Evaluator evaluate(p, s);
  // The free DOFs of the slave and master nodes (what a projection reads), ascending.
  std::vector<int> contact_free;
  for (const std::vector<int>* nodes : {&p.pair->slave, &p.pair->master}) {
    for (int node : *nodes) {
      for (int c = 0; c < 2; ++c) {
        const int fi = global_to_free[static_cast<std::size_t>(2 * node + c)];
        if (fi >= 0) contact_free.push_back(fi);
      }
    }
  }
  std::sort(contact_free.begin(), contact_free.end());
  contact_free.erase(std::unique(contact_free.begin(), contact_free.end()), contact_free.end());

  NewtonResult res;
  State st;
  const auto t_initial = Clock::now();
  try {
    st = evaluate(u0_start, lambda_start);
  } catch (const Error& e) {
    res.message = std::string("semi-smooth Newton: the initial guess cannot be evaluated: ") + e.what();
    res.u0 = u0_start;
    res.lambda = lambda_start;
    return res;
  }
  res.timings.initial_s = seconds_since(t_initial);
  std::vector<char> previous_active(static_cast<std::size_t>(R), 0);
  bool newton_phase = s.inner_passes == NewtonInnerPasses::Consistent;
  int free_steps = 0;
  solve::SparseLU lu(s.lu);
  // ActiveSchur: A_00 = L L' once for the whole solve, z = A_00^-1 b. Each step then reads
  //   u_0 + du = z - A_00^-1 P_E y,   y = H_E w + K_E' lambda_A,   w = du[E],
  // and w, lambda_A solve the dense system of size |E| + |A| (exact: H, K_A, D_A vanish off E)
  //   [ I + G H_E   G K_E' ] [ w        ]   [ z_E - u_0,E ]
  //   [ -D_E        0      ] [ lambda_A ] = [ d_A         ],   G = (A_00^-1)[E, E].
  solve::SelectedInverse inverse;
  // G = (A_00^-1)[E, E] (SelectedInverse::block) and G K_E', in storage reused by every system:
  // at 1.2e6 DOFs they are ~80 and ~20 MB, and a new allocation per system was returned to the
  // OS at its end and page-faulted again by the next (docs/benchmarks.md).
  std::vector<double> g_storage, gkt_storage;
  auto reuse = [](std::vector<double>& storage, int rows, int cols) {
    const std::size_t size = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
    if (storage.capacity() < size) {
      storage = std::vector<double>();
      storage.reserve(size + size / 4);
    }
    storage.resize(size);
    return Eigen::Map<Eigen::MatrixXd>(storage.data(), rows, cols);
  };
  Eigen::VectorXd z;
  std::vector<int> e_position(static_cast<std::size_t>(n), -1);
  const bool schur = s.linear_solver == NewtonLinearSolver::ActiveSchur;
  const int blas_threads = s.blas_threads > 0 && n >= s.blas_threads_from ? s.blas_threads : 0;
  // When the solver sets the threads (blas_threads > 0 and n >= blas_threads_from), everything
  // but the two BLAS-3 parts runs with one OpenBLAS thread: the dense LUs of size |A| (dgetrf) and
  // the BLAS-2 calls of the substitutions woke OpenBLAS's worker, which then spins in sched_yield
  // (hertz-a level 7 with 2 threads: ~12 % of the process's CPU samples in the scheduler). Below
  // blas_threads_from the count is left alone: at level 5 one thread everywhere was slower than
  // OpenBLAS's own count (1.11-1.23 s against 0.85-0.95 s, docs/benchmarks.md).
  const solve::ScopedBlasThreads serial_blas(blas_threads > 0 ? 1 : 0);
  if (schur) {
    solve::SelectedInverseStatus status;
    double ahead_seconds = 0.0;
    {
      const solve::ScopedBlasThreads threads(blas_threads);
      res.timings.blas_threads = solve::blas_threads();
      const auto t_wait = Clock::now();
      const solve::FactorAnalysis* ahead = p.a00_analysis ? p.a00_analysis() : nullptr;
      res.timings.analysis_wait_s = seconds_since(t_wait);
      const solve::FactorOrdering ordering =
          s.ordering == solve::FactorOrdering::Auto ? solve::auto_ordering(n) : s.ordering;
      if (ahead != nullptr && ahead->requested() == ordering) {
        status = inverse.compute(*p.A00, *ahead);  // falls back to its own analysis if the pattern differs
        res.timings.analysis_ahead = inverse.used_analysis();
        ahead_seconds = ahead->seconds();
      } else {
        status = inverse.compute(*p.A00, s.ordering);
      }
    }
    if (status != solve::SelectedInverseStatus::Success) {
      res.message = std::string("semi-smooth Newton: the stiffness A_00 (") + std::to_string(n) +
                    " free DOFs) cannot be factorized: " + solve::to_string(status);
      res.u0 = st.u0;
      res.lambda = st.lambda;
      return res;
    }
    // Two threads for the full substitutions too (the BLAS is single-threaded there).
    if (blas_threads >= 2) inverse.set_substitution_threads(2);
    res.timings.analyze_s = res.timings.analysis_ahead ? ahead_seconds : inverse.analyze_seconds();
    res.timings.numeric_s = inverse.factorize_seconds();
    res.timings.factor_nonzeros = inverse.factor_nonzeros();
    const auto t_rhs = Clock::now();
    z = inverse.solve(*p.b);
    res.timings.rhs_s = seconds_since(t_rhs);
  }
  auto finish = [&](solve::KacanovStatus status, std::string message) {
    res.status = status;
    res.message = std::move(message);
    res.u0 = st.u0;
    res.lambda = st.lambda;
    res.stationarity = st.stationarity;
    res.primal = st.primal;
    res.dual = st.dual;
    res.complementarity = st.complementarity;
    return res;
  };

  for (int k = 0;; ++k) {
    if (!finite(st)) {
      return finish(solve::KacanovStatus::NonFinite, "semi-smooth Newton iteration " + std::to_string(k) +
                                                         ": the iterate is not finite (" + residual_text(st) + ")");
    }
    if (st.kkt() <= s.tolerance) return finish(solve::KacanovStatus::Converged, "");
    if (k >= s.max_iterations) {
      std::ostringstream os;
      os << "semi-smooth Newton did not converge in " << k << " iterations (tolerance " << s.tolerance
         << "); last " << residual_text(st);
      return finish(solve::KacanovStatus::MaxIterations, os.str());
    }
    NewtonIteration it;
    it.residual = st.kkt();
    it.merit = st.merit;

    // Consistent linearization of the geometry (D, H) at u, lambda: in the Newton phase only
    // (the Kacanov phase's frozen steps need K and d, already in st.maps). Analytic by default
    // (the 2 x (24-32 colours) map evaluations of the finite differences were most of an
    // iteration's time on hertz-a level 0; both take the same steps).
    const bool kacanov_phase = !newton_phase;
    auto t0 = Clock::now();
    contact::ContactLinearization lin;
    if (!kacanov_phase) {
      try {
        lin = contact::linearize_contact(*p.mesh, *p.pair, *p.quadrature, st.u, st.lambda, movable, st.maps,
                                         s.linearization);
      } catch (const Error& e) {
        return finish(solve::KacanovStatus::StepFailed, "semi-smooth Newton iteration " + std::to_string(k) +
                                                            ": the contact maps cannot be linearized: " + e.what());
      }
    } else {
      lin.D.resize(R, N);
      lin.H.resize(N, N);
    }
    it.colours = lin.colours;
    it.linearize_s = seconds_since(t0);
    RowSparse D0 = p.dofs->restrict_columns(lin.D);
    // The free DOFs the constraint rows read (K_0, D_0 over every row): an inner pass needs du
    // there only (the predicted active set reads K_0 du or D_0 du). Recomputed when a branch pass
    // replaces K_0 and D_0.
    std::vector<int> read_dofs;
    auto set_read_dofs = [&] {
      read_dofs.clear();
      if (!schur) return;
      for (const RowSparse* rows : {static_cast<const RowSparse*>(&st.K0), static_cast<const RowSparse*>(&D0)}) {
        for (int r = 0; r < rows->outerSize(); ++r) {
          for (RowSparse::InnerIterator kk(*rows, r); kk; ++kk) {
            int& mark = e_position[static_cast<std::size_t>(kk.col())];
            if (mark < 0) {
              mark = 0;
              read_dofs.push_back(static_cast<int>(kk.col()));
            }
          }
        }
      }
      for (int fi : read_dofs) e_position[static_cast<std::size_t>(fi)] = -1;
    };
    set_read_dofs();

    // Two linearizations. Consistent: [A_00 + H, K_A'; -D_A, 0]. Frozen: H = 0, D = -K, the
    // Jacobian of the Kacanov step with the geometry frozen at u: the linearized problem is then
    // a strictly convex QP (A_00 SPD), on which the primal-dual active-set passes settle. The
    // frozen one is also the fallback when the consistent Jacobian is singular (e.g. a slave
    // node at an open master end, where the finite differences straddle the candidate switch).
    t0 = Clock::now();
    bool singular_consistent = false;  // this iteration: consistent Jacobian found singular
    std::vector<Eigen::Triplet<double>> a_trip, h_free;  // A_00 (SaddleLU only) and H, free indices
    auto set_h_free = [&](const Eigen::SparseMatrix<double>& H) {
      h_free.clear();
      for (int j = 0; j < H.outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator h(H, j); h; ++h) {
          const int fr = global_to_free[static_cast<std::size_t>(h.row())];
          const int fc = global_to_free[static_cast<std::size_t>(h.col())];
          if (fr >= 0 && fc >= 0) h_free.emplace_back(fr, fc, h.value());
        }
      }
    };
    set_h_free(lin.H);
    if (!schur) {
      a_trip.reserve(static_cast<std::size_t>(p.A00->nonZeros()));
      for (int j = 0; j < p.A00->outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator a(*p.A00, j); a; ++a) a_trip.emplace_back(a.row(), a.col(), a.value());
      }
    }
    // The point the linear systems are written at: the iterate, or (chord correction) the full
    // step's trial with the right-hand side terms of the iterate's Jacobian (below).
    const Eigen::VectorXd* base_z = &z;
    const Eigen::VectorXd* base_u0 = &st.u0;
    const Eigen::VectorXd* base_d = &st.maps.d;
    const Eigen::VectorXd* base_lambda = &st.lambda;
    // SaddleLU's right-hand side b - A_00 u_0 (ActiveSchur reads z instead: not formed, one
    // product with A_00 per iteration saved).
    Eigen::VectorXd top;
    if (!schur) top = *p.b - *p.A00 * st.u0;

    Eigen::VectorXd du = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd lambda_next = st.lambda;
    // ActiveSchur: u_0 + du = z - A_00^-1 P_E y_E. A pass first computes du on read_dofs only
    // (forward substitution along the elimination-tree chains of E, backward along those of
    // read_dofs: hertz-a level 6, ~1 600 + ~8 000 DOFs of 3.1e5); the whole du only for the
    // step taken (complete_step). On hertz-a level 6 the Kacanov phase takes 23 passes in 3
    // iterations, each with a full substitution before (~0.1 s).
    struct StepSource {
      std::vector<int> E;
      Eigen::VectorXd yE;
      bool complete = true;
    };
    StepSource step_source;
    auto set_step = [&](const std::vector<int>& E, const Eigen::VectorXd& yE) {
      step_source.E = E;
      step_source.yE = yE;
      step_source.complete = false;
      const Eigen::VectorXd x = inverse.solve_sparse(E, yE, &read_dofs);
      du.setZero();
      for (int fi : read_dofs) du(fi) = (*base_z)(fi) - x(fi) - (*base_u0)(fi);
    };
    auto complete_step = [&](Eigen::VectorXd& out, StepSource& source) {
      if (source.complete) return;
      out = *base_z - inverse.solve_sparse(source.E, source.yE) - *base_u0;
      source.complete = true;
    };
    std::string failure;  // set when a frozen system is singular: the step fails

    // One linear system on the active rows `act`: sets du, lambda_next. Returns false when the
    // system is singular (failure holds the message if it was the frozen one).
    auto solve_active = [&](const std::vector<char>& act, bool frozen) -> bool {
      std::vector<int> active;
      for (int r = 0; r < R; ++r) {
        if (act[static_cast<std::size_t>(r)]) active.push_back(r);
      }
      const int m = static_cast<int>(active.size());
      ++it.factorizations;
      it.active = m;
      auto singular_message = [&](const std::string& what) {
        if (frozen) {
          failure = "semi-smooth Newton iteration " + std::to_string(k) + ": " + what + "; " + residual_text(st);
        }
        return false;
      };
      if (schur) {
        // E: the free DOFs the active rows (K_A, D_A) and H touch, ascending.
        std::vector<int> E;
        auto add = [&](int fi) {
          if (e_position[static_cast<std::size_t>(fi)] < 0) {
            e_position[static_cast<std::size_t>(fi)] = 0;
            E.push_back(fi);
          }
        };
        for (int r : active) {
          for (RowSparse::InnerIterator kk(st.K0, r); kk; ++kk) add(static_cast<int>(kk.col()));
          if (!frozen) {
            for (RowSparse::InnerIterator dd(D0, r); dd; ++dd) add(static_cast<int>(dd.col()));
          }
        }
        if (!frozen) {
          for (const auto& t : h_free) {
            add(t.row());
            add(t.col());
          }
        }
        std::sort(E.begin(), E.end());
        const int e = static_cast<int>(E.size());
        for (int a = 0; a < e; ++a) e_position[static_cast<std::size_t>(E[static_cast<std::size_t>(a)])] = a;
        it.reduced_size = e;
        const auto t_block = Clock::now();
        const Eigen::Map<const Eigen::MatrixXd> G = [&] {
          const solve::ScopedBlasThreads threads(blas_threads);  // the first block: all columns new
          return inverse.block(E, g_storage);
        }();
        it.block_s += seconds_since(t_block);
        // H_E, K_E and the constraint rows stay sparse: G H_E and G K_E' cost |E| x nnz.
        std::vector<Eigen::Triplet<double>> h_trip, k_trip, r_trip;
        if (!frozen) {
          for (const auto& t : h_free) h_trip.emplace_back(e_position[static_cast<std::size_t>(t.row())], e_position[static_cast<std::size_t>(t.col())], t.value());
        }
        Eigen::VectorXd rhs(e + m);
        for (int a = 0; a < m; ++a) {
          const int r = active[static_cast<std::size_t>(a)];
          for (RowSparse::InnerIterator kk(st.K0, r); kk; ++kk) {
            k_trip.emplace_back(a, e_position[static_cast<std::size_t>(kk.col())], kk.value());
            if (frozen) r_trip.emplace_back(a, e_position[static_cast<std::size_t>(kk.col())], kk.value());
          }
          if (!frozen) {
            for (RowSparse::InnerIterator dd(D0, r); dd; ++dd) r_trip.emplace_back(a, e_position[static_cast<std::size_t>(dd.col())], -dd.value());
          }
          rhs(e + a) = (*base_d)(r);
        }
        Eigen::SparseMatrix<double> HE(e, e), KE(m, e), RE(m, e);
        HE.setFromTriplets(h_trip.begin(), h_trip.end());
        KE.setFromTriplets(k_trip.begin(), k_trip.end());
        RE.setFromTriplets(r_trip.begin(), r_trip.end());
        for (int a = 0; a < e; ++a) {
          const int fi = E[static_cast<std::size_t>(a)];
          rhs(a) = (*base_z)(fi) - (*base_u0)(fi);
        }
        for (int fi : E) e_position[static_cast<std::size_t>(fi)] = -1;
        if (frozen) {
          // H = 0, D = -K: w = r_E - G K_E' lambda_A with r_E = z_E - u_0,E, and K_E w = d_A
          // gives the SPD system of the active rows alone (Kacanov's dual system, paper (12)):
          //   (K_E G K_E') lambda_A = K_E r_E - d_A,
          // size |A| instead of |E| + |A| (hertz-a level 6: 393 against ~1 800).
          Eigen::Map<Eigen::MatrixXd> GKt = reuse(gkt_storage, e, m);
          GKt.noalias() = G * KE.transpose();
          Eigen::MatrixXd Q = KE * GKt;
          const Eigen::VectorXd rE = rhs.head(e);
          const Eigen::VectorXd q = KE * rE - rhs.tail(m);
          // Symmetric equilibration (rows of K carry the units of the constraint weights).
          Eigen::VectorXd scale(m);
          for (int a = 0; a < m; ++a) scale(a) = Q(a, a) > 0.0 ? 1.0 / std::sqrt(Q(a, a)) : 1.0;
          Q = scale.asDiagonal() * Q * scale.asDiagonal();
          solve::DenseLU dense;
          const bool finite_system = dense.compute(std::move(Q));
          const double rcond = dense.rcond();
          if (!finite_system || !(rcond >= s.min_rcond) || rcond == 0.0) {
            std::ostringstream os;
            os << "the frozen-geometry system of the active rows (" << m << " rows) is singular (reciprocal condition "
               << rcond << " < min_rcond " << s.min_rcond << ")";
            return singular_message(os.str());
          }
          const Eigen::VectorXd lambda_A = scale.cwiseProduct(dense.solve(scale.cwiseProduct(q)));
          set_step(E, KE.transpose() * lambda_A);
          lambda_next.setZero();
          for (int a = 0; a < m; ++a) lambda_next(active[static_cast<std::size_t>(a)]) = lambda_A(a);
          return true;
        }
        // Newton phase: GMRES on the reduced system, preconditioned by the frozen-geometry one
        // (H = 0, D = -K; solved through its SPD dual matrix Q = K_E G K_E' of size |A|). The
        // Newton phase starts where the frozen steps contract fast, so the preconditioned
        // operator is near the identity: a few tens of products with G (|E|^2 each) instead
        // of the dense LU of size |E| + |A| (hertz-a level 6: ~2 000, 1.1 of 10 CPU seconds;
        // level 7 ~4 000). Without convergence in krylov_max_iterations: the dense LU below,
        // which also judges singularity (min_rcond).
        if (s.krylov_max_iterations > 0 && m > 0) {
          Eigen::Map<Eigen::MatrixXd> GKt = reuse(gkt_storage, e, m);  // |E| x |A|
          GKt.noalias() = G * KE.transpose();
          Eigen::MatrixXd Q = KE * GKt;
          Eigen::VectorXd q_scale(m);
          for (int a = 0; a < m; ++a) q_scale(a) = Q(a, a) > 0.0 ? 1.0 / std::sqrt(Q(a, a)) : 1.0;
          Q = q_scale.asDiagonal() * Q * q_scale.asDiagonal();
          solve::DenseLU frozen_lu;
          if (frozen_lu.compute(std::move(Q)) && frozen_lu.rcond() >= s.min_rcond && frozen_lu.rcond() > 0.0) {
            // Equilibration as for the dense LU: the constraint rows by their largest entry, the
            // multiplier columns by the largest entry of G K_E'.
            Eigen::VectorXd row_scale = Eigen::VectorXd::Ones(e + m), col_scale = Eigen::VectorXd::Ones(e + m);
            const Eigen::SparseMatrix<double, Eigen::RowMajor> RErow = RE;
            for (int a = 0; a < m; ++a) {
              double rmax = 0.0;
              for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator rr(RErow, a); rr; ++rr) rmax = std::max(rmax, std::abs(rr.value()));
              const double cmax = GKt.col(a).cwiseAbs().maxCoeff();
              if (rmax > 0.0) row_scale(e + a) = 1.0 / rmax;
              if (cmax > 0.0) col_scale(e + a) = 1.0 / cmax;
            }
            const Eigen::SparseMatrix<double> KEt = KE.transpose();
            auto apply = [&](const Eigen::VectorXd& xs) -> Eigen::VectorXd {
              const Eigen::VectorXd x = col_scale.cwiseProduct(xs);
              Eigen::VectorXd out(e + m);
              const Eigen::VectorXd yE = HE * x.head(e) + KEt * x.tail(m);
              out.head(e).noalias() = G * yE;
              out.head(e) += x.head(e);
              out.tail(m) = RE * x.head(e);
              return row_scale.cwiseProduct(out);
            };
            // P [a; b] = [f; g], P = [I, G K_E'; K_E, 0]: b = Q^-1 (K_E f - g), a = f - G K_E' b.
            auto precondition = [&](const Eigen::VectorXd& vs) -> Eigen::VectorXd {
              const Eigen::VectorXd v = vs.cwiseQuotient(row_scale);
              Eigen::VectorXd out(e + m);
              const Eigen::VectorXd rhs_b = KE * v.head(e) - v.tail(m);
              out.tail(m) = q_scale.cwiseProduct(frozen_lu.solve(q_scale.cwiseProduct(rhs_b)));
              out.head(e) = v.head(e) - GKt * out.tail(m);
              return out.cwiseQuotient(col_scale);
            };
            // From the iterate itself (w = 0, lambda_A = lambda at u): rhs - M x0 vanishes at the
            // solution, so the tolerance applies to the correction, not to u (the reduced
            // unknowns are the new iterate, whose size is the load's).
            Eigen::VectorXd x0s = Eigen::VectorXd::Zero(e + m);
            for (int a = 0; a < m; ++a) x0s(e + a) = (*base_lambda)(active[static_cast<std::size_t>(a)]) / col_scale(e + a);
            const Eigen::VectorXd r0s = row_scale.cwiseProduct(rhs) - apply(x0s);
            const solve::GmresResult kr = solve::gmres(apply, precondition, r0s, s.krylov_tolerance, s.krylov_max_iterations);
            it.krylov += kr.iterations;
            if (kr.converged) {
              const Eigen::VectorXd x = col_scale.cwiseProduct(x0s + kr.x);
              set_step(E, HE * x.head(e) + KEt * x.tail(m));
              lambda_next.setZero();
              for (int a = 0; a < m; ++a) lambda_next(active[static_cast<std::size_t>(a)]) = x(e + a);
              return true;
            }
          }
        }
        Eigen::MatrixXd M = Eigen::MatrixXd::Zero(e + m, e + m);
        if (!frozen) M.topLeftCorner(e, e) = G * HE;
        M.topLeftCorner(e, e).diagonal().array() += 1.0;
        M.topRightCorner(e, m) = G * KE.transpose();
        M.bottomLeftCorner(m, e) = Eigen::MatrixXd(RE);
        // Equilibration (the blocks carry different units: gaps, displacements, pressures),
        // so that min_rcond judges the problem and not its units.
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
        if (!finite_system || !(rcond >= s.min_rcond) || rcond == 0.0) {
          std::ostringstream os;
          os << "the reduced Newton system (" << e << " contact DOFs, " << m
             << " active rows) is singular (reciprocal condition " << rcond << " < min_rcond " << s.min_rcond << ")";
          return singular_message(os.str());
        }
        const Eigen::VectorXd x = col_scale.cwiseProduct(dense.solve(row_scale.cwiseProduct(rhs)));
        set_step(E, HE * x.head(e) + KE.transpose() * x.tail(m));
        lambda_next.setZero();
        for (int a = 0; a < m; ++a) lambda_next(active[static_cast<std::size_t>(a)]) = x(e + a);
        return true;
      }
      // [A_00 + H, K_A'; -D_A, 0] [du; lambda_A] = [b - A_00 u_0; d_A].
      std::vector<Eigen::Triplet<double>> trip = a_trip;
      if (!frozen) trip.insert(trip.end(), h_free.begin(), h_free.end());
      Eigen::VectorXd rhs(n + m);
      rhs.head(n) = top;
      for (int a = 0; a < m; ++a) {
        const int r = active[static_cast<std::size_t>(a)];
        for (RowSparse::InnerIterator kk(st.K0, r); kk; ++kk) trip.emplace_back(kk.col(), n + a, kk.value());
        if (frozen) {
          for (RowSparse::InnerIterator kk(st.K0, r); kk; ++kk) trip.emplace_back(n + a, kk.col(), kk.value());
        } else {
          for (RowSparse::InnerIterator dd(D0, r); dd; ++dd) trip.emplace_back(n + a, dd.col(), -dd.value());
        }
        rhs(n + a) = (*base_d)(r);
      }
      Eigen::SparseMatrix<double> J(n + m, n + m);
      J.setFromTriplets(trip.begin(), trip.end());
      if (lu.compute(J) != solve::SparseLUStatus::Success) {
        return singular_message("the Newton system (" + std::to_string(n) + " free DOFs, " + std::to_string(m) +
                                " active rows) is " + solve::to_string(lu.status()));
      }
      const Eigen::VectorXd x = lu.solve(rhs);
      du = x.head(n);
      lambda_next.setZero();
      for (int a = 0; a < m; ++a) lambda_next(active[static_cast<std::size_t>(a)]) = x(n + a);
      return true;
    };
    // A solve on the consistent Jacobian, falling back to the frozen one (for the rest of the
    // iteration) when it is singular.
    auto solve_newton_system = [&](const std::vector<char>& act) {
      if (!singular_consistent && solve_active(act, false)) return true;
      if (!singular_consistent) {
        singular_consistent = true;
        it.frozen = true;
      }
      return solve_active(act, true);
    };

    // Predicted active set: the complementarity function of the LINEARIZED gap, d + D du
    // (consistent) or d - K du (frozen). Returns the number of rows that changed in `out`.
    std::vector<char> is_active(static_cast<std::size_t>(R), 0);
    auto predicted_active = [&](std::vector<char>& out, bool frozen) {
      const Eigen::VectorXd d_lin = frozen ? Eigen::VectorXd(st.maps.d - st.K0 * du) : Eigen::VectorXd(st.maps.d + D0 * du);
      int changed = 0;
      for (int r = 0; r < R; ++r) {
        // A non-candidate row (zero K row: no master faces the slave node) never binds.
        const bool candidate = st.K0.outerIndexPtr()[r + 1] > st.K0.outerIndexPtr()[r];
        const char a = candidate && lambda_next(r) - evaluate.c()(r) * d_lin(r) > 0.0 ? 1 : 0;
        if (a != out[static_cast<std::size_t>(r)]) ++changed;
        out[static_cast<std::size_t>(r)] = a;
      }
      return changed;
    };
    predicted_active(is_active, false);  // du = 0: the active set of the iterate itself
    for (int r = 0; r < R; ++r) it.changed += is_active[static_cast<std::size_t>(r)] != previous_active[static_cast<std::size_t>(r)];

    // Kacanov phase (inner_passes Frozen, until the active set settles): the step solves the
    // frozen-geometry linearization exactly (a strictly convex QP: primal-dual active-set passes
    // on it settle), i.e. an undamped Kacanov step. Newton phase: the plain semi-smooth Newton step
    // on the consistent linearization, then, if it predicts another active set, passes on the
    // consistent linearization until the set repeats. From u = u_D the consistent passes alone
    // cycled on fine meshes (hertz-a level 5: a 2-cycle of 7 rows until the cap of 20 passes;
    // level 6: no convergence in 50 iterations; docs/benchmarks.md).
    if (!(kacanov_phase ? solve_active(is_active, true) : solve_newton_system(is_active))) {
      return finish(solve::KacanovStatus::StepFailed, failure);
    }
    Eigen::VectorXd du_first = du;
    const Eigen::VectorXd lambda_first = lambda_next;
    StepSource first_source = step_source;
    int passes = 1;
    const bool pass_frozen = kacanov_phase || singular_consistent;
    const int max_passes = pass_frozen ? s.max_inner_iterations : std::min(s.max_inner_iterations, s.max_newton_passes);
    while (passes < max_passes && predicted_active(is_active, pass_frozen) != 0) {
      if (!(pass_frozen ? solve_active(is_active, true) : solve_newton_system(is_active))) {
        return finish(solve::KacanovStatus::StepFailed, failure);
      }
      ++passes;
    }
    // Branch passes (Newton phase, pointwise rows): the contact maps are piecewise smooth (the
    // closest segment; a vertex's clamped wedge), and on fine hertz-a meshes slave nodes in
    // contact end within 1e-5 of a segment of master vertices: a step that carries them across
    // such a kink converges only linearly (level 5: 2.1e-8 -> 4.2e-9, 27 nodes crossing). When
    // u + du lies on other branches than u, the step is solved again with the maps at u continued
    // on the branches of u + du (contact::linearize_contact_on_branches): exact on piecewise
    // linear maps; repeated while the branches move, at most max_branch_passes times. Only near
    // the solution (KKT residual <= branch_passes_below): further out each pass costs a system
    // and the step's other errors dominate (hertz-a level 6: passes at every Newton iteration
    // 16.9 s CPU, 8 iterations; without 15.1 s, 9).
    if (!pass_frozen && s.max_branch_passes > 0 && it.residual <= s.branch_passes_below &&
        p.quadrature->discretization != contact::Discretization::LAC) {
      for (int pass = 0; pass < s.max_branch_passes; ++pass) {
        // The projection at u + du reads du at the contact nodes only (beyond read_dofs): the
        // backward substitution along their chains gives those entries bitwise as the complete
        // step would, without a substitution through all of L (~0.2 s at 1.2e6 DOFs).
        Eigen::VectorXd du_contact = du;
        if (!step_source.complete) {
          const Eigen::VectorXd x = inverse.solve_sparse(step_source.E, step_source.yE, &contact_free);
          for (int fi : contact_free) du_contact(fi) = z(fi) - x(fi) - st.u0(fi);
        }
        contact::PointwiseContact next;
        try {
          next = contact::project_slave_nodes(*p.mesh, *p.pair, p.dofs->lift() + p.dofs->extend(st.u0 + du_contact),
                                              s.linearization.projection);
        } catch (const Error&) {
          break;  // the full step cannot be evaluated: the line search shortens it
        }
        bool moved = false;
        for (std::size_t q = 0; q < next.projection.size() && !moved; ++q) {
          moved = !contact::same_branch(st.maps.pointwise.projection[q], next.projection[q]);
        }
        if (!moved) break;
        contact::ContactLinearization branch;
        try {
          branch = contact::linearize_contact_on_branches(*p.mesh, *p.pair, *p.quadrature, st.u, st.lambda, movable, next);
        } catch (const Error&) {
          break;
        }
        // The step's system reads K, d (st) and D, H: all on the continued branches now. The
        // merit and the line search keep the maps of u itself (the trials are evaluated afresh).
        st.maps = std::move(branch.maps);
        st.K0 = p.dofs->restrict_columns(st.maps.rows.K);
        D0 = p.dofs->restrict_columns(branch.D);
        set_h_free(branch.H);
        set_read_dofs();
        // A singular system here keeps the previous pass's step (du, lambda_next are untouched).
        if (!solve_newton_system(is_active)) break;
        ++passes;
        ++it.branch_passes;
      }
    }
    complete_step(du, step_source);
    // The frozen passes found the active set at once: the iterate is near enough for Newton.
    if (kacanov_phase && passes <= s.switch_passes) newton_phase = true;
    previous_active = is_active;

    // Kacanov safeguard (Newton phase): the Newton step is good only where the slave nodes'
    // remaining slip is below the master segment length (the contact forces are distributed by
    // the hat functions of xi, whose slope jumps by |lambda_r| / h at each master vertex; on
    // hertz-a the slave nodes in contact end next to master vertices). Further out, e.g. hertz-a
    // level 5 at mu 0.45 from merit 0.21, the full Newton step raised the merit (0.24) where
    // the exact frozen step lowered it to 0.065, and the backtracked Newton steps then crawled
    // (steps of 1/128-1/4 for 14 iterations). So when the full Newton step does not reduce the
    // merit to kacanov_safeguard x its value, the frozen step (Kacanov phase) is computed as
    // well and the full step with the smaller merit goes first into the line search below.
    // Not in iterations with branch passes (st holds the maps continued on other branches
    // there; they happen only in the last, quadratic steps).
    State full_trial;  // the full step of du, evaluated: the line search's first trial
    bool have_full_trial = false;
    if (!kacanov_phase && !pass_frozen && it.branch_passes == 0 && s.kacanov_safeguard > 0.0) {
      const double phi_now = st.merit * st.merit;
      auto evaluate_full = [&](State& out) {
        try {
          out = evaluate(st.u0 + du, lambda_next);
        } catch (const Error&) {
          return std::numeric_limits<double>::infinity();
        }
        return finite(out) ? out.merit * out.merit : std::numeric_limits<double>::infinity();
      };
      State newton_trial;
      const double phi_newton = evaluate_full(newton_trial);
      if (!(phi_newton <= s.kacanov_safeguard * s.kacanov_safeguard * phi_now)) {
        const Eigen::VectorXd du_newton = du, lambda_newton = lambda_next;
        const StepSource source_newton = step_source;
        // The frozen passes from the iterate's own active set (du = 0), as in the Kacanov phase.
        std::vector<char> frozen_active(static_cast<std::size_t>(R), 0);
        du.setZero();
        lambda_next = st.lambda;
        predicted_active(frozen_active, true);
        bool solved = solve_active(frozen_active, true);
        for (int pass = 1; solved && pass < s.max_inner_iterations && predicted_active(frozen_active, true) != 0; ++pass) {
          solved = solve_active(frozen_active, true);
        }
        State frozen_trial;
        double phi_frozen = std::numeric_limits<double>::infinity();
        if (solved) {
          complete_step(du, step_source);
          phi_frozen = evaluate_full(frozen_trial);
        }
        if (phi_frozen < phi_newton) {
          it.kacanov_step = true;
          previous_active = frozen_active;
          full_trial = std::move(frozen_trial);
          have_full_trial = true;
        } else {
          du = du_newton;
          lambda_next = lambda_newton;
          step_source = source_newton;
          failure.clear();  // a singular frozen system here only means: keep the Newton step
        }
      }
      if (!have_full_trial && std::isfinite(phi_newton)) {
        full_trial = std::move(newton_trial);
        have_full_trial = true;
      }
    }
    // Chord corrections (Newton phase, when the step is a Newton step): the full step's trial
    // (u_1, lambda_1) is corrected with the iterate's Jacobian J on the same active rows,
    //   J [dv; lambda_2] = -F(u_1, lambda_1),
    // i.e. the Newton system written at u_1 with K_0, D, H of the iterate:
    //   [A_00 + H, K_A'; -D_A, 0] [dv; lambda_2] = [b - A_00 u_1 + (K_0 - K_0(u_1))' lambda_1; d_A(u_1)].
    // On a smooth residual the error after the pair of solves is O(e^3) instead of O(e^2)
    // (Shamanskii's method); on hertz-a at mu 0.45 the Newton steps from merit ~0.1 left a
    // residual that is such a second-order term (docs/solvers.md, "Limits"). A correction is
    // kept only when it lowers the merit of the full step; then the line search below starts
    // from the corrected step (and backtracks along the plain Newton direction).
    Eigen::VectorXd du_plain, lambda_plain;  // the Newton step, when a chord correction was kept
    if (!kacanov_phase && !it.kacanov_step && s.chord_steps > 0) {
      complete_step(du, step_source);
      if (!have_full_trial) {
        try {
          full_trial = evaluate(st.u0 + du, lambda_next);
          have_full_trial = finite(full_trial);
        } catch (const Error&) {
          have_full_trial = false;
        }
      }
      for (int c = 0; c < s.chord_steps && have_full_trial && full_trial.kkt() > s.tolerance; ++c) {
        // f = (K_0 - K_0(u_1))' lambda_1, on the few contact DOFs of both geometries.
        const Eigen::VectorXd extra = (st.K0 - full_trial.K0).transpose() * full_trial.lambda;
        std::vector<int> in;
        std::vector<double> values;
        for (int i = 0; i < n; ++i) {
          if (extra(i) != 0.0) {
            in.push_back(i);
            values.push_back(extra(i));
          }
        }
        // ActiveSchur: the systems read z_chord = A_00^-1 (b + f) on read_dofs and on H's DOFs
        // (E lies in them); the whole step is formed below in one substitution.
        Eigen::VectorXd z_chord;
        if (schur) {
          z_chord = z;
          if (!in.empty()) {
            std::vector<int> out = read_dofs;
            for (const auto& t : h_free) {
              out.push_back(t.row());
              out.push_back(t.col());
            }
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
            z_chord += inverse.solve_sparse(in, Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())), &out);
          }
        } else {
          top = *p.b - *p.A00 * full_trial.u0 + extra;
        }
        const Eigen::VectorXd du_keep = du, lambda_keep = lambda_next;
        const StepSource source_keep = step_source;
        base_z = &z_chord;
        base_u0 = &full_trial.u0;
        base_d = &full_trial.maps.d;
        base_lambda = &full_trial.lambda;
        const bool solved = solve_newton_system(is_active);
        base_z = &z;
        base_u0 = &st.u0;
        base_d = &st.maps.d;
        base_lambda = &st.lambda;
        if (!schur) top = *p.b - *p.A00 * st.u0;
        failure.clear();  // a singular system here only means: keep the step as it was
        State chord_trial;
        bool better = false;
        if (solved) {
          if (!step_source.complete) {
            // u_1 + dv = z - A_00^-1 (P_E y_E - f): the step from u_0 in one substitution.
            std::vector<std::pair<int, double>> rhs;
            for (std::size_t a = 0; a < step_source.E.size(); ++a) rhs.emplace_back(step_source.E[a], step_source.yE(static_cast<Eigen::Index>(a)));
            for (std::size_t a = 0; a < in.size(); ++a) rhs.emplace_back(in[a], -values[a]);
            std::sort(rhs.begin(), rhs.end());
            std::vector<int> idx;
            std::vector<double> val;
            for (const auto& [i, v] : rhs) {
              if (!idx.empty() && idx.back() == i) {
                val.back() += v;
              } else {
                idx.push_back(i);
                val.push_back(v);
              }
            }
            du = z - inverse.solve_sparse(idx, Eigen::Map<const Eigen::VectorXd>(val.data(), static_cast<Eigen::Index>(val.size()))) - st.u0;
            step_source.complete = true;
          } else {
            du = full_trial.u0 + du - st.u0;  // SaddleLU: dv itself
          }
          try {
            chord_trial = evaluate(st.u0 + du, lambda_next);
            better = finite(chord_trial) && chord_trial.merit < full_trial.merit;
          } catch (const Error&) {
            better = false;
          }
        }
        if (!better) {
          du = du_keep;
          lambda_next = lambda_keep;
          step_source = source_keep;
          break;
        }
        if (c == 0) {
          du_plain = du_keep;
          lambda_plain = lambda_keep;
        }
        full_trial = std::move(chord_trial);
        ++it.chord_steps;
      }
    }
    it.factorize_s = seconds_since(t0);
    const Eigen::VectorXd dlambda = lambda_next - st.lambda;

    // Globalization: Armijo backtracking on the merit; a full step that changes the active set
    // is taken without a decrease (combinatorial phase), at most max_free_steps times. Order of
    // the trials: the full step of the inner active-set passes; then, when the passes moved the
    // active set, the plain semi-smooth Newton direction (a descent direction of the merit,
    // which the passes' one need not be: on hertz-a level 5 the latter alone crawled with steps
    // of 1/16-1/64 for 6 iterations), backtracked; then the passes' direction backtracked.
    const auto t_search = Clock::now();
    const double phi0 = st.merit * st.merit;
    bool accepted = false;
    State best;
    double best_phi = std::numeric_limits<double>::infinity();
    double best_t = 0.0;
    const Eigen::VectorXd dlambda_first = passes > 1 ? Eigen::VectorXd(lambda_first - st.lambda) : Eigen::VectorXd();
    struct Trial {
      const Eigen::VectorXd* du;
      const Eigen::VectorXd* dl;
      double t_first, t_last;
    };
    std::vector<Trial> trials{{&du, &dlambda, 1.0, 1.0}};
    if (passes > 1) trials.push_back({&du_first, &dlambda_first, 1.0, s.min_step});
    const Eigen::VectorXd dlambda_plain = it.chord_steps > 0 ? Eigen::VectorXd(lambda_plain - st.lambda) : Eigen::VectorXd();
    if (it.chord_steps > 0) {
      trials.push_back({&du_plain, &dlambda_plain, 0.5, s.min_step});
    } else {
      trials.push_back({&du, &dlambda, 0.5, s.min_step});
    }
    for (const Trial& tr : trials) {
      if (tr.du == &du_first) complete_step(du_first, first_source);
      for (double t = tr.t_first; t >= tr.t_last && !accepted; t *= 0.5) {
        State trial;
        if (have_full_trial && tr.du == &du && t == 1.0) {
          trial = std::move(full_trial);  // evaluated by the safeguard above
          have_full_trial = false;
        } else {
          try {
            trial = evaluate(st.u0 + t * *tr.du, st.lambda + t * *tr.dl);
          } catch (const Error&) {
            continue;  // the geometry cannot be evaluated there: shorten the step
          }
        }
        if (!finite(trial)) continue;
        const double phi = trial.merit * trial.merit;
        const bool decrease = phi <= (1.0 - 2.0 * s.armijo * t) * phi0;
        const bool free_step = t == 1.0 && tr.du == &du && free_steps < s.max_free_steps;
        if (decrease || free_step) {
          if (!decrease) ++free_steps;
          it.step = t;
          st = std::move(trial);
          accepted = true;
          break;
        }
        if (phi < best_phi) {
          best_phi = phi;
          best_t = t;
          best = std::move(trial);
        }
      }
      if (accepted) break;
    }
    if (!accepted) {
      if (!std::isfinite(best_phi)) {
        return finish(solve::KacanovStatus::StepFailed,
                      "semi-smooth Newton iteration " + std::to_string(k) +
                          ": no damped step can be evaluated (the contact geometry fails at every trial); " +
                          residual_text(st));
      }
      it.step = best_t;  // no decrease down to min_step: take the best trial, the cap ends a stall
      st = std::move(best);
    }
    it.search_s = seconds_since(t_search);
    res.history.push_back(it);
    res.iterations = k + 1;
  }
}

}  // namespace contactrb::hf
