#include "contactrb/offline/geometric_term.hpp"

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/solve/blas_threads.hpp"
#include "contactrb/solve/constrained_eigenvalue.hpp"
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

bool same_materials(const std::vector<fem::Material>& a, const std::vector<fem::Material>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](const fem::Material& x, const fem::Material& y) { return x.E == y.E && x.nu == y.nu; });
}

// A_00(mu_p) assembled and factored once and kept while the next snapshot's stiffness is the
// same: it depends on mu only through the mesh of Omega(mu), the materials and the prescribed
// DOFs, so a parameter that enters none of them (an imposed displacement) reuses the factor and
// the columns of the inverse it has cached.
class InverseBlocks {
 public:
  Eigen::MatrixXd block(const hf::ContactProblem& problem, const fem::DofMap& dofs, const std::vector<int>& idx) {
    if (!same_stiffness(problem, dofs)) {
      require(inverse_.compute(dofs.restrict_matrix(fem::stiffness(problem.mesh, problem.materials))) ==
                  solve::SelectedInverseStatus::Success,
              "geometric_ratio: A_00(mu) is not positive definite");
      nodes_ = problem.mesh.nodes;
      cells_ = problem.mesh.cells();
      body_ = problem.mesh.body;
      materials_ = problem.materials;
      free_ = dofs.free_dofs();
      factored_ = true;
    }
    return inverse_.block(idx);
  }

 private:
  bool same_stiffness(const hf::ContactProblem& problem, const fem::DofMap& dofs) const {
    return factored_ && problem.mesh.nodes == nodes_ && problem.mesh.cells() == cells_ && problem.mesh.body == body_ &&
           same_materials(problem.materials, materials_) && dofs.free_dofs() == free_;
  }
  solve::SelectedInverse inverse_;
  bool factored_ = false;
  std::vector<mesh::Mesh::Point> nodes_;
  std::vector<mesh::Mesh::Cell> cells_;
  std::vector<int> body_;
  std::vector<fem::Material> materials_;
  std::vector<int> free_;
};

// The pencil of eta_p on the touched DOFs cd (free numbering, slot[] its position there):
// M = -H (symmetrized) and the active rows D_A.
struct TouchedPencil {
  Eigen::SparseMatrix<double> M;
  Eigen::SparseMatrix<double, Eigen::RowMajor> DA;
};

TouchedPencil touched_pencil(const contact::ContactLinearization& lin, const Eigen::VectorXd& lambda,
                             const std::vector<int>& to_free, const std::vector<Index>& slot, Index m) {
  const auto local = [&](Index dof) { return to_free[sz(dof)] >= 0 ? slot[sz(to_free[sz(dof)])] : Index{-1}; };
  std::vector<Eigen::Triplet<double>> entries;
  for (Index k = 0; k < lin.H.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lin.H, k); it; ++it) {
      const Index a = local(it.row()), b = local(it.col());
      if (a < 0 || b < 0) continue;
      entries.emplace_back(a, b, -0.5 * it.value());
      entries.emplace_back(b, a, -0.5 * it.value());
    }
  }
  TouchedPencil p;
  p.M.resize(m, m);
  p.M.setFromTriplets(entries.begin(), entries.end());
  entries.clear();
  Index rows = 0;
  for (Index r = 0; r < lambda.size(); ++r) {
    if (!(lambda(r) > 0.0)) continue;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(lin.D, r); it; ++it) {
      if (local(it.col()) >= 0) entries.emplace_back(rows, local(it.col()), it.value());
    }
    ++rows;
  }
  p.DA.resize(rows, m);
  p.DA.setFromTriplets(entries.begin(), entries.end());
  return p;
}

// (A_00(mu_p)^-1)[idx, idx] on free indices idx.
using InverseBlock = std::function<Eigen::MatrixXd(const std::vector<int>& idx)>;

// eta_p on the snapshot's discretization at mu_p (its mesh, pair, quadrature and DOF map).
double ratio_on(const mesh::Mesh& mesh, const contact::ContactPair& pair, const contact::ContactQuadrature& quadrature,
                const fem::DofMap& dofs, const io::Snapshot& snapshot, const InverseBlock& inverse) {
  require(snapshot.u.size() == dofs.num_dofs() && snapshot.lambda.size() == quadrature.weight.size(),
          "geometric_ratio: the snapshot does not match the case's discretization");
  std::vector<int> to_free(sz(dofs.num_dofs()), -1);
  std::vector<char> movable(sz(dofs.num_dofs()), 0);
  for (std::size_t i = 0; i < dofs.free_dofs().size(); ++i) {
    to_free[sz(dofs.free_dofs()[i])] = static_cast<int>(i);
    movable[sz(dofs.free_dofs()[i])] = 1;
  }
  const contact::ContactLinearization lin =
      contact::linearize_contact(mesh, pair, quadrature, snapshot.u, snapshot.lambda, movable);
  const std::vector<Index> cd = touched_dofs(lin, snapshot.lambda, to_free);
  if (cd.empty()) return 0.0;
  const Index m = static_cast<Index>(cd.size());
  std::vector<Index> slot(dofs.free_dofs().size(), -1);
  for (Index i = 0; i < m; ++i) slot[sz(cd[sz(i)])] = i;
  const TouchedPencil pencil = touched_pencil(lin, snapshot.lambda, to_free, slot, m);
  // C = (A_00^-1) on cd, the inverse of the Schur complement there (the minimum energy of an
  // extension), so that eta_p = max { v'Mv / v'C^-1 v : D_A v = 0 } over cd alone.
  const Eigen::MatrixXd C = inverse(std::vector<int>(cd.begin(), cd.end()));
  const solve::ConstrainedEigenvalueResult eig = solve::largest_constrained_eigenvalue(C, pencil.M, pencil.DA);
  require(eig.converged, "geometric_ratio: the Lanczos iteration did not converge (" +
                             std::to_string(eig.iterations) + " steps, residual " + std::to_string(eig.residual) + ")");
  return std::max(0.0, eig.value);
}

double geometric_ratio(const cases::CaseSpec& spec, const mesh::Mesh& reference, contact::Discretization d,
                       const io::Snapshot& snapshot, InverseBlocks& inverse) {
  // One BLAS thread: the supernodal factor and block are then the same bitwise whatever the
  // machine's threads (a model built on each MPI rank is the serial one).
  const solve::ScopedBlasThreads blas(1);
  const hf::ContactProblem problem = cases::make_problem(spec, reference, snapshot.mu, d);
  const fem::DofMap dofs(problem.mesh, problem.dirichlet);
  const contact::ContactPair pair = contact::make_contact_pair(problem.mesh);
  const contact::ContactQuadrature quadrature = contact::make_quadrature(problem.mesh, pair, d);
  return ratio_on(problem.mesh, pair, quadrature, dofs, snapshot,
                  [&](const std::vector<int>& idx) { return inverse.block(problem, dofs, idx); });
}

}  // namespace

double geometric_ratio(const cases::CaseSpec& spec, const mesh::Mesh& reference, contact::Discretization d,
                       const io::Snapshot& snapshot) {
  InverseBlocks inverse;
  return geometric_ratio(spec, reference, d, snapshot, inverse);
}

double geometric_ratio(const hf::HFSolver& solver, const io::Snapshot& snapshot) {
  const solve::ScopedBlasThreads blas(1);  // as above
  const hf::ContactProblem& problem = solver.problem();
  std::optional<InverseBlocks> own;  // A_00 factored here when the solver holds no factor
  return ratio_on(problem.mesh, solver.pair(), solver.quadrature(), solver.dofs(), snapshot,
                  [&](const std::vector<int>& idx) {
                    if (std::optional<Eigen::MatrixXd> held = solver.held_inverse_block(idx)) return std::move(*held);
                    return own.emplace().block(problem, solver.dofs(), idx);
                  });
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
