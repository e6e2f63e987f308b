#include "contactrb/offline/geometric_term.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <string>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/solve/blas_threads.hpp"
#include "contactrb/solve/selected_inverse.hpp"

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

// A_00(mu_p) factored once and kept while the next snapshot's matrix is the same (a parameter
// that does not enter the stiffness, as an imposed displacement): its block of the inverse on
// the touched DOFs is then read from the same factor and the columns it has cached.
class InverseBlocks {
 public:
  Eigen::MatrixXd block(const Eigen::SparseMatrix<double>& A, const std::vector<int>& idx) {
    // One BLAS thread: the supernodal factor and block are then the same bitwise whatever the
    // machine's threads (a model built on each MPI rank is the serial one).
    const solve::ScopedBlasThreads blas(1);
    if (!same_as_factored(A)) {
      require(inverse_.compute(A) == solve::SelectedInverseStatus::Success,
              "geometric_ratio: A_00(mu) is not positive definite");
      factored_ = A;
    }
    return inverse_.block(idx);
  }

 private:
  bool same_as_factored(const Eigen::SparseMatrix<double>& A) const {
    if (factored_.rows() != A.rows() || factored_.nonZeros() != A.nonZeros() || !A.isCompressed()) return false;
    const auto n = static_cast<std::size_t>(A.nonZeros());
    return std::equal(A.valuePtr(), A.valuePtr() + n, factored_.valuePtr()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + n, factored_.innerIndexPtr()) &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, factored_.outerIndexPtr());
  }
  solve::SelectedInverse inverse_;
  Eigen::SparseMatrix<double> factored_;
};

double geometric_ratio(const cases::CaseSpec& spec, const mesh::Mesh& reference, contact::Discretization d,
                       const io::Snapshot& snapshot, InverseBlocks& inverse) {
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
  const std::vector<int> idx(cd.begin(), cd.end());
  const Eigen::MatrixXd S = inverse.block(dofs.restrict_matrix(solver.stiffness()), idx).inverse();

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
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Z.transpose() * H * Z, Z.transpose() * S * Z,
                                                                      Eigen::EigenvaluesOnly);
  require(eig.info() == Eigen::Success, "geometric_ratio: the eigenvalue problem did not converge");
  return std::max(0.0, eig.eigenvalues().maxCoeff());
}

}  // namespace

double geometric_ratio(const cases::CaseSpec& spec, const mesh::Mesh& reference, contact::Discretization d,
                       const io::Snapshot& snapshot) {
  InverseBlocks inverse;
  return geometric_ratio(spec, reference, d, snapshot, inverse);
}

double max_geometric_ratio(const io::SnapshotSet& set, const cases::CaseSpec& spec, const mesh::Mesh& reference,
                           contact::Discretization d, GeometricRatios* known) {
  InverseBlocks inverse;
  double eta = 0.0;
  for (const io::Snapshot& s : set.snapshots) {
    if (!s.converged) continue;
    const auto seen = known ? std::find_if(known->begin(), known->end(), [&](const auto& k) { return k.first == s.mu; })
                            : GeometricRatios::iterator{};
    if (known && seen != known->end()) {
      eta = std::max(eta, seen->second);
      continue;
    }
    const double eta_p = geometric_ratio(spec, reference, d, s, inverse);
    if (known) known->emplace_back(s.mu, eta_p);
    eta = std::max(eta, eta_p);
  }
  return eta;
}

}  // namespace contactrb::offline
