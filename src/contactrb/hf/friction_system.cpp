#include "contactrb/hf/friction_system.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contactrb/solve/dense_lu.hpp"

namespace contactrb::hf {

namespace {

inline std::size_t sz(Eigen::Index i) { return static_cast<std::size_t>(i); }

FrictionSystemResult solve_saddle_lu(const FrictionJacobian& J, solve::SparseLUBackend backend) {
  const auto n = J.A00->rows();
  const auto m = J.rhs.size();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(sz(J.A00->nonZeros()) + J.H.size() + 2 * sz(J.B.nonZeros()) + J.rows.size());
  for (int j = 0; j < J.A00->outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator a(*J.A00, j); a; ++a) trip.emplace_back(a.row(), a.col(), a.value());
  }
  trip.insert(trip.end(), J.H.begin(), J.H.end());
  for (int i = 0; i < J.B.outerSize(); ++i) {
    for (RowSparse::InnerIterator b(J.B, i); b; ++b) trip.emplace_back(b.col(), n + i, b.value());
  }
  trip.insert(trip.end(), J.rows.begin(), J.rows.end());
  Eigen::SparseMatrix<double> M(n + m, n + m);
  M.setFromTriplets(trip.begin(), trip.end());
  Eigen::VectorXd rhs(n + m);
  rhs << J.top, J.rhs;
  FrictionSystemResult out;
  solve::SparseLU lu(backend);
  if (lu.compute(M) != solve::SparseLUStatus::Success) {
    out.singular = lu.status() == solve::SparseLUStatus::Singular;
    out.message = "the Newton system (" + std::to_string(n) + " free DOFs, " + std::to_string(m) + " multipliers) is " +
                  solve::to_string(lu.status());
    return out;
  }
  const Eigen::VectorXd x = lu.solve(rhs);
  out.du = x.head(n);
  out.mu = x.tail(m);
  out.solved = x.allFinite();
  if (!out.solved) out.message = "the Newton system has no finite solution";
  return out;
}

// Positions: E (free DOFs) and the kept multipliers, -1 elsewhere.
struct Reduction {
  std::vector<int> E, kept;
  std::vector<int> e_pos, k_pos;
};

Reduction reduction(const FrictionJacobian& J) {
  const auto n = J.A00->rows();
  Reduction r;
  r.e_pos.assign(sz(n), -1);
  r.k_pos.assign(sz(J.rhs.size()), -1);
  for (Eigen::Index i = 0; i < J.rhs.size(); ++i) {
    if (J.zero[sz(i)]) continue;
    r.k_pos[sz(i)] = static_cast<int>(r.kept.size());
    r.kept.push_back(static_cast<int>(i));
  }
  auto add = [&](Eigen::Index fi) {
    if (r.e_pos[sz(fi)] < 0) {
      r.e_pos[sz(fi)] = 0;
      r.E.push_back(static_cast<int>(fi));
    }
  };
  for (int i : r.kept) {
    for (RowSparse::InnerIterator b(J.B, i); b; ++b) add(b.col());
  }
  for (const auto& t : J.rows) {
    if (t.col() < n && !J.zero[sz(t.row() - n)]) add(t.col());
  }
  for (const auto& t : J.H) {
    add(t.row());
    add(t.col());
  }
  std::sort(r.E.begin(), r.E.end());
  for (std::size_t a = 0; a < r.E.size(); ++a) r.e_pos[sz(r.E[a])] = static_cast<int>(a);
  return r;
}

FrictionSystemResult solve_schur(const FrictionJacobian& J, solve::SelectedInverse& inverse, const Eigen::VectorXd& z,
                                 const Eigen::VectorXd& u0, double min_rcond) {
  const auto n = J.A00->rows();
  const Reduction red = reduction(J);
  const int e = static_cast<int>(red.E.size()), m = static_cast<int>(red.kept.size());
  const Eigen::MatrixXd G = inverse.block(red.E);
  Eigen::SparseMatrix<double> HE(e, e), BE(m, e);
  {
    std::vector<Eigen::Triplet<double>> h, b;
    for (const auto& t : J.H) h.emplace_back(red.e_pos[sz(t.row())], red.e_pos[sz(t.col())], t.value());
    for (int k = 0; k < m; ++k) {
      for (RowSparse::InnerIterator bb(J.B, red.kept[sz(k)]); bb; ++bb) b.emplace_back(k, red.e_pos[sz(bb.col())], bb.value());
    }
    HE.setFromTriplets(h.begin(), h.end());
    BE.setFromTriplets(b.begin(), b.end());
  }
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(e + m, e + m);
  M.topLeftCorner(e, e) = G * HE;
  M.topLeftCorner(e, e).diagonal().array() += 1.0;
  M.topRightCorner(e, m) = G * BE.transpose();  // BE sparse: O(e nnz(BE)), not O(e^2 m) as a dense product
  Eigen::VectorXd rhs(e + m);
  for (int a = 0; a < e; ++a) rhs(a) = z(red.E[sz(a)]) - u0(red.E[sz(a)]);
  for (const auto& t : J.rows) {
    const int k = red.k_pos[sz(t.row() - n)];
    if (k < 0) continue;
    const int col = t.col() < n ? red.e_pos[sz(t.col())] : e + red.k_pos[sz(t.col() - n)];
    if (col >= 0) M(e + k, col) += t.value();
  }
  for (int k = 0; k < m; ++k) rhs(e + k) = J.rhs(red.kept[sz(k)]);
  // Equilibration (displacements, gaps and tractions in one system), so that min_rcond judges the
  // problem and not its units (as the frictionless Newton's dense LU).
  Eigen::VectorXd rs = Eigen::VectorXd::Ones(e + m), cs = Eigen::VectorXd::Ones(e + m);
  for (int k = 0; k < m; ++k) {
    const double rmax = M.row(e + k).cwiseAbs().maxCoeff(), cmax = M.col(e + k).cwiseAbs().maxCoeff();
    if (rmax > 0.0) rs(e + k) = 1.0 / rmax;
    if (cmax > 0.0) cs(e + k) = 1.0 / cmax;
  }
  solve::DenseLU dense;
  const bool finite = dense.compute(rs.asDiagonal() * M * cs.asDiagonal());
  FrictionSystemResult out;
  if (!finite || !(dense.rcond() >= min_rcond) || dense.rcond() == 0.0) {
    std::ostringstream os;
    os << "the reduced Newton system (" << e << " contact DOFs, " << m << " multipliers) is singular (reciprocal "
       << "condition " << dense.rcond() << ")";
    out.singular = true;
    out.message = os.str();
    return out;
  }
  const Eigen::VectorXd x = cs.cwiseProduct(dense.solve(rs.cwiseProduct(rhs)));
  const Eigen::VectorXd yE = HE * x.head(e) + BE.transpose() * x.tail(m);
  out.du = z - inverse.solve_sparse(red.E, yE) - u0;
  out.mu = Eigen::VectorXd::Zero(J.rhs.size());
  for (int k = 0; k < m; ++k) out.mu(red.kept[sz(k)]) = x(e + k);
  out.solved = out.du.allFinite() && out.mu.allFinite();
  if (!out.solved) out.message = "the Newton system has no finite solution";
  return out;
}

}  // namespace

FrictionSystemResult solve_friction_system(const FrictionJacobian& J, solve::SelectedInverse* inverse,
                                           const Eigen::VectorXd& z, const Eigen::VectorXd& u0,
                                           solve::SparseLUBackend lu, double min_rcond) {
  if (inverse == nullptr) return solve_saddle_lu(J, lu);
  FrictionSystemResult schur = solve_schur(J, *inverse, z, u0, min_rcond);
  if (schur.solved) return schur;
  // A numerically singular A_00 that CHOLMOD factorized (a rigid mode that only the contact
  // holds: a pivot at round-off) makes G meaningless: the whole system decides.
  return solve_saddle_lu(J, lu);
}

}  // namespace contactrb::hf
