#include "contactrb/online/complementary_correction.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "contactrb/common/index_cast.hpp"

namespace contactrb::online {

namespace {
// Rounds of the row set: each adds the measured rows the previous correction closed.
constexpr int kMaxRounds = 8;
}  // namespace

void ComplementaryCorrection::setup(const Eigen::MatrixXd& load_T, const std::vector<int>& exact_dofs,
                                    Eigen::Index n_c) {
  load_T_ = load_T;
  gram_.resize(0, 0);
  local_.assign(sz(n_c), -1);
  for (std::size_t k = 0; k < exact_dofs.size(); ++k) local_[sz(exact_dofs[k])] = static_cast<int>(k);
}

void ComplementaryCorrection::form_gram() {
  // Formed on first use: a model answered without the correction never pays the n_e^2 rank flops.
  gram_.noalias() = load_T_.transpose() * load_T_;
  load_T_.resize(0, 0);
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
  KG_.setZero(m, gram_.cols());
  for (Index i = 0; i < m; ++i) {
    for (RowSparse::InnerIterator it(K, rows_[sz(i)]); it; ++it) {
      KG_.row(i).noalias() += it.value() * gram_.col(local_[sz(it.col())]).transpose();  // gram_ is symmetric
    }
  }
  S_.setZero(m, m);
  for (Index j = 0; j < m; ++j) {
    for (RowSparse::InnerIterator it(K, rows_[sz(j)]); it; ++it) {
      S_.col(j).noalias() += (it.value() / t) * KG_.col(local_[sz(it.col())]);
    }
  }
  for (Index j = 0; j < m; ++j) {
    for (Index i = j + 1; i < m; ++i) S_(i, j) = S_(j, i) = 0.5 * (S_(i, j) + S_(j, i));
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
