#include "contactrb/online/complementary_correction.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <vector>

#include "contactrb/common/index_cast.hpp"

namespace contactrb::online {

namespace {
// Rounds of the row set: each adds the measured rows the previous correction closed.
constexpr int kMaxRounds = 8;
// Rows of the R factor per block of the Gram matrix's rank updates.
constexpr Eigen::Index kGramBlockRows = 64;
}  // namespace

void ComplementaryCorrection::setup(const Eigen::MatrixXd& load_T, const std::vector<int>& exact_dofs,
                                    Eigen::Index n_c) {
  load_T_ = load_T;
  gram_.resize(0, 0);
  local_.assign(sz(n_c), -1);
  for (std::size_t k = 0; k < exact_dofs.size(); ++k) local_[sz(exact_dofs[k])] = static_cast<int>(k);
}

void ComplementaryCorrection::form_gram() {
  // Formed on first use: a model answered without the correction never pays for it. The columns
  // are columns of a pivoted R factor: ordered by their last non-zero row they form an upper
  // trapezoidal U, whose U'U is summed by blocks of rows over the columns each block reaches
  // (n^3 / 3 multiply-adds for n columns against n^3 for the full product, symmetric: one triangle).
  const Index n = load_T_.cols(), rank = load_T_.rows();
  std::vector<Index> last(sz(n)), order(sz(n)), position(sz(n));
  for (Index k = 0; k < n; ++k) {
    Index r = rank - 1;
    while (r >= 0 && load_T_(r, k) == 0.0) --r;
    last[sz(k)] = r;
  }
  std::iota(order.begin(), order.end(), Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return last[sz(a)] < last[sz(b)]; });
  Eigen::MatrixXd U(rank, n);
  for (Index j = 0; j < n; ++j) {
    U.col(j) = load_T_.col(order[sz(j)]);
    position[sz(order[sz(j)])] = j;
  }
  load_T_.resize(0, 0);
  gram_.setZero(n, n);
  Index c0 = 0;  // the first column that reaches the block's rows
  for (Index i0 = 0; i0 < rank; i0 += kGramBlockRows) {
    const Index b = std::min(kGramBlockRows, rank - i0);
    while (c0 < n && last[sz(order[sz(c0)])] < i0) ++c0;
    if (c0 == n) break;
    gram_.bottomRightCorner(n - c0, n - c0).selfadjointView<Eigen::Lower>().rankUpdate(
        U.block(i0, c0, b, n - c0).transpose());
  }
  gram_.triangularView<Eigen::StrictlyUpper>() = gram_.transpose();
  for (int& k : local_) {
    if (k >= 0) k = static_cast<int>(position[sz(k)]);
  }
}

bool ComplementaryCorrection::gather_measured(const RowSparse& K, const Eigen::VectorXd& lambda) {
  measured_.clear();
  for (Index r = 0; r < K.rows(); ++r) {
    bool measured = K.row(r).nonZeros() > 0;
    for (RowSparse::InnerIterator it(K, r); it && measured; ++it) measured = local_[sz(it.col())] >= 0;
    if (measured) {
      measured_.push_back(r);
    } else if (lambda(r) != 0.0) {
      return false;
    }
  }
  return true;
}

void ComplementaryCorrection::form_schur(const RowSparse& K, double t) {
  const Index m = ix(rows_.size());
  // The rows' entries by measured index, in one array (each row: a few DOFs).
  entry_start_.assign(sz(m + 1), 0);
  entries_.clear();
  for (Index i = 0; i < m; ++i) {
    for (RowSparse::InnerIterator it(K, rows_[sz(i)]); it; ++it) entries_.push_back({local_[sz(it.col())], it.value()});
    entry_start_[sz(i + 1)] = static_cast<int>(entries_.size());
  }
  KG_.setZero(m, gram_.cols());
  for (Index i = 0; i < m; ++i) {
    for (int e = entry_start_[sz(i)]; e < entry_start_[sz(i + 1)]; ++e) {
      KG_.row(i).noalias() += entries_[sz(e)].value * gram_.col(entries_[sz(e)].local).transpose();  // gram_ is symmetric
    }
  }
  // One triangle of S / t = K_rows KG_' / t, by sparse dots on the rows of KG_ (contiguous), mirrored.
  S_.resize(m, m);
  for (Index i = 0; i < m; ++i) {
    const double* g = KG_.row(i).data();
    for (Index j = i; j < m; ++j) {
      double v = 0.0;
      for (int e = entry_start_[sz(j)]; e < entry_start_[sz(j + 1)]; ++e) v += entries_[sz(e)].value * g[entries_[sz(e)].local];
      S_(i, j) = S_(j, i) = v / t;
    }
  }
}

bool ComplementaryCorrection::solve_on_rows(const Eigen::VectorXd& slack, const Eigen::VectorXd& lambda) {
  const Index m = ix(rows_.size());
  lam_.resize(m);
  q_.resize(m);
  warm_.clear();
  for (Index i = 0; i < m; ++i) {
    lam_(i) = lambda(rows_[sz(i)]);
    q_(i) = slack(rows_[sz(i)]);
    if (lam_(i) > 0.0) warm_.push_back(static_cast<int>(i));
  }
  q_.noalias() -= S_ * lam_;
  // min 1/2 z' (S/t) z + q' z over z >= 0 is the complementarity problem of the header.
  const solve::QPResult& qp = qp_.solve(S_, -q_, warm_);
  if (qp.status != solve::QPStatus::Solved) return false;
  c_ = lam_ - qp.x;
  return true;
}

int ComplementaryCorrection::add_closed_rows(const RowSparse& K, const Eigen::VectorXd& slack, double t) {
  y_.noalias() = KG_.transpose() * c_;  // X^-1 K_rows' c on the measured DOFs
  change_.resize(ix(measured_.size()));
  std::vector<Index> closed;
  std::size_t next = 0;
  for (std::size_t k = 0; k < measured_.size(); ++k) {
    const Index r = measured_[k];
    double dr = 0.0;
    for (RowSparse::InnerIterator it(K, r); it; ++it) dr += it.value() * y_(local_[sz(it.col())]);
    change_(ix(k)) = dr / t;
    while (next < rows_.size() && rows_[next] < r) ++next;
    const bool in_rows = next < rows_.size() && rows_[next] == r;
    if (!in_rows && slack(r) - change_(ix(k)) < 0.0) closed.push_back(r);
  }
  if (closed.empty()) return 0;
  std::vector<Index> merged;
  std::merge(rows_.begin(), rows_.end(), closed.begin(), closed.end(), std::back_inserter(merged));
  rows_.swap(merged);
  return static_cast<int>(closed.size());
}

ComplementaryCorrection::Result ComplementaryCorrection::evaluate(const RowSparse& K, const Eigen::VectorXd& slack,
                                                                  const Eigen::VectorXd& lambda, double t) {
  Result out;
  if (local_.empty() || !(t > 0.0) || !gather_measured(K, lambda) || measured_.empty()) return out;
  if (gram_.size() == 0) form_gram();
  // The rows that carry a multiplier or cross their constraint, then those the correction closes.
  rows_.clear();
  for (Index r : measured_) {
    if (lambda(r) > 0.0 || slack(r) <= 0.0) rows_.push_back(r);
  }
  if (rows_.empty()) return out;
  int round = 0;
  do {
    if (++round > kMaxRounds) return out;
    form_schur(K, t);
    if (!solve_on_rows(slack, lambda)) return out;
  } while (add_closed_rows(K, slack, t) > 0);
  // A row outside the measured DOFs cannot be corrected: the correction must leave it open. Its
  // gap change is taken as at most the largest on the measured rows (the response to loads on
  // the contact zone is largest there).
  const double largest_change = change_.cwiseAbs().maxCoeff();
  std::size_t next = 0;
  for (Index r = 0; r < K.rows(); ++r) {
    if (next < measured_.size() && measured_[next] == r) {
      ++next;
      continue;
    }
    if (K.row(r).nonZeros() > 0 && slack(r) < largest_change) return out;
  }
  out.available = true;
  out.v_norm = std::sqrt(std::max(0.0, t * c_.dot(S_ * c_)));
  out.rows = static_cast<int>(rows_.size());
  return out;
}

}  // namespace contactrb::online
