#include "contactrb/offline/geometric_term.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/fem/cholesky.hpp"
#include "contactrb/hf/hf_solver.hpp"

namespace contactrb::offline {

namespace {

using Index = Eigen::Index;
inline std::size_t sz(Index i) { return static_cast<std::size_t>(i); }

// The free DOFs (free numbering) that H or the active rows of D touch, in increasing order.
std::vector<Index> touched_dofs(const contact::ContactLinearization& lin, const Eigen::VectorXd& lambda,
                                const std::vector<int>& to_free) {
  std::vector<char> mark(to_free.size(), 0);
  for (Index k = 0; k < lin.H.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lin.H, k); it; ++it) mark[sz(it.row())] = mark[sz(it.col())] = 1;
  }
  for (Index r = 0; r < lambda.size(); ++r) {
    if (!(lambda(r) > 0.0)) continue;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(lin.D, r); it; ++it) mark[sz(it.col())] = 1;
  }
  std::vector<Index> out;
  for (std::size_t i = 0; i < mark.size(); ++i) {
    if (mark[i] && to_free[i] >= 0) out.push_back(to_free[i]);
  }
  return out;
}

}  // namespace

double geometric_ratio(const cases::CaseSpec& spec, const mesh::Mesh& reference, contact::Discretization d,
                       const io::Snapshot& snapshot) {
  const hf::HFSolver solver(cases::make_problem(spec, reference, snapshot.mu, d));
  const fem::DofMap& dofs = solver.dofs();
  require(snapshot.u.size() == dofs.num_dofs() && snapshot.lambda.size() == solver.quadrature().weight.size(),
          "geometric_ratio: the snapshot does not match the case's discretization");
  std::vector<int> to_free(sz(dofs.num_dofs()), -1);
  std::vector<char> movable(sz(dofs.num_dofs()), 0);
  for (std::size_t i = 0; i < dofs.free_dofs().size(); ++i) {
    to_free[sz(dofs.free_dofs()[i])] = static_cast<int>(i);
    movable[sz(dofs.free_dofs()[i])] = 1;
  }
  const contact::ContactLinearization lin = contact::linearize_contact(
      solver.problem().mesh, solver.pair(), solver.quadrature(), snapshot.u, snapshot.lambda, movable);
  const std::vector<Index> cd = touched_dofs(lin, snapshot.lambda, to_free);
  if (cd.empty()) return 0.0;
  const Index m = static_cast<Index>(cd.size());
  std::vector<Index> slot(dofs.free_dofs().size(), -1);
  for (Index i = 0; i < m; ++i) slot[sz(cd[sz(i)])] = i;

  // C = (A_00^-1) on cd; its inverse is the Schur complement (the minimum energy of an extension).
  fem::SparseCholesky chol;
  require(chol.compute(dofs.restrict_matrix(solver.stiffness())) == fem::FactorStatus::Success,
          "geometric_ratio: A_00(mu) is not positive definite");
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(dofs.num_free(), m);
  for (Index i = 0; i < m; ++i) E(cd[sz(i)], i) = 1.0;
  const Eigen::MatrixXd X = chol.solve(E);
  Eigen::MatrixXd C(m, m);
  for (Index i = 0; i < m; ++i) C.row(i) = X.row(cd[sz(i)]);
  const Eigen::MatrixXd S = C.inverse();

  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, m);
  for (Index k = 0; k < lin.H.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lin.H, k); it; ++it) {
      const Index a = to_free[sz(it.row())] >= 0 ? slot[sz(to_free[sz(it.row())])] : -1;
      const Index b = to_free[sz(it.col())] >= 0 ? slot[sz(to_free[sz(it.col())])] : -1;
      if (a >= 0 && b >= 0) H(a, b) -= it.value();  // -H
    }
  }
  H = 0.5 * (H + H.transpose()).eval();
  std::vector<Index> active;
  for (Index r = 0; r < snapshot.lambda.size(); ++r) {
    if (snapshot.lambda(r) > 0.0) active.push_back(r);
  }
  Eigen::MatrixXd DA = Eigen::MatrixXd::Zero(static_cast<Index>(active.size()), m);
  for (std::size_t a = 0; a < active.size(); ++a) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(lin.D, active[a]); it; ++it) {
      if (to_free[sz(it.col())] >= 0) DA(static_cast<Index>(a), slot[sz(to_free[sz(it.col())])]) = it.value();
    }
  }
  const Eigen::MatrixXd Z = active.empty() ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(m, m))
                                           : Eigen::MatrixXd(Eigen::FullPivLU<Eigen::MatrixXd>(DA).kernel());
  if (Z.cols() == 0 || Z.norm() == 0.0) return 0.0;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Z.transpose() * H * Z,
                                                                      Z.transpose() * S * Z);
  require(eig.info() == Eigen::Success, "geometric_ratio: the eigenvalue problem did not converge");
  return std::max(0.0, eig.eigenvalues().maxCoeff());
}

double max_geometric_ratio(const io::SnapshotSet& set, const cases::CaseSpec& spec, const mesh::Mesh& reference,
                           contact::Discretization d) {
  double eta = 0.0;
  for (const io::Snapshot& s : set.snapshots) {
    if (s.converged) eta = std::max(eta, geometric_ratio(spec, reference, d, s));
  }
  return eta;
}

}  // namespace contactrb::offline
