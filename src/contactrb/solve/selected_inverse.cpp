#include "contactrb/solve/selected_inverse.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cstdio>
#include <chrono>
#include <mutex>
#include <cmath>
#include <string>
#include <exception>
#include <thread>
#include <unordered_map>
#include <vector>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"

// BLAS (Debian: the libblas.so.3 alternative, OpenBLAS), Fortran calling convention.
extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
}

namespace contactrb::solve {

const char* to_string(SelectedInverseStatus status) {
  switch (status) {
    case SelectedInverseStatus::Success: return "success";
    case SelectedInverseStatus::NotPositiveDefinite: return "not positive definite";
    case SelectedInverseStatus::InvalidInput: return "invalid input";
  }
  return "unknown";
}

SelectedInverseStatus selected_inverse_status_from_string(const std::string& name) {
  using enum SelectedInverseStatus;
  return enum_from_string(name, "selected inverse status", std::array{Success, NotPositiveDefinite, InvalidInput});
}

namespace {
// One cached column x = L^-1 P e_i: its pattern (ascending, the elimination-tree path) and values.
struct SparseColumn {
  std::vector<int> rows;
  std::vector<double> values;
};
// A right-hand side b of forward_batch(): its entries on the permuted rows `rows`.
struct SparseRhs {
  std::vector<int> rows;
  std::vector<double> values;
};
struct ColumnCursors;

// Cached columns x_k = L^-1 P b_k and their Gram matrix G(i, j) = x_i . x_j, by key: the
// original index i of b = e_i (block()), or a row of V (row_block()).
struct GramCache {
  std::unordered_map<int, int> column_of;   // key -> position in `columns` / G
  std::vector<SparseColumn> columns;
  // G column-major with leading dimension g_capacity (>= columns.size()): new columns are
  // written in place, and the storage grows by a quarter beyond what is asked, so that a Newton
  // iteration adding a few columns neither copies G nor touches fresh memory (at 1.2e6 DOFs G
  // is ~3 500^2 doubles, ~100 MB: a new one per call is freed to the OS and page-faulted again
  // by the next; docs/performance.md, "Why the defaults are what they are", "Newton: storage
  // reused across systems").
  std::vector<double> G;
  int g_capacity = 0;
  double& g(int i, int j) { return G[static_cast<std::size_t>(i) + static_cast<std::size_t>(j) * static_cast<std::size_t>(g_capacity)]; }
  void clear() {
    column_of.clear();
    columns.clear();
    G = std::vector<double>();
    g_capacity = 0;
  }
  // G[:, new] for the columns old.. (defined with SelectedInverse::block()); row_pos: n, -1
  // between uses.
  void gram_new_columns(int old, std::vector<int>& row_pos);
  std::vector<int> new_rows(int old, int total, std::vector<int>& row_pos);
  void grow_gram(int old, int total);
  void gram_chunk(int begin, int end, int old, ColumnCursors& cursors, std::vector<int>& present, Eigen::MatrixXd& Xc,
                  Eigen::MatrixXd& Gc);
  // G[keys, keys] into `storage` (its capacity kept and grown by a quarter beyond what is asked).
  Eigen::Map<const Eigen::MatrixXd> gather(const std::vector<int>& keys, std::vector<double>& storage);
};
}  // namespace

struct SelectedInverse::Impl {
  cholmod_common common{};
  cholmod_factor* L = nullptr;
  SelectedInverseStatus status = SelectedInverseStatus::InvalidInput;
  int n = 0;
  double analyze_s = 0.0, factorize_s = 0.0;
  FactorOrdering ordering_used = FactorOrdering::Cholmod;
  bool used_analysis = false;
  std::vector<int> inverse_perm;            // original index -> position in P A P'
  std::vector<int> row_pos;                 // n, -1 between uses (block(): row -> dense row)
  GramCache units;                          // block(): x_i = L^-1 P e_i by original index i
  GramCache rows;                           // row_block(): x_r = L^-1 P V' e_r by row r of V
  // The block of `cache` on `keys`, its missing columns from rhs(key) first.
  template <class MakeRhs>
  Eigen::Map<const Eigen::MatrixXd> cached_block(GramCache& cache, const std::vector<int>& keys, MakeRhs rhs,
                                                 std::vector<double>& storage);

  Impl() { cholmod_start(&common); }
  ~Impl() {
    release();
    cholmod_finish(&common);
  }
  void release() {
    if (L != nullptr) cholmod_free_factor(&L, &common);
    units.clear();
    rows.clear();
  }

  // Supernodal structure (CHOLMOD, relaxed supernodes): supernode of each column and the parent
  // of each supernode in the supernodal elimination tree (the supernode of the first row below
  // its diagonal block; -1 at a root). A parent's index is larger than its children's.
  std::vector<int> supernode_of;
  std::vector<int> supernode_parent;
  std::vector<std::vector<int>> path_columns;  // per supernode, scratch of forward_batch()
  std::vector<int> block_of;                   // per supernode, -1 between uses
  std::vector<char> chain_mark;                // per supernode, 0 between uses
  std::vector<double> work;                    // n, zero between uses (solve_sparse)
  // The full backward substitution on two threads: the supernodes from split_top up are the
  // chain above the first fork of the (postordered) supernodal tree, done first; below it the
  // subtrees of its children form the two index ranges [0, split_cut) and [split_cut, split_top),
  // independent of each other (a supernode reads its ancestors only). split_top < 0: no fork.
  int split_top = -1, split_cut = -1;
  int substitution_threads = 1;

  // Finds split_top, split_cut (the two ranges of about equal nnz(L)); leaves -1 unless the tree
  // is one postordered tree (a supernode's subtree is the index range ending at it).
  void find_split() {
    split_top = split_cut = -1;
    const int nsuper = static_cast<int>(L->nsuper);
    const int* super = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    std::vector<int> subtree(static_cast<std::size_t>(nsuper), 1);
    std::vector<double> cost(static_cast<std::size_t>(nsuper), 0.0);
    for (int s = 0; s < nsuper; ++s) {
      cost[static_cast<std::size_t>(s)] += static_cast<double>(super[s + 1] - super[s]) * static_cast<double>(pi[s + 1] - pi[s]);
      const int parent = supernode_parent[static_cast<std::size_t>(s)];
      if (parent < 0) {
        if (s != nsuper - 1) return;  // a forest
        continue;
      }
      if (parent <= s) return;
      subtree[static_cast<std::size_t>(parent)] += subtree[static_cast<std::size_t>(s)];
      cost[static_cast<std::size_t>(parent)] += cost[static_cast<std::size_t>(s)];
    }
    int top = nsuper - 1;
    while (true) {
      if (subtree[static_cast<std::size_t>(top)] != top + 1) return;  // not postordered
      std::vector<int> children;  // descending
      for (int c = top - 1; c >= 0; c -= subtree[static_cast<std::size_t>(c)]) {
        if (supernode_parent[static_cast<std::size_t>(c)] != top) return;
        children.push_back(c);
      }
      if (children.empty()) return;
      if (children.size() == 1) {
        top = children[0];
        continue;
      }
      // Children ascending tile [0, top); cut at the boundary nearest half of their cost.
      const double total = cost[static_cast<std::size_t>(top)] - static_cast<double>(super[top + 1] - super[top]) * static_cast<double>(pi[top + 1] - pi[top]);
      double prefix = 0.0, best = total;
      for (auto it = children.rbegin(); it + 1 != children.rend(); ++it) {
        prefix += cost[static_cast<std::size_t>(*it)];
        if (std::abs(total - 2.0 * prefix) < best) {
          best = std::abs(total - 2.0 * prefix);
          split_cut = *it + 1;
        }
      }
      split_top = top;
      return;
    }
  }

  // The supernodes on the chains from the supernodes of the (permuted) rows q to the root,
  // ascending (children before parents).
  std::vector<int> chains(const std::vector<int>& q) {
    std::vector<int> out;
    for (int r : q) {
      for (int s = supernode_of[static_cast<std::size_t>(r)]; s >= 0 && !chain_mark[static_cast<std::size_t>(s)];
           s = supernode_parent[static_cast<std::size_t>(s)]) {
        chain_mark[static_cast<std::size_t>(s)] = 1;
        out.push_back(s);
      }
    }
    for (int s : out) chain_mark[static_cast<std::size_t>(s)] = 0;
    std::sort(out.begin(), out.end());
    return out;
  }

  // x_j = L^-1 b_j for a batch of sparse b_j (permuted rows). The pattern of x_j is the union of
  // the paths from the rows of b_j to the root of the elimination tree (Gilbert's theorem), in
  // supernodal terms the chains of supernodes from the ones holding them to the root. One sweep
  // over the union of these chains, children before parents: in supernode s, B_s (its columns x the batch columns J_s whose
  // chain passes through s) gets B_s = L_ss^-1 B_s (dtrsm), then L_below,s B_s (dgemm) is
  // subtracted from the ancestors' blocks. Dense BLAS per supernode instead of one scalar sparse
  // substitution per column (simplicial L), which takes 4 of the 15 CPU seconds of a hertz-a
  // level 6 solve.
  std::vector<SparseColumn> forward_batch(const std::vector<SparseRhs>& b) {
    const int* super = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    const int* px = static_cast<const int*>(L->px);
    const int* Ls = static_cast<const int*>(L->s);
    const double* Lx = static_cast<const double*>(L->x);
    const int nb = static_cast<int>(b.size());
    std::vector<int> touched;
    std::vector<std::vector<int>> chain(static_cast<std::size_t>(nb));  // per column, its supernodes ascending
    for (int j = 0; j < nb; ++j) {
      for (int r : b[static_cast<std::size_t>(j)].rows) {
        for (int s = supernode_of[static_cast<std::size_t>(r)]; s >= 0; s = supernode_parent[static_cast<std::size_t>(s)]) {
          auto& cols = path_columns[static_cast<std::size_t>(s)];
          if (!cols.empty() && cols.back() == j) break;  // the rest of this chain is column j's already
          if (cols.empty()) touched.push_back(s);
          cols.push_back(j);  // ascending in j: batch columns are visited in order
          chain[static_cast<std::size_t>(j)].push_back(s);
        }
      }
      std::sort(chain[static_cast<std::size_t>(j)].begin(), chain[static_cast<std::size_t>(j)].end());
    }
    std::sort(touched.begin(), touched.end());
    std::vector<Eigen::MatrixXd> blocks(touched.size());
    for (std::size_t a = 0; a < touched.size(); ++a) {
      const int s = touched[a];
      block_of[static_cast<std::size_t>(s)] = static_cast<int>(a);
      blocks[a].setZero(super[s + 1] - super[s], static_cast<Eigen::Index>(path_columns[static_cast<std::size_t>(s)].size()));
    }
    auto position = [this](int s, int j) {  // of batch column j in the block of supernode s
      const auto& js = path_columns[static_cast<std::size_t>(s)];
      return std::lower_bound(js.begin(), js.end(), j) - js.begin();
    };
    for (int j = 0; j < nb; ++j) {
      const SparseRhs& bj = b[static_cast<std::size_t>(j)];
      for (std::size_t e = 0; e < bj.rows.size(); ++e) {
        const int r = bj.rows[e];
        const int s0 = supernode_of[static_cast<std::size_t>(r)];
        blocks[static_cast<std::size_t>(block_of[static_cast<std::size_t>(s0)])](r - super[s0], position(s0, j)) += bj.values[e];
      }
    }
    Eigen::MatrixXd W;
    std::vector<int> column_map;
    for (std::size_t a = 0; a < touched.size(); ++a) {
      const int s = touched[a];
      Eigen::MatrixXd& B = blocks[a];
      const int nscol = super[s + 1] - super[s];
      const int nsrow = pi[s + 1] - pi[s];
      const int ncols = static_cast<int>(B.cols());
      const double* Ls_x = Lx + px[s];
      const char left = 'L', lower = 'L', notrans = 'N', nonunit = 'N';
      const double one = 1.0, zero = 0.0;
      dtrsm_(&left, &lower, &notrans, &nonunit, &nscol, &ncols, &one, Ls_x, &nsrow, B.data(), &nscol);
      const int nbelow = nsrow - nscol;
      if (nbelow == 0) continue;
      W.resize(nbelow, ncols);
      dgemm_(&notrans, &notrans, &nbelow, &ncols, &nscol, &one, Ls_x + nscol, &nsrow, B.data(), &nscol, &zero, W.data(),
             &nbelow);
      // Scatter into the ancestors: row r of supernode t, batch column J_s[c] at its place in J_t
      // (J_s is a subset of J_t: a chain through s goes on through every ancestor).
      const auto& js = path_columns[static_cast<std::size_t>(s)];
      int last_t = -1;
      Eigen::MatrixXd* Bt = nullptr;
      for (int i = 0; i < nbelow; ++i) {
        const int r = Ls[pi[s] + nscol + i];
        const int t = supernode_of[static_cast<std::size_t>(r)];
        if (t != last_t) {
          last_t = t;
          Bt = &blocks[static_cast<std::size_t>(block_of[static_cast<std::size_t>(t)])];
          const auto& jt = path_columns[static_cast<std::size_t>(t)];
          column_map.resize(static_cast<std::size_t>(ncols));
          for (int c = 0; c < ncols; ++c) {
            column_map[static_cast<std::size_t>(c)] =
                static_cast<int>(std::lower_bound(jt.begin(), jt.end(), js[static_cast<std::size_t>(c)]) - jt.begin());
          }
        }
        const int row = r - super[t];
        for (int c = 0; c < ncols; ++c) (*Bt)(row, column_map[static_cast<std::size_t>(c)]) -= W(i, c);
      }
    }
    std::vector<SparseColumn> out(static_cast<std::size_t>(nb));
    for (int j = 0; j < nb; ++j) {
      SparseColumn& x = out[static_cast<std::size_t>(j)];
      const auto& rows_j = b[static_cast<std::size_t>(j)].rows;
      const int first = rows_j.empty() ? 0 : *std::min_element(rows_j.begin(), rows_j.end());
      for (int s : chain[static_cast<std::size_t>(j)]) {
        const auto c = position(s, j);
        const Eigen::MatrixXd& B = blocks[static_cast<std::size_t>(block_of[static_cast<std::size_t>(s)])];
        for (int k = std::max(super[s], first); k < super[s + 1]; ++k) {  // rows above the first of b_j are zero
          x.rows.push_back(k);
          x.values.push_back(B(k - super[s], c));
        }
      }
    }
    for (int s : touched) {
      path_columns[static_cast<std::size_t>(s)].clear();
      block_of[static_cast<std::size_t>(s)] = -1;
    }
    return out;
  }
};

namespace {

// Nested dissection (METIS) of the supervariable graph of A: runs of consecutive indices whose
// columns have the same pattern (the 2 DOFs of a node in 2-D elasticity) become one vertex, so
// METIS orders a graph with half the vertices and a quarter of the edges; the permutation of A
// takes each run's indices together. A: both triangles stored, compressed, sorted. Returns an
// empty vector when CHOLMOD's METIS fails (the caller falls back to CHOLMOD's default).
std::vector<int> supervariable_metis(int n, const int* p, const int* i, cholmod_common& common) {
  std::vector<int> group_of(static_cast<std::size_t>(n));
  std::vector<int> group_start{0};
  for (int j = 1; j < n; ++j) {
    const bool same = p[j + 1] - p[j] == p[j] - p[j - 1] && std::equal(i + p[j], i + p[j + 1], i + p[j - 1]);
    if (!same) group_start.push_back(j);
  }
  const int ng = static_cast<int>(group_start.size());
  group_start.push_back(n);
  for (int g = 0; g < ng; ++g) {
    for (int j = group_start[static_cast<std::size_t>(g)]; j < group_start[static_cast<std::size_t>(g) + 1]; ++j) {
      group_of[static_cast<std::size_t>(j)] = g;
    }
  }
  // Pattern of the compressed graph (both triangles, diagonal dropped: METIS ignores it).
  std::vector<int> cp{0}, ci;
  ci.reserve(static_cast<std::size_t>(p[n]) / 4 + static_cast<std::size_t>(n));
  for (int g = 0; g < ng; ++g) {
    const int j = group_start[static_cast<std::size_t>(g)];
    int last = -1;
    for (int k = p[j]; k < p[j + 1]; ++k) {
      const int h = group_of[static_cast<std::size_t>(i[k])];
      if (h != g && h != last) ci.push_back(h);  // rows ascending: groups ascending
      last = h;
    }
    cp.push_back(static_cast<int>(ci.size()));
  }
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<std::size_t>(ng);
  view.nzmax = ci.size();
  view.p = cp.data();
  view.i = ci.data();
  view.stype = 1;  // symmetric: METIS reads the whole pattern, the upper triangle is the one kept
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_PATTERN;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  std::vector<int> group_perm(static_cast<std::size_t>(ng));

  const int metis_ok = cholmod_metis(&view, nullptr, 0, 0, group_perm.data(), &common);

  if (!metis_ok) {
    common.status = CHOLMOD_OK;  // e.g. out of memory in METIS: CHOLMOD's default ordering instead
    return {};
  }
  std::vector<int> perm;
  perm.reserve(static_cast<std::size_t>(n));
  for (int g : group_perm) {
    for (int j = group_start[static_cast<std::size_t>(g)]; j < group_start[static_cast<std::size_t>(g) + 1]; ++j) perm.push_back(j);
  }
  return perm;
}

}  // namespace

const char* to_string(FactorOrdering ordering) {
  switch (ordering) {
    case FactorOrdering::Auto: return "auto";
    case FactorOrdering::Cholmod: return "cholmod";
    case FactorOrdering::NodeMetis: return "node-metis";
  }
  return "unknown";
}

FactorOrdering factor_ordering_from_string(const std::string& name) {
  using enum FactorOrdering;
  return enum_from_string(name, "factor ordering", std::array{Auto, Cholmod, NodeMetis});
}

FactorOrdering auto_ordering(int rows) { return rows >= kNodeMetisFrom ? FactorOrdering::NodeMetis : FactorOrdering::Cholmod; }

SelectedInverse::SelectedInverse() : impl_(std::make_unique<Impl>()) {}
SelectedInverse::~SelectedInverse() = default;
SelectedInverse::SelectedInverse(SelectedInverse&&) noexcept = default;
SelectedInverse& SelectedInverse::operator=(SelectedInverse&&) noexcept = default;

namespace {

// CHOLMOD's read-only view of a compressed matrix (both triangles stored, the lower read);
// x == nullptr: the pattern alone.
cholmod_sparse view_of(int n, const int* p, const int* i, const double* x) {
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<std::size_t>(n);
  view.nzmax = static_cast<std::size_t>(p[n]);
  // CHOLMOD reads its input only (cholmod_analyze, cholmod_factorize take it as const data).
  view.p = const_cast<int*>(p);
  view.i = const_cast<int*>(i);
  view.x = const_cast<double*>(x);
  view.stype = -1;  // symmetric, lower triangle read
  view.itype = CHOLMOD_INT;
  view.xtype = x != nullptr ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}
cholmod_sparse view_of(const Eigen::SparseMatrix<double>& A) {
  return view_of(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr());
}

// The settings of the numeric factorization, the same on every path.
void set_factor_options(cholmod_common& common) {
  common.supernodal = CHOLMOD_SUPERNODAL;  // BLAS-3 numeric factorization
  common.final_asis = 1;
}

// Ordering + symbolic analysis (the pattern of A only). `ordering` resolved (not Auto); `used`:
// the ordering taken (NodeMetis falls back to CHOLMOD's default when METIS fails).
cholmod_factor* analyze_pattern(int n, const int* p, const int* i, FactorOrdering ordering, cholmod_common& common,
                                FactorOrdering& used) {
  cholmod_sparse view = view_of(n, p, i, nullptr);
  set_factor_options(common);
  // METIS keeps state shared by the threads of the process (its random-number generator): two
  // orderings at once on two threads gave different permutations from one run to the next
  // (tests/hf/test_semismooth_newton.cpp, analysis beside the assembly against a solve's own), so
  // the calls that may run METIS take turns.
  static std::mutex metis_mutex;
  std::vector<int> given;
  if (ordering == FactorOrdering::NodeMetis) {
    const std::lock_guard<std::mutex> lock(metis_mutex);
    given = supervariable_metis(n, p, i, common);
  }
  if (!given.empty()) {
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_GIVEN;
    common.postorder = 1;
    used = FactorOrdering::NodeMetis;
    return cholmod_analyze_p(&view, given.data(), nullptr, 0, &common);
  }
  common.nmethods = 0;  // CHOLMOD's default: AMD, METIS when AMD fills badly
  common.method[0].ordering = CHOLMOD_GIVEN;
  used = FactorOrdering::Cholmod;
  const std::lock_guard<std::mutex> lock(metis_mutex);  // METIS when AMD fills badly
  return cholmod_analyze(&view, &common);
}

}  // namespace

struct FactorAnalysis::Impl {
  cholmod_common common{};
  cholmod_factor* L = nullptr;  // symbolic
  FactorOrdering requested = FactorOrdering::Cholmod, used = FactorOrdering::Cholmod;
  std::vector<int> outer, inner;  // the pattern analysed, for matches()
  double seconds = 0.0;
  double lnz = 0.0, flops = 0.0;  // cholmod_common's, read right after the analysis
  Impl() { cholmod_start(&common); }
  ~Impl() {
    if (L != nullptr) cholmod_free_factor(&L, &common);
    cholmod_finish(&common);
  }
};

FactorAnalysis::FactorAnalysis() : impl_(std::make_unique<Impl>()) {}
FactorAnalysis::~FactorAnalysis() = default;
FactorAnalysis::FactorAnalysis(FactorAnalysis&&) noexcept = default;
FactorAnalysis& FactorAnalysis::operator=(FactorAnalysis&&) noexcept = default;

FactorAnalysis FactorAnalysis::analyze(const Eigen::SparseMatrix<double>& pattern, FactorOrdering ordering) {
  if (pattern.rows() != pattern.cols() || pattern.rows() == 0 || !pattern.isCompressed()) {
    FactorAnalysis a;
    a.impl_->requested = ordering == FactorOrdering::Auto ? auto_ordering(static_cast<int>(pattern.rows())) : ordering;
    return a;
  }
  return analyze(static_cast<int>(pattern.rows()),
                 std::vector<int>(pattern.outerIndexPtr(), pattern.outerIndexPtr() + pattern.cols() + 1),
                 std::vector<int>(pattern.innerIndexPtr(), pattern.innerIndexPtr() + pattern.nonZeros()), ordering);
}

FactorAnalysis FactorAnalysis::analyze(int n, std::vector<int> outer, std::vector<int> inner, FactorOrdering ordering) {
  const auto t0 = std::chrono::steady_clock::now();
  FactorAnalysis a;
  Impl& m = *a.impl_;
  m.requested = ordering == FactorOrdering::Auto ? auto_ordering(n) : ordering;
  if (n <= 0 || outer.size() != static_cast<std::size_t>(n) + 1 || outer[0] != 0 ||
      static_cast<std::size_t>(outer.back()) != inner.size()) {
    return a;
  }
  m.L = analyze_pattern(n, outer.data(), inner.data(), m.requested, m.common, m.used);
  // Set from the column counts before the supernodal analysis, so also when that one fails for
  // size (CHOLMOD_TOO_LARGE: a factor beyond the int indices).
  m.lnz = std::max(0.0, m.common.lnz);  // EMPTY (-1) when the analysis stopped before the counts
  m.flops = std::max(0.0, m.common.fl);
  if (m.L == nullptr) return a;
  m.outer = std::move(outer);
  m.inner = std::move(inner);
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return a;
}

bool FactorAnalysis::valid() const { return impl_ && impl_->L != nullptr; }
FactorOrdering FactorAnalysis::requested() const { return impl_ ? impl_->requested : FactorOrdering::Auto; }
double FactorAnalysis::seconds() const { return impl_ ? impl_->seconds : 0.0; }
double FactorAnalysis::factor_nonzeros() const { return impl_ ? impl_->lnz : 0.0; }
double FactorAnalysis::factor_flops() const { return impl_ ? impl_->flops : 0.0; }
bool FactorAnalysis::matches(const Eigen::SparseMatrix<double>& A) const {
  if (!valid() || !A.isCompressed() || A.rows() != A.cols()) return false;
  const Impl& m = *impl_;
  if (static_cast<std::size_t>(A.cols()) + 1 != m.outer.size() || static_cast<std::size_t>(A.nonZeros()) != m.inner.size()) {
    return false;
  }
  return std::equal(m.outer.begin(), m.outer.end(), A.outerIndexPtr()) &&
         std::equal(m.inner.begin(), m.inner.end(), A.innerIndexPtr());
}

SelectedInverseStatus SelectedInverse::compute(const Eigen::SparseMatrix<double>& A, FactorOrdering ordering) {
  return compute_impl(A, ordering, nullptr);
}

SelectedInverseStatus SelectedInverse::compute(const Eigen::SparseMatrix<double>& A, const FactorAnalysis& analysis) {
  return compute_impl(A, analysis.requested(), analysis.matches(A) ? &analysis : nullptr);
}

bool SelectedInverse::used_analysis() const { return impl_->used_analysis; }

SelectedInverseStatus SelectedInverse::compute_impl(const Eigen::SparseMatrix<double>& A_in, FactorOrdering ordering,
                                                    const FactorAnalysis* analysis) {
  Impl& m = *impl_;
  m.release();
  m.n = 0;
  m.analyze_s = m.factorize_s = 0.0;
  m.used_analysis = false;
  m.status = SelectedInverseStatus::InvalidInput;
  if (A_in.rows() != A_in.cols() || A_in.rows() == 0) return m.status;
  // A compressed A_in is read in place (a copy is ~250 MB of fresh memory at 1.2e6 DOFs).
  Eigen::SparseMatrix<double> compressed;
  if (!A_in.isCompressed()) {
    compressed = A_in;
    compressed.makeCompressed();
  }
  const Eigen::SparseMatrix<double>& A = A_in.isCompressed() ? A_in : compressed;
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) {
    if (!std::isfinite(A.valuePtr()[k])) return m.status;
  }
  cholmod_sparse view = view_of(A);
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  if (analysis != nullptr) {
    // The symbolic factor, copied (the analysis stays usable for other computes).
    set_factor_options(m.common);
    m.L = cholmod_copy_factor(analysis->impl_->L, &m.common);
    m.ordering_used = analysis->impl_->used;
    m.used_analysis = m.L != nullptr;
  } else {
    if (ordering == FactorOrdering::Auto) ordering = auto_ordering(static_cast<int>(A.rows()));
    m.L = analyze_pattern(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(), ordering, m.common,
                          m.ordering_used);
  }
  m.analyze_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (m.L == nullptr) return m.status;
  t0 = Clock::now();
  const int ok = cholmod_factorize(&view, m.L, &m.common);
  m.factorize_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (m.common.status == CHOLMOD_NOT_POSDEF || (ok && m.L->minor < m.L->n)) {
    m.status = SelectedInverseStatus::NotPositiveDefinite;
    cholmod_free_factor(&m.L, &m.common);
    return m.status;
  }
  if (!ok || !m.L->is_super) {
    cholmod_free_factor(&m.L, &m.common);
    return m.status;
  }
  m.n = static_cast<int>(A.rows());
  const int nsuper = static_cast<int>(m.L->nsuper);
  const int* super = static_cast<const int*>(m.L->super);
  const int* pi = static_cast<const int*>(m.L->pi);
  const int* Ls = static_cast<const int*>(m.L->s);
  m.supernode_of.assign(static_cast<std::size_t>(m.n), -1);
  for (int s = 0; s < nsuper; ++s) {
    for (int k = super[s]; k < super[s + 1]; ++k) m.supernode_of[static_cast<std::size_t>(k)] = s;
  }
  m.supernode_parent.assign(static_cast<std::size_t>(nsuper), -1);
  for (int s = 0; s < nsuper; ++s) {
    const int nscol = super[s + 1] - super[s];
    if (pi[s + 1] - pi[s] > nscol) m.supernode_parent[static_cast<std::size_t>(s)] = m.supernode_of[static_cast<std::size_t>(Ls[pi[s] + nscol])];
  }
  m.path_columns.assign(static_cast<std::size_t>(nsuper), {});
  m.chain_mark.assign(static_cast<std::size_t>(nsuper), 0);
  m.work.assign(static_cast<std::size_t>(m.n), 0.0);
  m.block_of.assign(static_cast<std::size_t>(nsuper), -1);
  m.inverse_perm.assign(static_cast<std::size_t>(m.n), 0);
  const int* perm = static_cast<const int*>(m.L->Perm);
  for (int k = 0; k < m.n; ++k) m.inverse_perm[static_cast<std::size_t>(perm[k])] = k;
  m.row_pos.assign(static_cast<std::size_t>(m.n), -1);
  m.find_split();
  m.status = SelectedInverseStatus::Success;
  return m.status;
}

SelectedInverseStatus SelectedInverse::status() const { return impl_->status; }
int SelectedInverse::rows() const { return impl_->n; }
long SelectedInverse::factor_nonzeros() const {
  const Impl& m = *impl_;
  if (m.L == nullptr) return 0;
  const int* super = static_cast<const int*>(m.L->super);
  const int* pi = static_cast<const int*>(m.L->pi);
  long count = 0;
  for (std::size_t s = 0; s < m.L->nsuper; ++s) {
    const long nscol = super[s + 1] - super[s], nsrow = pi[s + 1] - pi[s];
    count += nscol * (nscol + 1) / 2 + nscol * (nsrow - nscol);
  }
  return count;
}
double SelectedInverse::analyze_seconds() const { return impl_->analyze_s; }
double SelectedInverse::factorize_seconds() const { return impl_->factorize_s; }
FactorOrdering SelectedInverse::ordering() const { return impl_->ordering_used; }
int SelectedInverse::cached_columns() const { return static_cast<int>(impl_->units.columns.size()); }
void SelectedInverse::set_substitution_threads(int threads) { impl_->substitution_threads = std::max(1, threads); }
bool SelectedInverse::has_substitution_fork() const { return impl_->status == SelectedInverseStatus::Success && impl_->split_top >= 0; }

Eigen::VectorXd SelectedInverse::solve(const Eigen::VectorXd& b) const {
  Impl& m = *impl_;
  require(m.status == SelectedInverseStatus::Success,
          std::string("SelectedInverse::solve: the factorization is ") + to_string(m.status));
  require(b.size() == m.n, "SelectedInverse::solve: right-hand side has " + std::to_string(b.size()) +
                               " entries for " + std::to_string(m.n) + " rows");
  Eigen::VectorXd copy = b;
  cholmod_dense view{};
  view.nrow = static_cast<std::size_t>(m.n);
  view.ncol = 1;
  view.nzmax = static_cast<std::size_t>(m.n);
  view.d = static_cast<std::size_t>(m.n);
  view.x = copy.data();
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, m.L, &view, &m.common);
  require(x != nullptr, "SelectedInverse::solve: CHOLMOD failed (out of memory?)");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), m.n);
  cholmod_free_dense(&x, &m.common);
  return out;
}

Eigen::VectorXd SelectedInverse::solve_sparse(const std::vector<int>& in, const Eigen::VectorXd& b_in,
                                              const std::vector<int>* out) const {
  Impl& m = *impl_;
  require(m.status == SelectedInverseStatus::Success,
          std::string("SelectedInverse::solve_sparse: the factorization is ") + to_string(m.status));
  require(b_in.size() == static_cast<Eigen::Index>(in.size()), "SelectedInverse::solve_sparse: " +
                                                                   std::to_string(b_in.size()) + " values for " +
                                                                   std::to_string(in.size()) + " indices");
  auto permuted = [&](const std::vector<int>& idx) {
    std::vector<int> q;
    q.reserve(idx.size());
    for (int i : idx) {
      require(i >= 0 && i < m.n, "SelectedInverse::solve_sparse: index " + std::to_string(i) + " outside [0, " +
                                     std::to_string(m.n) + ")");
      q.push_back(m.inverse_perm[static_cast<std::size_t>(i)]);
    }
    return q;
  };
  const std::vector<int> q_in = permuted(in);
  const int* super = static_cast<const int*>(m.L->super);
  const int* pi = static_cast<const int*>(m.L->pi);
  const int* px = static_cast<const int*>(m.L->px);
  const int* Ls = static_cast<const int*>(m.L->s);
  const double* Lx = static_cast<const double*>(m.L->x);
  double* w = m.work.data();
  const char lower = 'L', notrans = 'N', trans = 'T', nonunit = 'N';
  const double one = 1.0, minus_one = -1.0, zero = 0.0;
  const int inc = 1;
  std::vector<double> below;
  // Forward L v = P b: only the chains of `in` (v vanishes elsewhere, Gilbert's theorem).
  for (std::size_t a = 0; a < in.size(); ++a) w[q_in[a]] += b_in(static_cast<Eigen::Index>(a));
  const std::vector<int> forward = m.chains(q_in);
  for (int s : forward) {
    const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s], nbelow = nsrow - nscol;
    const double* Lss = Lx + px[s];
    dtrsv_(&lower, &notrans, &nonunit, &nscol, Lss, &nsrow, w + k1, &inc);
    if (nbelow == 0) continue;
    below.assign(static_cast<std::size_t>(nbelow), 0.0);
    dgemv_(&notrans, &nbelow, &nscol, &one, Lss + nscol, &nsrow, w + k1, &inc, &zero, below.data(), &inc);
    for (int i = 0; i < nbelow; ++i) w[Ls[pi[s] + nscol + i]] -= below[static_cast<std::size_t>(i)];
  }
  // Backward L' x' = v, root first: x' on a supernode needs x' on its ancestors only, so the
  // chains of `out` suffice for x[out]; all supernodes for the whole x.
  std::vector<int> backward;
  std::vector<int> q_out;
  if (out != nullptr) {
    q_out = permuted(*out);
    backward = m.chains(q_out);
  } else {
    backward.resize(m.L->nsuper);
    for (std::size_t s = 0; s < backward.size(); ++s) backward[s] = static_cast<int>(s);
  }
  auto backward_one = [&](int s, std::vector<double>& buffer) {
    const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s], nbelow = nsrow - nscol;
    const double* Lss = Lx + px[s];
    if (nbelow > 0) {
      buffer.resize(static_cast<std::size_t>(nbelow));
      for (int i = 0; i < nbelow; ++i) buffer[static_cast<std::size_t>(i)] = w[Ls[pi[s] + nscol + i]];
      dgemv_(&trans, &nbelow, &nscol, &minus_one, Lss + nscol, &nsrow, buffer.data(), &inc, &one, w + k1, &inc);
    }
    dtrsv_(&lower, &trans, &nonunit, &nscol, Lss, &nsrow, w + k1, &inc);
  };
  if (out == nullptr && m.substitution_threads >= 2 && m.split_top >= 0) {
    // The chain above the fork, then its two subtree ranges at once: each supernode's
    // arithmetic is the serial one (same inputs, same calls), so x is bitwise the same.
    const int nsuper = static_cast<int>(m.L->nsuper);
    for (int s = nsuper - 1; s >= m.split_top; --s) backward_one(s, below);
    // An exception on either thread (bad_alloc of a buffer) reaches the caller after the join,
    // never std::terminate.
    std::exception_ptr upper_error;
    std::thread upper_range([&] {
      try {
        std::vector<double> buffer;
        for (int s = m.split_top - 1; s >= m.split_cut; --s) backward_one(s, buffer);
      } catch (...) {
        upper_error = std::current_exception();
      }
    });
    try {
      for (int s = m.split_cut - 1; s >= 0; --s) backward_one(s, below);
    } catch (...) {
      upper_range.join();
      throw;
    }
    upper_range.join();
    if (upper_error) std::rethrow_exception(upper_error);
  } else {
    for (auto it = backward.rbegin(); it != backward.rend(); ++it) backward_one(*it, below);
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(m.n);
  if (out != nullptr) {
    for (std::size_t a = 0; a < out->size(); ++a) x((*out)[a]) = w[q_out[a]];
  } else {
    const int* perm = static_cast<const int*>(m.L->Perm);
    for (int k = 0; k < m.n; ++k) x(perm[k]) = w[k];
  }
  // Restore the zero work vector on every supernode touched.
  for (const std::vector<int>* touched : {&forward, static_cast<const std::vector<int>*>(&backward)}) {
    for (int s : *touched) std::fill(w + super[s], w + super[s + 1], 0.0);
  }
  return x;
}

Eigen::MatrixXd SelectedInverse::block(const std::vector<int>& idx) {
  std::vector<double> storage;
  return block(idx, storage);
}

namespace {

// Per cached column, a cursor on its entries (ascending rows, so ascending positions on the
// rows U_new of block()); next_position(j) skips the rows outside U_new (row_pos < 0) and gives
// the position of the next entry (`end` past the last). The entries are read in place: a copy of
// every column's entries on U_new (16 bytes per entry) would be ~300 MB of fresh memory in the
// first call at 1.2e6 DOFs.
struct ColumnCursors {
  const std::vector<SparseColumn>& columns;
  const std::vector<int>& row_pos;
  int end;
  std::vector<std::size_t> at;
  int next_position(int j) {
    const SparseColumn& col = columns[static_cast<std::size_t>(j)];
    std::size_t& c = at[static_cast<std::size_t>(j)];
    while (c < col.rows.size() && row_pos[static_cast<std::size_t>(col.rows[c])] < 0) ++c;
    return c < col.rows.size() ? row_pos[static_cast<std::size_t>(col.rows[c])] : end;
  }
};

}  // namespace

// The pattern rows of the columns old..total-1, ascending: U_new; row_pos holds their positions.
std::vector<int> GramCache::new_rows(int old, int total, std::vector<int>& row_pos) {
  std::vector<int> union_rows;
  for (int j = old; j < total; ++j) {
    for (int r : columns[static_cast<std::size_t>(j)].rows) {
      int& pos = row_pos[static_cast<std::size_t>(r)];
      if (pos < 0) {
        pos = 0;
        union_rows.push_back(r);
      }
    }
  }
  std::sort(union_rows.begin(), union_rows.end());
  for (std::size_t a = 0; a < union_rows.size(); ++a) row_pos[static_cast<std::size_t>(union_rows[a])] = static_cast<int>(a);
  return union_rows;
}

// G to hold `total` columns: exactly at the first call (all the columns of the first system:
// hertz-a level 7, 3 960, the most of the solve); a quarter more than asked when later calls
// add columns.
void GramCache::grow_gram(int old, int total) {
  if (total <= g_capacity) return;
  const int capacity = old == 0 ? total : total + total / 4;
  std::vector<double> grown(static_cast<std::size_t>(capacity) * static_cast<std::size_t>(capacity));
  for (int j = 0; j < old; ++j) {
    std::copy_n(&g(0, j), old, grown.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(capacity));
  }
  G = std::move(grown);
  g_capacity = capacity;
}

// One chunk [begin, end) of U_new: G[:, old:] += Xc' Xc[:, new], Xc = X[chunk, J_c] over the
// columns J_c present in the chunk. Old columns x new ones (dgemm), new x new (dsyrk, one
// triangle: the first call has only new columns, and this halves its flops).
void GramCache::gram_chunk(int begin, int end, int old, ColumnCursors& cursors, std::vector<int>& present,
                                      Eigen::MatrixXd& Xc, Eigen::MatrixXd& Gc) {
  const int total = static_cast<int>(columns.size());
  present.clear();
  int first_new = -1;  // position in `present` of the first new column
  for (int j = 0; j < total; ++j) {
    if (cursors.next_position(j) < end) {
      if (j >= old && first_new < 0) first_new = static_cast<int>(present.size());
      present.push_back(j);
    }
  }
  if (first_new < 0) {  // no new column here: nothing to add, but advance the cursors
    for (int j : present) {
      while (cursors.next_position(j) < end) ++cursors.at[static_cast<std::size_t>(j)];
    }
    return;
  }
  const int np = static_cast<int>(present.size());
  Xc.setZero(end - begin, np);
  for (int a = 0; a < np; ++a) {
    const int j = present[static_cast<std::size_t>(a)];
    const std::vector<double>& values = columns[static_cast<std::size_t>(j)].values;
    for (int pos; (pos = cursors.next_position(j)) < end; ++cursors.at[static_cast<std::size_t>(j)]) {
      Xc(pos - begin, a) = values[cursors.at[static_cast<std::size_t>(j)]];
    }
  }
  const int nn = np - first_new;  // the new columns are the last ones of `present`
  const int rows_c = end - begin;
  const double* Xnew = Xc.data() + static_cast<std::size_t>(first_new) * static_cast<std::size_t>(rows_c);
  const char t = 'T', nt = 'N', upper = 'U';
  const double one = 1.0, zero = 0.0;
  auto right = [this, old](int i, int jb) -> double& { return g(i, old + jb); };  // G[:, old:total]
  if (first_new > 0) {
    Gc.resize(first_new, nn);
    dgemm_(&t, &nt, &first_new, &nn, &rows_c, &one, Xc.data(), &rows_c, Xnew, &rows_c, &zero, Gc.data(), &first_new);
    for (int b = 0; b < nn; ++b) {
      const int jb = present[static_cast<std::size_t>(first_new + b)] - old;
      for (int a = 0; a < first_new; ++a) right(present[static_cast<std::size_t>(a)], jb) += Gc(a, b);
    }
  }
  Gc.resize(nn, nn);
  dsyrk_(&upper, &t, &nn, &rows_c, &one, Xnew, &rows_c, &zero, Gc.data(), &nn);
  for (int b = 0; b < nn; ++b) {
    const int jb = present[static_cast<std::size_t>(first_new + b)] - old;
    for (int a = 0; a < nn; ++a) {
      right(present[static_cast<std::size_t>(first_new + a)], jb) += a <= b ? Gc(a, b) : Gc(b, a);
    }
  }
}

// G[:, new] = X' X[:, new], X = [x_1 .. x_total], for the columns old..total-1. Only the rows
// U_new of the new columns' patterns count (X[:, new] is zero elsewhere). The patterns are
// elimination-tree paths: near the root every column has entries, further down only a few. So
// U_new is cut into chunks of kChunk rows, and each chunk contributes a dense BLAS product over
// the columns present in it only. One dense product over all of U_new would cost
// |U_new| x total x new: on hertz-a level 6 (1 400 columns, paths of ~3 000 rows) 7 of the 15
// CPU seconds of a solve.
void GramCache::gram_new_columns(int old, std::vector<int>& row_pos) {
  constexpr int kChunk = 256;
  const int total = static_cast<int>(columns.size());
  const std::vector<int> union_rows = new_rows(old, total, row_pos);
  const int u = static_cast<int>(union_rows.size());
  grow_gram(old, total);
  for (int j = old; j < total; ++j) std::fill_n(&g(0, j), total, 0.0);  // accumulated in place
  ColumnCursors cursors{columns, row_pos, u, std::vector<std::size_t>(static_cast<std::size_t>(total), 0)};
  std::vector<int> present;
  Eigen::MatrixXd Xc, Gc;
  for (int begin = 0; begin < u; begin += kChunk) {
    gram_chunk(begin, std::min(u, begin + kChunk), old, cursors, present, Xc, Gc);
  }
  for (int r : union_rows) row_pos[static_cast<std::size_t>(r)] = -1;
  for (int i = old; i < total; ++i) {  // G[new, old] = G[old, new]'
    for (int j = 0; j < old; ++j) g(i, j) = g(j, i);
  }
}

Eigen::Map<const Eigen::MatrixXd> GramCache::gather(const std::vector<int>& keys, std::vector<double>& storage) {
  const std::size_t e = keys.size();
  if (storage.capacity() < e * e) {
    storage = std::vector<double>();  // no copy of the old contents
    storage.reserve(e * e + e * e / 4);
  }
  storage.resize(e * e);
  std::vector<int> pos(e);
  for (std::size_t a = 0; a < e; ++a) pos[a] = column_of[keys[a]];
  for (std::size_t b = 0; b < e; ++b) {
    const double* column = &g(0, pos[b]);
    double* out = storage.data() + b * e;
    for (std::size_t a = 0; a < e; ++a) out[a] = column[pos[a]];
  }
  return Eigen::Map<const Eigen::MatrixXd>(storage.data(), static_cast<Eigen::Index>(e), static_cast<Eigen::Index>(e));
}

template <class MakeRhs>
Eigen::Map<const Eigen::MatrixXd> SelectedInverse::Impl::cached_block(GramCache& cache, const std::vector<int>& keys,
                                                                      MakeRhs rhs, std::vector<double>& storage) {
  std::vector<SparseRhs> fresh;
  const int cached = static_cast<int>(cache.columns.size());
  for (int key : keys) {
    if (cache.column_of.count(key) == 0) {
      cache.column_of.emplace(key, cached + static_cast<int>(fresh.size()));
      fresh.push_back(rhs(key));
    }
  }
  for (SparseColumn& x : forward_batch(fresh)) cache.columns.push_back(std::move(x));
  if (!fresh.empty()) cache.gram_new_columns(cached, row_pos);
  return cache.gather(keys, storage);
}

Eigen::Map<const Eigen::MatrixXd> SelectedInverse::block(const std::vector<int>& idx, std::vector<double>& storage) {
  Impl& m = *impl_;
  require(m.status == SelectedInverseStatus::Success,
          std::string("SelectedInverse::block: the factorization is ") + to_string(m.status));
  for (int i : idx) {
    require(i >= 0 && i < m.n, "SelectedInverse::block: index " + std::to_string(i) + " outside [0, " +
                                   std::to_string(m.n) + ")");
  }
  auto unit = [&m](int i) { return SparseRhs{{m.inverse_perm[static_cast<std::size_t>(i)]}, {1.0}}; };
  return m.cached_block(m.units, idx, unit, storage);
}

Eigen::Map<const Eigen::MatrixXd> SelectedInverse::row_block(const std::vector<int>& rows,
                                                             const Eigen::SparseMatrix<double, Eigen::RowMajor>& V,
                                                             std::vector<double>& storage) {
  Impl& m = *impl_;
  require(m.status == SelectedInverseStatus::Success,
          std::string("SelectedInverse::row_block: the factorization is ") + to_string(m.status));
  require(V.cols() == m.n, "SelectedInverse::row_block: V has " + std::to_string(V.cols()) + " columns for " +
                               std::to_string(m.n) + " rows");
  for (int r : rows) {
    require(r >= 0 && r < V.rows(), "SelectedInverse::row_block: row " + std::to_string(r) + " outside [0, " +
                                        std::to_string(V.rows()) + ")");
  }
  auto row = [&m, &V](int r) {
    SparseRhs b;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator v(V, r); v; ++v) {
      b.rows.push_back(m.inverse_perm[static_cast<std::size_t>(v.col())]);
      b.values.push_back(v.value());
    }
    return b;
  };
  return m.cached_block(m.rows, rows, row, storage);
}

void SelectedInverse::forget_rows() { impl_->rows.clear(); }

}  // namespace contactrb::solve
