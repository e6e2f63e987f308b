#pragma once
// A sparse SPD matrix factorized once (CHOLMOD, supernodal), with three uses by the semi-smooth
// Newton solver (hf/semismooth_newton.hpp, docs/solvers.md "Newton linear algebra"):
//  - solve(b) = A^-1 b;
//  - solve_sparse(in, b_in, out): A^-1 b for a b supported on a few indices, on a few indices
//    (or all): only the elimination-tree chains of `in` (forward) and of `out` (backward) are
//    visited;
//  - block(idx) = (A^-1)[idx, idx], a small dense block of the inverse on a few indices (the
//    contact DOFs of the active rows), without ever forming A^-1 on more columns than asked;
//    row_block(rows, V) = (V A^-1 V')[rows, rows] the same on a few sparse rows of V.
// With P A P' = L L', (A^-1)_ij = x_i . x_j where x_i = L^-1 P e_i. The pattern of x_i is the
// path from P(i) to the root of the elimination tree (Gilbert's theorem), short under a
// fill-reducing ordering (about the separator sizes, O(sqrt N) for 2D meshes). The x_i of a
// request are computed together, supernode by supernode along the union of their paths (dense
// dtrsm / dgemm per supernode), and cached: Newton iterations ask for nearly the same indices
// again, and only the indices not seen before cost anything.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

namespace contactrb::solve {

// Fill-reducing ordering of the factorization. Cholmod: CHOLMOD's default (AMD; when AMD fills
// badly, flops / nnz(L) >= 500 and nnz(L) / nnz(A) >= 5, METIS on the whole graph as well, and the
// better of the two). NodeMetis: METIS nested dissection of the supervariable graph (runs of
// consecutive indices with the same column pattern: the 2 DOFs of a node), one vertex per run.
// Auto: auto_ordering(rows), NodeMetis from kNodeMetisFrom rows on, Cholmod below. Measured on
// hertz-a (docs/performance.md, "Why the defaults are what they are", "Fill-reducing ordering"): level 7 (1.2e6 rows) CHOLMOD's default
// runs AMD and METIS (analysis 13.8 s wall, loaded machine) for the nnz(L) that NodeMetis gets in
// 4.5 s; on levels 4-6 (2.7e4-3.1e5 rows) AMD alone, and NodeMetis's dearer analysis costs what
// its smaller factor saves (CPU of the whole solve within the machine's noise).
enum class FactorOrdering { Auto, Cholmod, NodeMetis };
const char* to_string(FactorOrdering ordering);
FactorOrdering factor_ordering_from_string(const std::string& name);  // throws contactrb::Error
inline constexpr int kNodeMetisFrom = 500000;
FactorOrdering auto_ordering(int rows);

enum class SelectedInverseStatus { Success, NotPositiveDefinite, InvalidInput };
const char* to_string(SelectedInverseStatus status);
SelectedInverseStatus selected_inverse_status_from_string(const std::string& name);  // throws contactrb::Error

// The ordering and symbolic analysis of SelectedInverse::compute, from the sparsity pattern alone
// (the values are never read): it can run on another thread while the values are assembled
// (hf::HFSolver, docs/solvers.md "Semi-smooth Newton"), and compute(A, analysis) then starts at
// the numeric factorization. CHOLMOD's analysis reads the pattern only, so a matrix with this
// pattern gets the same permutation and supernodes, hence the same factor, bitwise, as
// compute(A, ordering) (tests/solve/test_selected_inverse.cpp).
class FactorAnalysis {
 public:
  FactorAnalysis();
  ~FactorAnalysis();
  FactorAnalysis(FactorAnalysis&&) noexcept;
  FactorAnalysis& operator=(FactorAnalysis&&) noexcept;

  // pattern: square, compressed, both triangles stored (as compute() takes A); its values are
  // ignored. valid() is false when the analysis failed (empty, not square, out of memory).
  static FactorAnalysis analyze(const Eigen::SparseMatrix<double>& pattern, FactorOrdering ordering = FactorOrdering::Auto);
  // The same from a compressed-column pattern alone (outer: n + 1 entries, inner: rows ascending
  // in each column), kept for matches().
  static FactorAnalysis analyze(int n, std::vector<int> outer, std::vector<int> inner,
                                FactorOrdering ordering = FactorOrdering::Auto);
  bool valid() const;
  FactorOrdering requested() const;  // the ordering asked for (Auto resolved by the size)
  bool matches(const Eigen::SparseMatrix<double>& A) const;  // A compressed with exactly this pattern
  double seconds() const;  // wall seconds of analyze()
  // CHOLMOD's count from the symbolic analysis (cholmod_common lnz, fl), before any numeric work:
  // the nonzeros of L and the flops of its numeric factorization, from the column counts: also
  // when the supernodal analysis then failed for size (not valid(): a factor beyond CHOLMOD's int
  // indices); 0 when no analysis ran. Why: where a direct factorization stops fitting is known
  // before it is attempted (docs/performance.md, "HF scaling in 3D").
  double factor_nonzeros() const;
  double factor_flops() const;

 private:
  friend class SelectedInverse;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class SelectedInverse {
 public:
  SelectedInverse();
  ~SelectedInverse();
  SelectedInverse(SelectedInverse&&) noexcept;
  SelectedInverse& operator=(SelectedInverse&&) noexcept;

  // Ordering (`ordering`, above) and supernodal numeric
  // factorization (BLAS 3), kept supernodal for every substitution. A: symmetric
  // with both triangles stored (only the lower one is read). InvalidInput: not square, empty,
  // a non-finite entry or a CHOLMOD failure (out of memory). Drops the cached columns.
  SelectedInverseStatus compute(const Eigen::SparseMatrix<double>& A, FactorOrdering ordering = FactorOrdering::Auto);
  // The same with the ordering and symbolic analysis taken from `analysis` (copied: it can serve
  // several computes, also at once) when it is valid and matches(A); otherwise as
  // compute(A, analysis.requested()). analyze_seconds() is then 0 (the copy's time).
  SelectedInverseStatus compute(const Eigen::SparseMatrix<double>& A, const FactorAnalysis& analysis);
  bool used_analysis() const;  // whether the last compute() took a given analysis
  SelectedInverseStatus status() const;
  int rows() const;
  long factor_nonzeros() const;  // nnz(L)
  FactorOrdering ordering() const;  // the one used (NodeMetis falls back to Cholmod if METIS fails)
  // Wall seconds of the last compute(): ordering + symbolic analysis, numeric factorization.
  double analyze_seconds() const;
  double factorize_seconds() const;

  // Throw contactrb::Error unless status() == Success and the sizes / indices are valid.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // x = A^-1 b for b supported on the indices `in` (values b_in): the forward substitution runs
  // along the elimination-tree chains of `in` only. out == nullptr: the whole x (a full backward
  // substitution); else only x[out] (the backward one along the chains of `out`), zero elsewhere.
  Eigen::VectorXd solve_sparse(const std::vector<int>& in, const Eigen::VectorXd& b_in,
                               const std::vector<int>* out = nullptr) const;
  Eigen::MatrixXd block(const std::vector<int>& idx);
  // The same block in `storage` (resized to |idx|^2, its capacity kept and grown by a quarter
  // beyond what is asked): a caller asking at every iteration reuses the memory instead of
  // allocating (and page-faulting) a new |idx|^2 matrix. Valid until `storage` changes.
  Eigen::Map<const Eigen::MatrixXd> block(const std::vector<int>& idx, std::vector<double>& storage);
  // (V A^-1 V')[rows, rows] for rows of V (over A's indices): x_r = L^-1 P V' e_r is one sparse
  // forward substitution along the union of the chains of row r's entries, so a block on |rows|
  // constraint rows costs |rows| columns instead of the block() of every index they touch
  // (docs/performance.md, "Why the defaults are what they are", "Newton: the first frozen systems
  // on the constraint rows"). Cached by row like block(), until forget_rows() (V changed). Valid until
  // `storage` changes.
  Eigen::Map<const Eigen::MatrixXd> row_block(const std::vector<int>& rows,
                                              const Eigen::SparseMatrix<double, Eigen::RowMajor>& V,
                                              std::vector<double>& storage);
  void forget_rows();
  int cached_columns() const;  // of block()
  // Threads of solve_sparse's full backward substitution (out == nullptr): 2 runs the two
  // subtrees below the first fork of the elimination tree at once (bitwise the serial result;
  // the BLAS must be single-threaded then, solve/blas_threads.hpp). Default 1.
  void set_substitution_threads(int threads);
  bool has_substitution_fork() const;  // whether the tree has the fork that 2 threads split at

 private:
  SelectedInverseStatus compute_impl(const Eigen::SparseMatrix<double>& A, FactorOrdering ordering, const FactorAnalysis* analysis);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactrb::solve
