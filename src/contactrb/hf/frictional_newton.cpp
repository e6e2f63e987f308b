// One load step of the frictional solver: the semi-smooth Newton iteration of docs/solvers.md,
// "Friction" (steps 1-4 there).
#include "contactrb/hf/frictional_newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/tangential_rows.hpp"
#include "contactrb/hf/friction_system.hpp"

namespace contactrb::hf {

namespace {

using Clock = std::chrono::steady_clock;
inline std::size_t sz(Eigen::Index i) { return static_cast<std::size_t>(i); }

// Armijo constant and the smallest damping factor of the line search (step 4), as the
// frictionless Newton's defaults (NewtonTuning).
constexpr double kArmijo = 1e-4;
constexpr double kMinStep = 1.0 / 1024.0;
// A row touches at u_prev when its weighted gap d_r is at most this times |I_r| x the mesh's
// diameter (round-off of a zero gap, e.g. two blocks meshed in contact).
constexpr double kTouchingGap = 1e-12;
// A reduced system with a smaller reciprocal condition estimate is singular (NewtonTuning::min_rcond).
constexpr double kMinRcond = 1e-14;

// The diagonal of the mesh's bounding box.
template <int Dim>
double diameter(const mesh::SimplexMesh<Dim>& mesh) {
  Eigen::Matrix<double, Dim, 1> lo = mesh.nodes.front(), hi = lo;
  for (const auto& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

// frictional_rows with the contact maps at u_prev evaluated.
template <int Dim>
std::vector<char> frictional_rows(const FrictionAlgebra<Dim>& p, const FrictionState<Dim>& previous,
                                  const contact::ContactMapsOf<Dim>& before) {
  const int R = static_cast<int>(p.quadrature->weight.size());
  const double size = diameter(*p.mesh);
  std::vector<char> frictional(sz(R), 0);
  for (int r = 0; r < R; ++r) {
    const bool candidate = before.rows.K.outerIndexPtr()[r + 1] > before.rows.K.outerIndexPtr()[r];
    const double touching = kTouchingGap * p.quadrature->weight(r) * size;
    frictional[sz(r)] = candidate && (previous.lambda(r) > 0.0 || before.d(r) <= touching) ? 1 : 0;
  }
  return frictional;
}

// An iterate and what the method reads at it.
template <int Dim>
struct FrictionIterate {
  static constexpr int M = Dim - 1;  // tangential components per slave node
  NewtonIterate<Dim> n;              // u_0, lambda, u, the maps, K_0, the normal KKT numbers
  Eigen::VectorXd lambda_t;          // M R
  RowSparse T0;                      // T(u) on the free columns
  RowSparse S0;                      // delta'(u) on the free columns (contact::slip_rows)
  Eigen::VectorXd slip;              // M R: contact::tangential_slip since u_prev
  Eigen::VectorXd delta;             // -|I_r| slip_r: the weighted slip, in the units of the rows
  Eigen::VectorXd z;                 // lambda_t + c delta
  Eigen::VectorXd s;                 // R: the slip threshold of each row
  Eigen::VectorXd Ct;                // M R: the tangential complementarity function
  std::vector<SlipState> state;      // R
  Eigen::VectorXd F1;                // A_00 u_0 - b + K_0' lambda + T_0' lambda_t
  FrictionKKT kkt;
  double merit = 0.0;
  bool finite() const { return hf::finite(n) && lambda_t.allFinite() && std::isfinite(merit); }
  int count(SlipState which) const { return static_cast<int>(std::count(state.begin(), state.end(), which)); }
};

template <int Dim>
class FrictionStep {
 public:
  static constexpr int M = Dim - 1;
  FrictionStep(const FrictionAlgebra<Dim>& p, const FrictionState<Dim>& previous, solve::SelectedInverse* inverse,
               const FrictionSettings& s);
  // Throws contactrb::Error when the geometry cannot be evaluated at u.
  FrictionIterate<Dim> evaluate(Eigen::VectorXd u0, Eigen::VectorXd lambda, Eigen::VectorXd lambda_t) const;
  // Step 2: the generalized Newton system at x.
  FrictionSystemResult newton_step(const FrictionIterate<Dim>& x, bool consistent) const;
  // The largest slip increment of x, relative to max_slip x the mesh's diameter (> 1: divergence).
  double slip_ratio(const FrictionIterate<Dim>& x) const;
  double move_ratio(const Eigen::VectorXd& du) const {
    return (du.size() > 0 ? du.cwiseAbs().maxCoeff() : 0.0) / (s_.max_slip * diameter_);
  }
  Eigen::VectorXd slip_length(const FrictionIterate<Dim>& x) const;

 private:
  bool in_contact(const FrictionIterate<Dim>& x, int r) const;
  void classify(FrictionIterate<Dim>& x) const;
  void residuals(FrictionIterate<Dim>& x) const;
  void add_tangential_rows(const FrictionIterate<Dim>& x, int r, FrictionJacobian& J) const;

  const FrictionAlgebra<Dim>& p_;
  const FrictionSettings& s_;
  const NewtonSettings newton_settings_;  // the evaluator's projection options
  const NewtonEvaluator<Dim> evaluate_;
  const int n_, R_;
  std::vector<int> global_to_free_;
  std::vector<char> movable_;
  solve::SelectedInverse* inverse_;  // A_00 factorized, or nullptr (sparse LU)
  Eigen::VectorXd z_;                // A_00^-1 b (with inverse_)
  double diameter_ = 0.0;
  std::vector<Eigen::Matrix<double, Dim, 1>> rho_previous_;  // contact::material_points at u_prev
  // Rows in contact at u_prev (lambda_r > 0 or touching): only they carry friction in the step;
  // a row that closes during the step has no slip history yet (docs/solvers.md, "Friction").
  std::vector<char> frictional_;
};

NewtonSettings evaluator_settings(const FrictionSettings& s) {
  NewtonSettings n;
  n.linearization = s.linearization;
  return n;
}

template <int Dim>
FrictionStep<Dim>::FrictionStep(const FrictionAlgebra<Dim>& p, const FrictionState<Dim>& previous,
                                 solve::SelectedInverse* inverse, const FrictionSettings& s)
    : p_(p),
      s_(s),
      newton_settings_(evaluator_settings(s)),
      evaluate_(p, newton_settings_),
      n_(p.dofs->num_free()),
      R_(static_cast<int>(p.quadrature->weight.size())),
      global_to_free_(sz(p.dofs->num_dofs()), -1),
      movable_(sz(p.dofs->num_dofs()), 0),
      inverse_(inverse) {
  if (inverse_ != nullptr) z_ = inverse_->solve(*p.b);
  for (int i = 0; i < n_; ++i) {
    const int g = p.dofs->free_dofs()[sz(i)];
    global_to_free_[sz(g)] = i;
    movable_[sz(g)] = 1;
  }
  diameter_ = diameter(*p.mesh);
  const contact::ContactMapsOf<Dim> before =
      contact::evaluate_contact_maps(*p.mesh, *p.pair, *p.quadrature, previous.u, s.linearization.projection);
  frictional_ = frictional_rows(p, previous, before);
  rho_previous_ = contact::material_points<Dim>(*p.mesh, *p.pair, before.pointwise, previous.u);
}

// The normal law's active set: a candidate row with lambda_r - c_r d_r >= 0 (a touching row
// without pressure counts: two bodies meshed in contact start held by their stick rows).
template <int Dim>
bool FrictionStep<Dim>::in_contact(const FrictionIterate<Dim>& x, int r) const {
  const bool candidate = x.n.K0.outerIndexPtr()[r + 1] > x.n.K0.outerIndexPtr()[r];
  return candidate && x.n.lambda(r) - evaluate_.c()(r) * x.n.maps.d(r) >= 0.0;
}

// Step 1: the states of the rows, read off the complementarity functions at the iterate.
// Contact where lambda_r - c_r d_r > 0 (the normal law's active set); there the threshold is
// s_r (Tresca) or f lambda_r (Coulomb), and the row sticks when |lambda_t,r + c_r delta_r| <= s_r.
template <int Dim>
void FrictionStep<Dim>::classify(FrictionIterate<Dim>& x) const {
  const Eigen::VectorXd& c = evaluate_.c();
  x.z = x.lambda_t;
  x.Ct = x.lambda_t;
  x.s = Eigen::VectorXd::Zero(R_);
  x.state.assign(sz(R_), SlipState::Open);
  for (int r = 0; r < R_; ++r) {
    auto z = x.z.template segment<M>(M * r);
    z += c(r) * x.delta.template segment<M>(M * r);
    if (!in_contact(x, r)) continue;  // open: C_t = lambda_t
    if (!frictional_[sz(r)]) {  // closes in this step: no friction yet, C_t = lambda_t
      x.state[sz(r)] = SlipState::Stick;
      continue;
    }
    const double s = s_.law == FrictionLaw::Tresca ? s_.threshold : s_.coefficient * x.n.lambda(r);
    x.s(r) = s;
    auto Ct = x.Ct.template segment<M>(M * r);
    if (z.norm() <= s) {
      x.state[sz(r)] = SlipState::Stick;
      Ct = -c(r) * x.delta.template segment<M>(M * r);
    } else {
      x.state[sz(r)] = SlipState::Slip;
      Ct = x.lambda_t.template segment<M>(M * r) - (s / z.norm()) * z;
    }
  }
}

// The report (FrictionKKT) and the merit |F| of the whole nonsmooth system, its complementarity
// rows in force units (|I_r| C).
template <int Dim>
void FrictionStep<Dim>::residuals(FrictionIterate<Dim>& x) const {
  const Eigen::VectorXd Ttl = x.T0.transpose() * x.lambda_t;
  x.F1 = x.n.F1 + Ttl;
  const Eigen::VectorXd contact_forces = x.n.F1 - (*p_.A00 * x.n.u0 - *p_.b) + Ttl;
  const double force_scale = std::max({p_.b->norm(), contact_forces.norm(), 1e-300});
  x.kkt.normal = HFKKT{x.F1.norm() / force_scale, x.n.primal, x.n.dual, x.n.complementarity};
  x.kkt.friction = x.Ct.size() > 0 ? x.n.lambda_scale.relative(x.Ct.cwiseAbs().maxCoeff()) : 0.0;
  double ct2 = 0.0;
  for (int r = 0; r < R_; ++r) ct2 += std::pow(p_.quadrature->weight(r), 2) * x.Ct.template segment<M>(M * r).squaredNorm();
  x.merit = std::sqrt(x.F1.squaredNorm() + x.n.ncp.cwiseProduct(p_.quadrature->weight).squaredNorm() + ct2);
}

template <int Dim>
FrictionIterate<Dim> FrictionStep<Dim>::evaluate(Eigen::VectorXd u0, Eigen::VectorXd lambda,
                                                 Eigen::VectorXd lambda_t) const {
  FrictionIterate<Dim> x;
  x.n = evaluate_(std::move(u0), std::move(lambda));
  const RowSparse T = contact::tangential_rows<Dim>(*p_.mesh, *p_.pair, *p_.quadrature, x.n.maps.pointwise);
  x.T0 = p_.dofs->restrict_columns(T);
  x.slip = contact::tangential_slip<Dim>(
      x.n.maps.pointwise, contact::material_points<Dim>(*p_.mesh, *p_.pair, x.n.maps.pointwise, x.n.u), rho_previous_);
  for (int r = 0; r < R_; ++r) {
    if (!frictional_[sz(r)]) x.slip.template segment<M>(M * r).setZero();
  }
  x.delta = Eigen::VectorXd::Zero(M * R_);  // -W slip, W acting on the M components of each node
  for (int r = 0; r < R_; ++r) {
    for (RowSparse::InnerIterator w(p_.quadrature->W, r); w; ++w) {
      x.delta.template segment<M>(M * r) -= w.value() * x.slip.template segment<M>(M * w.col());
    }
  }
  x.S0 = p_.dofs->restrict_columns(
      contact::slip_rows<Dim>(*p_.mesh, *p_.pair, *p_.quadrature, x.n.maps.pointwise, x.n.u));
  x.lambda_t = std::move(lambda_t);
  classify(x);
  residuals(x);
  return x;
}

// The rows of C_t,r linearized (generalized Jacobian; S = delta'(u), contact::slip_rows): open,
// lambda_t,r = 0; stick, S_r du = -delta_r; slip, with z^ = z / |z|, P = I - z^ z^', a = s / |z|,
//   (I - a P) lambda_t' - f z^ lambda_r' - a c_r P S_r du = (I - a P) lambda_t - f z^ lambda_r - C_t
// (Tresca: no lambda_r term; 2D: P = 0, the row is lambda_t' = f lambda_r' z^, or s z^).
template <int Dim>
void FrictionStep<Dim>::add_tangential_rows(const FrictionIterate<Dim>& x, int r, FrictionJacobian& J) const {
  const int base = n_ + R_ + M * r;  // the rows and the multiplier columns
  std::vector<Eigen::Triplet<double>>& trip = J.rows;
  const SlipState state = x.state[sz(r)];
  if (state == SlipState::Open || !frictional_[sz(r)]) {
    for (int j = 0; j < M; ++j) {
      trip.emplace_back(base + j, base + j, 1.0);  // rhs 0
      J.zero[sz(R_ + M * r + j)] = 1;
    }
    return;
  }
  if (state == SlipState::Stick) {
    for (int j = 0; j < M; ++j) {
      for (RowSparse::InnerIterator t(x.S0, M * r + j); t; ++t) trip.emplace_back(base + j, t.col(), t.value());
      J.rhs(R_ + M * r + j) = -x.delta(M * r + j);
    }
    return;
  }
  using Block = Eigen::Matrix<double, M, M>;
  using Vec = Eigen::Matrix<double, M, 1>;
  const Vec z = x.z.template segment<M>(M * r);
  const Vec zh = z / z.norm();
  const double a = x.s(r) / z.norm();
  const Block P = Block::Identity() - zh * zh.transpose();
  const Block Jt = Block::Identity() - a * P;
  const Vec Jn = s_.law == FrictionLaw::Coulomb ? Vec(-s_.coefficient * zh) : Vec(Vec::Zero());
  const Vec rhs_r = Jt * x.lambda_t.template segment<M>(M * r) + Jn * x.n.lambda(r) - x.Ct.template segment<M>(M * r);
  for (int j = 0; j < M; ++j) {
    for (int l = 0; l < M; ++l) {
      if (Jt(j, l) != 0.0) trip.emplace_back(base + j, base + l, Jt(j, l));
      const double pu = -a * evaluate_.c()(r) * P(j, l);
      if (pu == 0.0) continue;
      for (RowSparse::InnerIterator t(x.S0, M * r + l); t; ++t) trip.emplace_back(base + j, t.col(), pu * t.value());
    }
    if (Jn(j) != 0.0) trip.emplace_back(base + j, n_ + r, Jn(j));
    J.rhs(R_ + M * r + j) = rhs_r(j);
  }
}

// Step 2: the generalized Newton system (friction_system.hpp). Normal rows: in contact,
// -D_r du = d_r (consistent: D = d'(u), H = (K' lambda)' + (T' lambda_t)' through xi,
// contact::tangential_stiffness) or K_r du = d_r (frozen: H = 0); open, lambda_r = 0. The
// tangential rows: add_tangential_rows (the tangents held at the iterate: small sliding).
template <int Dim>
FrictionSystemResult FrictionStep<Dim>::newton_step(const FrictionIterate<Dim>& x, bool consistent) const {
  FrictionJacobian J;
  J.A00 = p_.A00;
  RowSparse D0;
  if (consistent) {
    const contact::ContactLinearizationOf<Dim> lin = contact::linearize_contact(
        *p_.mesh, *p_.pair, *p_.quadrature, x.n.u, x.n.lambda, movable_, x.n.maps, s_.linearization);
    D0 = p_.dofs->restrict_columns(lin.D);
    const Eigen::SparseMatrix<double> Ht = contact::tangential_stiffness<Dim>(
        *p_.mesh, *p_.pair, *p_.quadrature, x.n.maps.pointwise, x.n.u, x.lambda_t);
    for (const Eigen::SparseMatrix<double>* H : {&lin.H, &Ht}) {
      for (int j = 0; j < H->outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator h(*H, j); h; ++h) {
          const int fr = global_to_free_[sz(h.row())], fc = global_to_free_[sz(h.col())];
          if (fr >= 0 && fc >= 0) J.H.emplace_back(fr, fc, h.value());
        }
      }
    }
  }
  {
    std::vector<Eigen::Triplet<double>> b;
    for (const RowSparse* rows : {&x.n.K0, &x.T0}) {
      const int offset = rows == &x.n.K0 ? 0 : R_;
      for (int i = 0; i < rows->outerSize(); ++i) {
        for (RowSparse::InnerIterator k(*rows, i); k; ++k) b.emplace_back(offset + i, k.col(), k.value());
      }
    }
    J.B.resize(R_ + M * R_, n_);
    J.B.setFromTriplets(b.begin(), b.end());
  }
  J.top = *p_.b - *p_.A00 * x.n.u0;
  J.rhs = Eigen::VectorXd::Zero(R_ + M * R_);
  J.zero.assign(sz(R_ + M * R_), 0);
  for (int r = 0; r < R_; ++r) {
    if (in_contact(x, r)) {
      const RowSparse& rows = consistent ? D0 : x.n.K0;
      const double sign = consistent ? -1.0 : 1.0;
      for (RowSparse::InnerIterator d(rows, r); d; ++d) J.rows.emplace_back(n_ + r, d.col(), sign * d.value());
      J.rhs(r) = x.n.maps.d(r);
    } else {
      J.rows.emplace_back(n_ + r, n_ + r, 1.0);
      J.zero[sz(r)] = 1;
    }
    add_tangential_rows(x, r, J);
  }
  return solve_friction_system(J, inverse_, z_, x.n.u0, s_.lu, kMinRcond);
}

template <int Dim>
Eigen::VectorXd FrictionStep<Dim>::slip_length(const FrictionIterate<Dim>& x) const {
  return x.slip;
}

template <int Dim>
double FrictionStep<Dim>::slip_ratio(const FrictionIterate<Dim>& x) const {
  const Eigen::VectorXd slip = slip_length(x);
  return (slip.size() > 0 ? slip.cwiseAbs().maxCoeff() : 0.0) / (s_.max_slip * diameter_);
}

// The iteration of one load step (docs/solvers.md, "Friction").
template <int Dim>
class FrictionDriver {
 public:
  FrictionDriver(const FrictionAlgebra<Dim>& p, const FrictionState<Dim>& previous, const FrictionState<Dim>& start,
                 solve::SelectedInverse* inverse, const FrictionSettings& s)
      : p_(p), start_(start), s_(s), step_(p, previous, inverse, s) {}

  FrictionStepResult<Dim> run() {
    const auto t0 = Clock::now();
    if (start()) {
      for (int k = 0; keep_iterating(k); ++k) {  // step 5: the convergence test at each iterate
        if (!iterate(k)) break;                  // steps 1-4
      }
    }
    out_.report.time_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return std::move(out_);
  }

 private:
  bool start() {
    try {
      x_ = step_.evaluate(p_.dofs->restrict(start_.u), start_.lambda, start_.lambda_t);
    } catch (const Error& e) {
      out_.report.status = FrictionStatus::StepFailed;
      out_.report.message = std::string("friction: the start of the step cannot be evaluated: ") + e.what();
      return false;
    }
    return true;
  }

  bool finish(FrictionStatus status, std::string message) {
    FrictionStepReport& rep = out_.report;
    rep.status = status;
    rep.message = std::move(message);
    rep.stick = x_.count(SlipState::Stick);
    rep.slip = x_.count(SlipState::Slip);
    rep.open = x_.count(SlipState::Open);
    rep.normal_force = x_.n.lambda.dot(p_.quadrature->weight);
    rep.tangential_force = Eigen::VectorXd::Zero(FrictionIterate<Dim>::M);
    for (int r = 0; r < x_.n.lambda.size(); ++r) {
      rep.tangential_force +=
          p_.quadrature->weight(r) * x_.lambda_t.template segment<FrictionIterate<Dim>::M>(FrictionIterate<Dim>::M * r);
    }
    out_.u0 = x_.n.u0;
    out_.state = FrictionState<Dim>{x_.n.u, x_.n.lambda, x_.lambda_t};
    out_.slip = step_.slip_length(x_);
    out_.nodes = x_.state;
    out_.kkt = x_.kkt;
    return false;
  }

  // Step 5: converged, or out of iterations, or not finite.
  bool keep_iterating(int k) {
    out_.report.iterations = k;
    out_.report.residuals.push_back(x_.kkt.max());
    if (!x_.finite()) return finish(FrictionStatus::NonFinite, "friction iteration " + std::to_string(k) + ": the iterate is not finite");
    if (x_.kkt.max() <= s_.tolerance) return finish(FrictionStatus::Converged, "");
    if (k >= s_.max_iterations) {
      std::ostringstream os;
      os << "friction: the load step did not converge in " << k << " iterations (tolerance " << s_.tolerance
         << "); last " << residual_text(x_.kkt.normal.stationarity, x_.kkt.normal.primal, x_.kkt.normal.dual,
                                        x_.kkt.normal.complementarity)
         << ", friction " << x_.kkt.friction << "; " << x_.count(SlipState::Stick) << " stick, "
         << x_.count(SlipState::Slip) << " slip";
      return finish(FrictionStatus::MaxIterations, os.str());
    }
    return true;
  }

  // A failure of the step: full sliding when no row sticks (nothing holds the body tangentially).
  bool fail(int k, const std::string& what) {
    const bool sliding = x_.count(SlipState::Stick) == 0;
    std::ostringstream os;
    os << "friction iteration " << k << ": " << what;
    if (sliding) {
      os << "; no node sticks (" << x_.count(SlipState::Slip) << " slip, " << x_.count(SlipState::Open)
         << " open): full sliding, no equilibrium";
    }
    return finish(sliding ? FrictionStatus::FullSliding : FrictionStatus::StepFailed, os.str());
  }

  // Steps 1-4: the states (evaluated with the iterate), the Newton system (frozen normal geometry
  // until the states repeat, then consistent), the line search on the merit.
  bool iterate(int k) {
    const bool consistent = k > 0 && x_.state == previous_state_;
    previous_state_ = x_.state;
    FrictionSystemResult sys;
    try {
      sys = step_.newton_step(x_, consistent);
    } catch (const Error& e) {
      sys.message = std::string("the contact maps cannot be linearized: ") + e.what();
    }
    if (!sys.solved) return fail(k, sys.message);
    const int R = static_cast<int>(x_.n.lambda.size());
    return line_search(k, sys.du, sys.mu.head(R), sys.mu.tail(FrictionIterate<Dim>::M * R));
  }

  // Step 4: the first damping alpha = 1, 1/2, ... with an Armijo decrease of the merit; without
  // one the full step (the states then change: the iteration cap ends a cycle).
  bool line_search(int k, const Eigen::VectorXd& du, const Eigen::VectorXd& lambda, const Eigen::VectorXd& lambda_t) {
    std::optional<FrictionIterate<Dim>> full;
    for (double alpha = 1.0; alpha >= kMinStep; alpha *= 0.5) {
      FrictionIterate<Dim> trial;
      try {
        trial = step_.evaluate(x_.n.u0 + alpha * du, x_.n.lambda + alpha * (lambda - x_.n.lambda),
                               x_.lambda_t + alpha * (lambda_t - x_.lambda_t));
      } catch (const Error&) {
        continue;  // the step leaves what the geometry can evaluate: shorten it
      }
      if (alpha == 1.0 && (step_.slip_ratio(trial) > 1.0 || step_.move_ratio(du) > 1.0)) {
        return fail(k, "the step moves or slips a node by more than max_slip x the mesh's diameter");
      }
      if (trial.finite() && trial.merit <= (1.0 - kArmijo * alpha) * x_.merit) {
        x_ = std::move(trial);
        return true;
      }
      if (alpha == 1.0 && trial.finite()) full = std::move(trial);
    }
    if (!full) return fail(k, "no step along the Newton direction can be evaluated");
    x_ = std::move(*full);
    return true;
  }

  const FrictionAlgebra<Dim>& p_;
  const FrictionState<Dim>& start_;
  const FrictionSettings& s_;
  FrictionStep<Dim> step_;
  FrictionIterate<Dim> x_;
  std::vector<SlipState> previous_state_;
  FrictionStepResult<Dim> out_;
};

}  // namespace

template <int Dim>
std::vector<char> frictional_rows(const FrictionAlgebra<Dim>& algebra, const FrictionState<Dim>& previous,
                                  const contact::ProjectionOptions& projection) {
  return frictional_rows(algebra, previous,
                         contact::evaluate_contact_maps(*algebra.mesh, *algebra.pair, *algebra.quadrature, previous.u,
                                                        projection));
}

template <int Dim>
FrictionStepResult<Dim> solve_friction_step(const FrictionAlgebra<Dim>& algebra, const FrictionState<Dim>& previous,
                                            const FrictionState<Dim>& start, solve::SelectedInverse* inverse,
                                            const FrictionSettings& settings) {
  return FrictionDriver<Dim>(algebra, previous, start, inverse, settings).run();
}

template FrictionStepResult<2> solve_friction_step(const FrictionAlgebra<2>&, const FrictionState<2>&,
                                                   const FrictionState<2>&, solve::SelectedInverse*,
                                                   const FrictionSettings&);
template FrictionStepResult<3> solve_friction_step(const FrictionAlgebra<3>&, const FrictionState<3>&,
                                                   const FrictionState<3>&, solve::SelectedInverse*,
                                                   const FrictionSettings&);

template std::vector<char> frictional_rows(const FrictionAlgebra<2>&, const FrictionState<2>&,
                                           const contact::ProjectionOptions&);
template std::vector<char> frictional_rows(const FrictionAlgebra<3>&, const FrictionState<3>&,
                                           const contact::ProjectionOptions&);

}  // namespace contactrb::hf
