#include "contactrb/solve/nonnegative_qp.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::solve {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// A pivot below -kNotPsdPivot * Q_jj is not rounding on a PSD matrix (whose Q_FF has a
// condition number below about 1 / rank_tolerance).
constexpr double kNotPsdPivot = 1e-2;
// A gradient entry below -kGradientNoise (|P| + 1) eps s is negative beyond the rounding of
// Q x - c: such entries may enter even when above -tolerance * s (which only certifies).
constexpr double kGradientNoise = 2.0;
// After a step, a variable moving to zero that keeps less than this fraction of its value is
// set to zero too (ties of the ratio test up to rounding).
constexpr double kTieFraction = 16 * kEps;
// Entries of a null direction below this fraction of its largest entry are rounding noise.
constexpr double kDirectionNoise = 1e-13;
// An outer iteration makes progress when the objective falls by more than this multiple of
// its rounding bound; otherwise the entering index is excluded until progress resumes.
constexpr double kProgressRoundoff = 8.0;
// Warm sets of at least this size are factored at once (blocked Cholesky) before falling back
// to one-by-one bordering.
constexpr int kBulkFactorMin = 12;

std::string dims(const Eigen::MatrixXd& A) {
  std::ostringstream s;
  s << A.rows() << " x " << A.cols();
  return s.str();
}

}  // namespace

const char* to_string(QPStatus status) {
  switch (status) {
    case QPStatus::Solved:
      return "solved";
    case QPStatus::MaxIterations:
      return "max-iterations";
    case QPStatus::Numerics:
      return "numerics";
    case QPStatus::Unbounded:
      return "unbounded";
    case QPStatus::InvalidInput:
      return "invalid-input";
  }
  return "unknown";
}

QPStatus qp_status_from_string(const std::string& name) {
  using enum QPStatus;
  return enum_from_string(name, "QP status", std::array{Solved, MaxIterations, Numerics, Unbounded, InvalidInput});
}

double KKTResiduals::max() const { return std::max({primal, dual, complementarity}); }

KKTResiduals kkt_residuals(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const Eigen::VectorXd& x) {
  if (!(Q.rows() == Q.cols())) throw Error("kkt_residuals: Q must be square, got " + dims(Q));
  if (!(c.size() == Q.rows() && x.size() == Q.rows()))
    throw Error("kkt_residuals: Q is " + dims(Q) + " but c has size " + std::to_string(c.size()) +
                " and x has size " + std::to_string(x.size()));
  KKTResiduals k;
  if (x.size() == 0) return k;
  const Eigen::VectorXd r = Q * x - c;
  k.primal = std::max(0.0, -x.minCoeff());
  k.dual = std::max(0.0, -r.minCoeff());
  k.complementarity = x.cwiseProduct(r).cwiseAbs().maxCoeff();
  return k;
}

// ------------------------------------------------------------------------------------------
// Workspace: the Cholesky factor of Q_FF for the factored passive set F (in factor order),
// gradient and scratch vectors, sized once for n and reused.
struct NonnegativeQPSolver::Workspace {
  Eigen::MatrixXd L;           // leading p x p block: lower Cholesky factor of Q_FF
  Eigen::VectorXd g;           // gradient Q x - c
  Eigen::VectorXd w1, w2, w3;  // scratch (size n)
  std::vector<int> fset;       // F in factor order (first p entries valid)
  std::vector<int> pos;        // pos[i]: position of i in fset, or -1
  std::vector<int> excluded;   // indices barred from entering until the objective decreases
  std::vector<char> is_excluded;
  std::vector<int> order;  // scratch for refactor()
  int p = 0;
  int n = 0;

  void reset(int size) {
    if (L.rows() < size) {
      L.resize(size, size);
      g.resize(size);
      w1.resize(size);
      w2.resize(size);
      w3.resize(size);
      fset.resize(static_cast<std::size_t>(size));
      pos.resize(static_cast<std::size_t>(size));
      is_excluded.resize(static_cast<std::size_t>(size));
      excluded.reserve(static_cast<std::size_t>(size));
      order.reserve(static_cast<std::size_t>(size));
    }
    n = size;
    p = 0;
    std::fill(pos.begin(), pos.begin() + size, -1);
    std::fill(is_excluded.begin(), is_excluded.begin() + size, 0);
    excluded.clear();
  }
};

namespace {

using Workspace = NonnegativeQPSolver::Workspace;

enum class Append { Added, Dependent, NotPsd };

// v <- L^-1 v and v <- L^-T v for the leading p x p block of the column-major L: column
// (axpy) and dot forms on contiguous columns, cheap for the small p of the online QP.
template <class Vec>
void forward_solve(const Eigen::MatrixXd& L, int p, Vec&& v) {
  for (int k = 0; k < p; ++k) {
    v[k] /= L(k, k);
    const int rest = p - k - 1;
    if (rest > 0) v.segment(k + 1, rest) -= v[k] * L.col(k).segment(k + 1, rest);
  }
}
template <class Vec>
void backward_solve_transposed(const Eigen::MatrixXd& L, int p, Vec&& v) {
  for (int k = p - 1; k >= 0; --k) {
    const int rest = p - k - 1;
    if (rest > 0) v[k] -= L.col(k).segment(k + 1, rest).dot(v.segment(k + 1, rest));
    v[k] /= L(k, k);
  }
}
enum class Outcome { Done, MaxIterations, Unbounded, Numerics };

// One call of the active-set method on a validated problem.
class ActiveSet {
 public:
  ActiveSet(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const QPSettings& settings,
            int max_iterations, double q_norm, Workspace& ws, QPResult& res)
      : Q_(Q),
        c_(c),
        s_(settings),
        max_it_(max_iterations),
        q_norm_(q_norm),
        ws_(ws),
        res_(res),
        c_norm_(c.size() > 0 ? c.cwiseAbs().maxCoeff() : 0.0) {}

  void run(const std::vector<int>& warm);

 private:
  int idx(int k) const { return ws_.fset[static_cast<std::size_t>(k)]; }

  Append append(int j);
  void remove_at(int r);
  void solve_face(bool refine);  // z = Q_FF^-1 c_F into ws_.w2.head(p)
  bool factor_warm(const std::vector<int>& warm);
  bool refactor();
  Outcome descend(int pending, bool refine = false);
  void gradient();
  void gradient_outside();
  double scale() const;
  bool kkt_ok(double s) const;
  void finish(QPStatus status, const std::string& message);

  const Eigen::MatrixXd& Q_;
  const Eigen::VectorXd& c_;
  const QPSettings& s_;
  const int max_it_;
  const double q_norm_;
  Workspace& ws_;
  QPResult& res_;
  const double c_norm_;
};

// Extends the factor of Q_FF by variable j (bordering): l = L^-1 Q_Fj, delta = Q_jj - l'l.
// On Dependent, ws_.w1.head(p) holds l.
Append ActiveSet::append(int j) {
  const int p = ws_.p;
  auto l = ws_.w1.head(p);
  for (int k = 0; k < p; ++k) l[k] = Q_(idx(k), j);
  forward_solve(ws_.L, p, l);
  const double qjj = Q_(j, j);
  const double delta = qjj - l.squaredNorm();
  if (delta < -kNotPsdPivot * qjj) return Append::NotPsd;
  if (!(delta > s_.rank_tolerance * qjj)) return Append::Dependent;
  ws_.L.row(p).head(p) = l.transpose();
  ws_.L(p, p) = std::sqrt(delta);
  ws_.fset[static_cast<std::size_t>(p)] = j;
  ws_.pos[static_cast<std::size_t>(j)] = p;
  ++ws_.p;
  return Append::Added;
}

// Deletes position r from F: drop row r of L, then Givens rotations on column pairs restore
// the triangular shape (L L' = Q_FF is preserved).
void ActiveSet::remove_at(int r) {
  const int p = ws_.p;
  Eigen::MatrixXd& L = ws_.L;
  ws_.pos[static_cast<std::size_t>(idx(r))] = -1;
  for (int k = r; k + 1 < p; ++k) {
    L.row(k).head(p) = L.row(k + 1).head(p);
    const int i = idx(k + 1);
    ws_.fset[static_cast<std::size_t>(k)] = i;
    ws_.pos[static_cast<std::size_t>(i)] = k;
  }
  for (int k = r; k + 1 < p; ++k) {
    const double a = L(k, k), b = L(k, k + 1);
    const double h = std::hypot(a, b);
    if (h == 0.0) continue;
    const double cs = a / h, sn = b / h;
    for (int row = k; row + 1 < p; ++row) {
      const double u = L(row, k), v = L(row, k + 1);
      L(row, k) = cs * u + sn * v;
      L(row, k + 1) = -sn * u + cs * v;
    }
  }
  --ws_.p;
}

void ActiveSet::solve_face(bool refine) {
  const int p = ws_.p;
  auto z = ws_.w2.head(p);
  auto r = ws_.w3.head(p);
  for (int k = 0; k < p; ++k) z[k] = c_[idx(k)];
  forward_solve(ws_.L, p, z);
  backward_solve_transposed(ws_.L, p, z);
  if (!refine) return;
  // One step of iterative refinement: r = c_F - Q_FF z.
  for (int k = 0; k < p; ++k) r[k] = c_[idx(k)];
  for (int col = 0; col < p; ++col) {
    const double zc = z[col];
    const int jc = idx(col);
    for (int k = 0; k < p; ++k) r[k] -= Q_(idx(k), jc) * zc;
  }
  forward_solve(ws_.L, p, r);
  backward_solve_transposed(ws_.L, p, r);
  z += r;
}

bool ActiveSet::refactor() {
  const int p = ws_.p;
  std::vector<int>& order = ws_.order;
  order.assign(ws_.fset.begin(), ws_.fset.begin() + p);
  for (int k = 0; k < p; ++k) ws_.pos[static_cast<std::size_t>(idx(k))] = -1;
  ws_.p = 0;
  for (int k = 0; k < p; ++k)
    if (append(order[static_cast<std::size_t>(k)]) != Append::Added) return false;
  return true;
}

// Factors Q_FF for the warm set at once (blocked Cholesky, in place in L); false, with F
// left empty, when the set is small or some pivot fails the rank test (then the caller
// appends one by one, skipping dependent variables).
bool ActiveSet::factor_warm(const std::vector<int>& warm) {
  int p = 0;
  for (int j : warm) {
    if (ws_.pos[static_cast<std::size_t>(j)] >= 0) continue;
    ws_.pos[static_cast<std::size_t>(j)] = p;
    ws_.fset[static_cast<std::size_t>(p++)] = j;
  }
  auto undo = [&] {
    for (int k = 0; k < p; ++k) ws_.pos[static_cast<std::size_t>(idx(k))] = -1;
    ws_.p = 0;
    return false;
  };
  if (p < kBulkFactorMin) return undo();
  auto block = ws_.L.topLeftCorner(p, p);
  for (int b = 0; b < p; ++b)
    for (int a = b; a < p; ++a) block(a, b) = Q_(idx(a), idx(b));
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(block);
  if (llt.info() != Eigen::Success) return undo();
  for (int k = 0; k < p; ++k) {
    const double pivot = block(k, k) * block(k, k);
    if (!(pivot > s_.rank_tolerance * Q_(idx(k), idx(k)))) return undo();
  }
  ws_.p = p;
  return true;
}

// Descends from the feasible x until x minimizes f on the face of F (Done), with the
// variable `pending` (or -1) entering F first. Every step is one iteration.
Outcome ActiveSet::descend(int pending, bool refine) {
  Eigen::VectorXd& x = res_.x;
  for (;;) {
    if (pending >= 0) {
      const Append a = append(pending);
      if (a == Append::NotPsd) return Outcome::Numerics;
      if (a == Append::Added) {
        pending = -1;
      } else {
        // Q_(F+j)(F+j) is singular with null vector d = (-Q_FF^-1 Q_Fj, 1): f is linear and
        // decreasing along d (slope g_j < 0, g_F = 0). Move until an F variable hits zero.
        if (res_.iterations >= max_it_) return Outcome::MaxIterations;
        ++res_.iterations;
        const int p = ws_.p;
        auto d = ws_.w1.head(p);  // holds l = L^-1 Q_Fj
        backward_solve_transposed(ws_.L, p, d);
        d = -d;
        const double dmax = std::max(1.0, p > 0 ? d.cwiseAbs().maxCoeff() : 0.0);
        double alpha = std::numeric_limits<double>::infinity();
        int block = -1;
        for (int k = 0; k < p; ++k) {
          if (d[k] < -kDirectionNoise * dmax) {
            const double ratio = x[idx(k)] / -d[k];
            if (ratio < alpha) alpha = ratio, block = k;
          } else if (d[k] < 0.0) {
            d[k] = 0.0;
          }
        }
        if (block < 0) {
          res_.ray.setZero(Q_.rows());
          for (int k = 0; k < p; ++k) res_.ray[idx(k)] = d[k];
          res_.ray[pending] = 1.0;
          res_.ray /= res_.ray.cwiseAbs().maxCoeff();
          return Outcome::Unbounded;
        }
        x[pending] += alpha;
        for (int k = p - 1; k >= 0; --k) {
          if (d[k] >= 0.0) continue;
          const int i = idx(k);
          const double xn = x[i] + alpha * d[k];
          if (k == block || xn <= kTieFraction * x[i]) {
            x[i] = 0.0;
            remove_at(k);
          } else {
            x[i] = xn;
          }
        }
        continue;
      }
    }
    if (res_.iterations >= max_it_) return Outcome::MaxIterations;
    ++res_.iterations;
    const int p = ws_.p;
    if (p == 0) return Outcome::Done;
    solve_face(refine);
    auto z = ws_.w2.head(p);
    if (!z.allFinite()) return Outcome::Numerics;
    double alpha = 1.0;
    int block = -1;
    for (int k = 0; k < p; ++k) {
      if (z[k] > 0.0) continue;
      const double xi = x[idx(k)];
      const double ratio = xi > 0.0 ? xi / (xi - z[k]) : 0.0;
      if (block < 0 || ratio < alpha) alpha = ratio, block = k;
    }
    if (block < 0) {
      for (int k = 0; k < p; ++k) x[idx(k)] = z[k];
      return Outcome::Done;
    }
    // Step back to feasibility: x <- x + alpha (z - x); drop the blocking variables.
    for (int k = p - 1; k >= 0; --k) {
      const int i = idx(k);
      const double xi = x[i];
      const double xn = xi + alpha * (z[k] - xi);
      if (z[k] <= 0.0 && (k == block || xn <= kTieFraction * xi)) {
        x[i] = 0.0;
        remove_at(k);
      } else {
        x[i] = std::max(xn, 0.0);
      }
    }
  }
}

// g = Q x - c using the nonzeros of x only.
void ActiveSet::gradient() {
  const Eigen::VectorXd& x = res_.x;
  auto g = ws_.g.head(ws_.n);
  g.noalias() = -c_;
  for (int i = 0; i < ws_.n; ++i)
    if (x[i] != 0.0) g.noalias() += x[i] * Q_.col(i);
}

// g_i = (Q x - c)_i for the variables outside F (x vanishes there), in min(n |F|, n (n - |F|))
// operations: by columns of F, or by dot products (Q symmetric) when F is the larger part.
void ActiveSet::gradient_outside() {
  const Eigen::VectorXd& x = res_.x;
  const int n = ws_.n, p = ws_.p;
  if (2 * p <= n) return gradient();
  for (int i = 0; i < n; ++i)
    if (ws_.pos[static_cast<std::size_t>(i)] < 0) ws_.g[i] = Q_.col(i).dot(x) - c_[i];
}

double ActiveSet::scale() const {
  const double xmax = res_.x.size() > 0 ? res_.x.cwiseAbs().maxCoeff() : 0.0;
  return std::max(c_norm_, q_norm_ * xmax);
}

bool ActiveSet::kkt_ok(double s) const {
  const double xmax = res_.x.size() > 0 ? res_.x.cwiseAbs().maxCoeff() : 0.0;
  const KKTResiduals& k = res_.kkt;
  return k.primal <= s_.tolerance * xmax && k.dual <= s_.tolerance * s &&
         k.complementarity <= s_.tolerance * s * xmax;
}

void ActiveSet::finish(QPStatus status, const std::string& message) {
  gradient();
  const Eigen::VectorXd& x = res_.x;
  const auto g = ws_.g.head(ws_.n);
  KKTResiduals& k = res_.kkt;
  k = KKTResiduals{};
  res_.passive.clear();
  for (int i = 0; i < ws_.n; ++i) {
    k.primal = std::max(k.primal, -x[i]);
    k.dual = std::max(k.dual, -g[i]);
    k.complementarity = std::max(k.complementarity, std::abs(x[i] * g[i]));
    if (x[i] > 0.0) res_.passive.push_back(i);
  }
  res_.kkt_scale = scale();
  const bool ok = kkt_ok(res_.kkt_scale);
  if (status == QPStatus::Unbounded) {
    res_.status = status;
    res_.message = message;
  } else if (ok && (status == QPStatus::Solved || status == QPStatus::MaxIterations)) {
    // A certified KKT point is a solution, however the loop ended.
    res_.status = QPStatus::Solved;
    res_.message.clear();
  } else {
    res_.status = status == QPStatus::Solved ? QPStatus::Numerics : status;
    std::ostringstream m;
    m << message << (message.empty() ? "" : "; ") << "KKT residuals at exit: primal " << k.primal << ", dual "
      << k.dual << ", complementarity " << k.complementarity << " (scale s = " << res_.kkt_scale
      << ", tolerance " << s_.tolerance << ")";
    res_.message = m.str();
  }
}

void ActiveSet::run(const std::vector<int>& warm) {
  Eigen::VectorXd& x = res_.x;
  const int n = ws_.n;
  auto stop = [&](Outcome o) {
    switch (o) {
      case Outcome::MaxIterations:
        finish(QPStatus::MaxIterations,
               "iteration cap max_iterations = " + std::to_string(max_it_) + " reached");
        break;
      case Outcome::Unbounded:
        finish(QPStatus::Unbounded,
               "objective unbounded below along the ray x + t d, d >= 0, Q d = 0, c'd > 0 (see ray)");
        break;
      case Outcome::Numerics:
        finish(QPStatus::Numerics,
               "numerical breakdown: Q is not positive semidefinite or the factor lost accuracy");
        break;
      case Outcome::Done:
        break;
    }
  };

  // Warm start: from the feasible x = 0, factor the warm set (skipping dependent variables)
  // and descend; variables whose face minimizer is <= 0 leave at the zero-length step.
  if (!warm.empty()) {
    if (!factor_warm(warm)) {
      for (int j : warm) {
        if (ws_.pos[static_cast<std::size_t>(j)] >= 0) continue;
        if (append(j) == Append::NotPsd) return stop(Outcome::Numerics);
      }
    }
    const Outcome o = descend(-1);
    if (o != Outcome::Done) return stop(o);
  }

  double f_prev = 0.0;
  int entered = -1;
  bool refactored = false;
  for (;;) {
    gradient_outside();
    const auto g = ws_.g.head(n);
    const double s = scale();
    const double threshold = std::min(s_.tolerance, kGradientNoise * (ws_.p + 1) * kEps) * s;
    // Objective at a face minimizer (g_F = 0), f = -1/2 c_F'x_F; its rounding bound.
    double f = 0.0, xl1 = 0.0;
    for (int k = 0; k < ws_.p; ++k) {
      const int i = idx(k);
      f -= 0.5 * x[i] * c_[i];
      xl1 += std::abs(x[i]);
    }
    if (entered >= 0) {
      const double roundoff = kProgressRoundoff * kEps * s * xl1;
      if (f < f_prev - roundoff) {
        for (int i : ws_.excluded) ws_.is_excluded[static_cast<std::size_t>(i)] = 0;
        ws_.excluded.clear();
      } else if (ws_.pos[static_cast<std::size_t>(entered)] < 0) {
        // Anti-cycling: no decrease (rounding made the entering step void); bar the index.
        ws_.is_excluded[static_cast<std::size_t>(entered)] = 1;
        ws_.excluded.push_back(entered);
      }
    }
    // Entering variable: most negative gradient outside F (smallest index on ties).
    int j = -1;
    double gmin = -threshold;
    for (int i = 0; i < n; ++i) {
      if (ws_.pos[static_cast<std::size_t>(i)] >= 0 || ws_.is_excluded[static_cast<std::size_t>(i)]) continue;
      if (g[i] < gmin) gmin = g[i], j = i;
    }
    if (j < 0) {
      finish(QPStatus::Solved,
             ws_.excluded.empty() ? "" : "entering variables barred by the anti-cycling rule");
      if (res_.status == QPStatus::Solved || refactored) return;
      // The updated factor may have drifted: rebuild it once and re-solve the face problem.
      refactored = true;
      if (!refactor()) return;
      const Outcome o = descend(-1, true);
      if (o != Outcome::Done) return stop(o);
      entered = -1;
      continue;
    }
    f_prev = f;
    entered = j;
    const Outcome o = descend(j);
    if (o != Outcome::Done) return stop(o);
  }
}

int default_max_iterations(int n) { return 10 * (n + 10); }

void validate(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const QPSettings& settings,
              const std::vector<int>& warm, double& q_norm) {
  constexpr const char* who = "solve_nonnegative_qp: ";
  if (!(Q.rows() == Q.cols())) throw Error(std::string(who) + "Q must be square, got " + dims(Q));
  if (!(c.size() == Q.rows()))
    throw Error(std::string(who) + "c has size " + std::to_string(c.size()) + " but Q is " + dims(Q));
  if (!(settings.max_iterations >= -1))
    throw Error(std::string(who) + "settings.max_iterations must be >= -1, got " +
                std::to_string(settings.max_iterations));
  if (!(std::isfinite(settings.tolerance) && settings.tolerance > 0.0))
    throw Error(std::string(who) + "settings.tolerance must be positive and finite, got " +
                number_text(settings.tolerance));
  if (!(settings.rank_tolerance >= 0.0 && settings.rank_tolerance < 1.0))
    throw Error(std::string(who) + "settings.rank_tolerance must lie in [0, 1), got " +
                number_text(settings.rank_tolerance));
  if (!(settings.symmetry_tolerance >= 0.0))
    throw Error(std::string(who) + "settings.symmetry_tolerance must be >= 0, got " +
                number_text(settings.symmetry_tolerance));
  const Eigen::Index n = Q.rows();
  // Vectorized passes first; the offending index is searched only on failure (this runs on
  // every online QP: its cost matters next to the small active-set solve).
  // x * 0 is 0 for finite x and NaN otherwise: one vectorized sum (allFinite() is an
  // element-by-element loop with an early exit).
  const auto has_non_finite = [](const auto& a) { return !std::isfinite((a.array() * 0.0).sum()); };
  if (has_non_finite(c)) {
    for (Eigen::Index i = 0; i < n; ++i)
      if (!(std::isfinite(c[i])))
        throw Error(std::string(who) + "c(" + std::to_string(i) + ") is not finite (size " + std::to_string(n) +
                    ")");
  }
  if (has_non_finite(Q)) {
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i < n; ++i)
        if (!std::isfinite(Q(i, j)))
          throw Error(std::string(who) + "Q(" + std::to_string(i) + ", " + std::to_string(j) +
                      ") is not finite (Q is " + dims(Q) + ")");
  }
  if (n > 0 && Q.diagonal().minCoeff() < 0.0) {
    for (Eigen::Index j = 0; j < n; ++j)
      if (Q(j, j) < 0.0)
        throw Error(std::string(who) + "Q(" + std::to_string(j) + ", " + std::to_string(j) +
                    ") < 0: Q is not positive semidefinite (Q is " + dims(Q) + ")");
  }
  q_norm = n > 0 ? Q.cwiseAbs().colwise().sum().maxCoeff() : 0.0;  // = max row sum (Q symmetric)
  const double max_abs = n > 0 ? Q.cwiseAbs().maxCoeff() : 0.0;
  // max |Q_ij - Q_ji| over tiles, so that the transposed reads stay in cache.
  constexpr Eigen::Index kTile = 32;
  double asym = 0.0;
  for (Eigen::Index j0 = 0; j0 < n; j0 += kTile) {
    const Eigen::Index j1 = std::min(n, j0 + kTile);
    for (Eigen::Index i0 = 0; i0 <= j0; i0 += kTile) {
      const Eigen::Index i1 = std::min(n, i0 + kTile);
      for (Eigen::Index j = j0; j < j1; ++j) {
        // A column-local maximum: with the running maximum alone, g++ -O3 kept it in memory
        // (a store-to-load chain per entry, 60 % of this function in perf).
        double col = 0.0;
        const double* qj = &Q(0, j);
        for (Eigen::Index i = i0; i < std::min(i1, j); ++i) {
          const double a = std::abs(qj[i] - Q(j, i));
          col = a > col ? a : col;
        }
        asym = col > asym ? col : asym;
      }
    }
  }
  if (asym > settings.symmetry_tolerance * max_abs) {
    // The first (in tile order) entry with the largest asymmetry, as reported before.
    Eigen::Index ai = 0, aj = 0;
    double worst = 0.0;
    for (Eigen::Index j0 = 0; j0 < n; j0 += kTile) {
      const Eigen::Index j1 = std::min(n, j0 + kTile);
      for (Eigen::Index i0 = 0; i0 <= j0; i0 += kTile) {
        const Eigen::Index i1 = std::min(n, i0 + kTile);
        for (Eigen::Index j = j0; j < j1; ++j)
          for (Eigen::Index i = i0; i < std::min(i1, j); ++i) {
            const double a = std::abs(Q(i, j) - Q(j, i));
            if (a > worst) worst = a, ai = i, aj = j;
          }
      }
    }
    std::ostringstream m;
    m << who << "Q (" << dims(Q) << ") is not symmetric: |Q(" << ai << ", " << aj << ") - Q(" << aj << ", "
      << ai << ")| = " << asym
      << " > symmetry_tolerance * max|Q| = " << settings.symmetry_tolerance * max_abs;
    throw Error(m.str());
  }
  for (std::size_t k = 0; k < warm.size(); ++k)
    if (!(warm[k] >= 0 && warm[k] < n))
      throw Error(std::string(who) + "warm_passive[" + std::to_string(k) + "] = " + std::to_string(warm[k]) +
                  " is outside [0, " + std::to_string(n) + ")");
}

void solve_into(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const QPSettings& settings,
                const std::vector<int>& warm, Workspace& ws, QPResult& res) {
  double q_norm = 0.0;
  validate(Q, c, settings, warm, q_norm);
  const int n = static_cast<int>(Q.rows());
  res.x.setZero(n);
  res.iterations = 0;
  res.kkt = KKTResiduals{};
  res.passive.clear();
  res.message.clear();
  res.kkt_scale = 0.0;
  res.ray.resize(0);
  res.status = QPStatus::Solved;
  ws.reset(n);
  if (n == 0) return;
  const int max_it = settings.max_iterations < 0 ? default_max_iterations(n) : settings.max_iterations;
  ActiveSet(Q, c, settings, max_it, q_norm, ws, res).run(warm);
}

}  // namespace

NonnegativeQPSolver::NonnegativeQPSolver(const QPSettings& settings)
    : settings_(settings), workspace_(std::make_unique<Workspace>()) {}
NonnegativeQPSolver::~NonnegativeQPSolver() = default;
NonnegativeQPSolver::NonnegativeQPSolver(NonnegativeQPSolver&&) noexcept = default;
NonnegativeQPSolver& NonnegativeQPSolver::operator=(NonnegativeQPSolver&&) noexcept = default;

const QPResult& NonnegativeQPSolver::solve(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c,
                                           const std::vector<int>& warm_passive) {
  solve_into(Q, c, settings_, warm_passive, *workspace_, result_);
  return result_;
}

QPResult solve_nonnegative_qp(const Eigen::MatrixXd& Q, const Eigen::VectorXd& c, const QPSettings& settings,
                              const std::vector<int>& warm_passive) {
  Workspace ws;
  QPResult res;
  solve_into(Q, c, settings, warm_passive, ws, res);
  return res;
}

QPResult solve_nnls(const Eigen::MatrixXd& Xi, const Eigen::VectorXd& x, const Eigen::VectorXd& m,
                    const QPSettings& settings) {
  constexpr const char* who = "solve_nnls: ";
  if (!(Xi.rows() == x.size()))
    throw Error(std::string(who) + "Xi is " + dims(Xi) + " but x has size " + std::to_string(x.size()));
  if (!(m.size() == 0 || m.size() == x.size()))
    throw Error(std::string(who) + "m has size " + std::to_string(m.size()) + " but x has size " +
                std::to_string(x.size()) + " (m must be empty or match)");
  if (!(Xi.allFinite())) throw Error(std::string(who) + "Xi (" + dims(Xi) + ") has non-finite entries");
  if (!(x.allFinite()))
    throw Error(std::string(who) + "x (size " + std::to_string(x.size()) + ") has non-finite entries");
  if (!(m.allFinite() && (m.size() == 0 || m.minCoeff() >= 0.0)))
    throw Error(std::string(who) + "the weights m (size " + std::to_string(m.size()) +
                ") must be finite and >= 0");
  // Q = W'W with W = diag(sqrt(m)) Xi, built by a symmetric rank update so Q is exactly symmetric.
  Eigen::MatrixXd W = Xi;
  Eigen::VectorXd b = x;
  if (m.size() > 0) {
    const Eigen::VectorXd sq = m.cwiseSqrt();
    W = sq.asDiagonal() * Xi;
    b = sq.cwiseProduct(x);
  }
  const Eigen::Index k = Xi.cols();
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(k, k);
  Q.selfadjointView<Eigen::Lower>().rankUpdate(W.transpose());
  for (Eigen::Index j = 1; j < k; ++j)
    for (Eigen::Index i = 0; i < j; ++i) Q(i, j) = Q(j, i);
  const Eigen::VectorXd c = W.transpose() * b;
  return solve_nonnegative_qp(Q, c, settings);
}

}  // namespace contactrb::solve
