#include "contactrb/solve/saddle_point_krylov.hpp"

#include <Eigen/SparseLU>
#include <cmath>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/solve/gmres.hpp"

namespace contactrb::solve {

const char* to_string(SaddlePointKrylovStatus status) {
  switch (status) {
    case SaddlePointKrylovStatus::Converged: return "converged";
    case SaddlePointKrylovStatus::MaxIterations: return "max-iterations";
    case SaddlePointKrylovStatus::SchurSingular: return "schur-singular";
    case SaddlePointKrylovStatus::InvalidInput: return "invalid-input";
  }
  return "unknown";
}

SaddlePointKrylovStatus saddle_point_krylov_status_from_string(const std::string& name) {
  return enum_from_string(name, "saddle-point Krylov status",
                          std::array{SaddlePointKrylovStatus::Converged, SaddlePointKrylovStatus::MaxIterations,
                                     SaddlePointKrylovStatus::SchurSingular, SaddlePointKrylovStatus::InvalidInput});
}

namespace {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Per row of M: scale / (its largest entry), 1 for an empty row.
Eigen::VectorXd row_equilibration(const RowSparse& M, double scale) {
  Eigen::VectorXd s = Eigen::VectorXd::Ones(M.rows());
  for (Eigen::Index r = 0; r < M.outerSize(); ++r) {
    double largest = 0.0;
    for (RowSparse::InnerIterator it(M, r); it; ++it) largest = std::max(largest, std::abs(it.value()));
    if (largest > 0.0) s(r) = scale / largest;
  }
  return s;
}

bool sizes_match(const Eigen::SparseMatrix<double>& F, const RowSparse& B, const RowSparse& C,
                 const AmgPreconditioner& amg, const Eigen::VectorXd& rhs, const Eigen::VectorXd& x0) {
  const Eigen::Index n = F.rows(), m = B.rows();
  return F.cols() == n && B.cols() == n && C.rows() == m && C.cols() == n && rhs.size() == n + m &&
         x0.size() == n + m && amg.status() == AmgStatus::Success;
}

}  // namespace

SaddlePointKrylovResult solve_saddle_point(const Eigen::SparseMatrix<double>& F, const RowSparse& B,
                                           const RowSparse& C, const AmgPreconditioner& amg,
                                           const Eigen::VectorXd& rhs, const Eigen::VectorXd& x0,
                                           const SaddlePointKrylovSettings& settings, const Eigen::VectorXd* x_ref) {
  SaddlePointKrylovResult res;
  if (!sizes_match(F, B, C, amg, rhs, x0) || (x_ref != nullptr && x_ref->size() != x0.size())) return res;
  const Eigen::Index n = F.rows(), m = B.rows();
  const Eigen::VectorXd diag = F.diagonal();
  const double mean_diag = diag.cwiseAbs().mean();
  // Unknowns y = col_scale ys, constraint rows times row_scale: both blocks in F's units.
  const Eigen::VectorXd col_scale = row_equilibration(B, mean_diag);
  const Eigen::VectorXd row_scale = row_equilibration(C, mean_diag);
  const RowSparse Bs = col_scale.asDiagonal() * B;
  const RowSparse Cs = row_scale.asDiagonal() * C;
  const Eigen::SparseMatrix<double> Bst = Bs.transpose();
  // S^ = C_s diag(F)^-1 B_s' (sparse LU: C = -D_A makes it nonsymmetric).
  Eigen::SparseLU<Eigen::SparseMatrix<double>> schur;
  if (m > 0) {
    const Eigen::SparseMatrix<double> S = Cs * diag.cwiseInverse().asDiagonal() * Bst;
    schur.compute(S);
    if (schur.info() != Eigen::Success) {
      res.status = SaddlePointKrylovStatus::SchurSingular;
      return res;
    }
  }
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    Eigen::VectorXd out(n + m);
    out.head(n) = F * v.head(n) + Bst * v.tail(m);
    out.tail(m) = Cs * v.head(n);
    return out;
  };
  // P [a; b] = [f; g]: b = -S^-1 g, a = F^-1 (f - B' b).
  auto precondition = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    Eigen::VectorXd out(n + m);
    if (m > 0) out.tail(m) = -schur.solve(v.tail(m));
    out.head(n) = amg.apply(v.head(n) - Bst * out.tail(m));
    return out;
  };
  auto scaled = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd xs = x;
    xs.tail(m) = x.tail(m).cwiseQuotient(col_scale);
    return xs;
  };
  const Eigen::VectorXd x0s = scaled(x0);
  Eigen::VectorXd rhs_s = rhs;
  rhs_s.tail(m) = rhs.tail(m).cwiseProduct(row_scale);
  const Eigen::VectorXd r0 = rhs_s - apply(x0s);
  const double r0_norm = r0.norm();
  const double ref_norm = x_ref != nullptr ? (rhs_s - apply(scaled(*x_ref))).norm() : r0_norm;
  // The tolerance relative to |r0| that is `tolerance` relative to the residual at x_ref.
  const double tolerance = r0_norm > 0.0 ? std::min(0.5, settings.tolerance * ref_norm / r0_norm) : settings.tolerance;
  const GmresResult kr = gmres(apply, precondition, r0, tolerance, settings.max_iterations, settings.restart);
  res.iterations = kr.iterations;
  res.relative_residual = ref_norm > 0.0 ? kr.relative_residual * r0_norm / ref_norm : kr.relative_residual;
  res.x = x0s + kr.x;
  res.x.tail(m) = res.x.tail(m).cwiseProduct(col_scale);
  res.status = kr.converged ? SaddlePointKrylovStatus::Converged : SaddlePointKrylovStatus::MaxIterations;
  return res;
}

}  // namespace contactrb::solve
