#include "contactrb/hf/contact_condensation.hpp"

#include "contactrb/common/error.hpp"

namespace contactrb::hf {

ContactCondensation::ContactCondensation(const Eigen::SparseMatrix<double>& A00, const std::vector<int>& contact) {
  const int n = static_cast<int>(A00.rows());
  const int nc = static_cast<int>(contact.size());
  llt_.compute(A00);
  require(llt_.info() == Eigen::Success,
          "the stiffness matrix with Dirichlet conditions is not positive definite: is every body held "
          "by Dirichlet conditions?");
  const Eigen::SparseMatrix<double>& L = llt_.matrixL().nestedExpression();  // lower, column-major
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();
  // Elimination tree: the parent of column k is the first row below the diagonal.
  std::vector<int> parent(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < n; ++k) {
    for (int p = outer[k]; p < outer[k + 1]; ++p) {
      if (inner[p] > k) {
        parent[static_cast<std::size_t>(k)] = inner[p];
        break;
      }
    }
  }
  // Y = L^-1 P E_c column by column, along elimination-tree paths.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd work = Eigen::VectorXd::Zero(n);
  std::vector<int> path;
  for (int j = 0; j < nc; ++j) {
    const int c = contact[static_cast<std::size_t>(j)];
    require(c >= 0 && c < n, "ContactCondensation: contact index out of range");
    const int start = llt_.permutationP().indices()(c);
    path.clear();
    for (int k = start; k >= 0; k = parent[static_cast<std::size_t>(k)]) path.push_back(k);
    work(start) = 1.0;
    for (int k : path) {  // increasing row order: updates only reach ancestors
      const int d = outer[k];  // the diagonal is the first entry of column k
      work(k) /= value[d];
      const double xk = work(k);
      for (int p = d + 1; p < outer[k + 1]; ++p) work(inner[p]) -= value[p] * xk;
    }
    for (int k : path) {
      entries.emplace_back(k, j, work(k));
      work(k) = 0.0;
    }
  }
  Eigen::SparseMatrix<double> Y(n, nc);
  Y.setFromTriplets(entries.begin(), entries.end());
  S_ = Eigen::MatrixXd(Y.transpose() * Y);
}

Eigen::VectorXd ContactCondensation::solve(const Eigen::VectorXd& b) const { return llt_.solve(b); }

}  // namespace contactrb::hf
