#include "contactrb/online/complementary_correction.hpp"

#include <algorithm>
#include <cmath>

#include "contactrb/common/index_cast.hpp"

namespace contactrb::online {

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

bool ComplementaryCorrection::gather_rows(const RowSparse& K, const Eigen::VectorXd& lambda) {
  rows_.clear();
  for (Index r = 0; r < K.rows(); ++r) {
    bool measured = K.row(r).nonZeros() > 0;
    for (RowSparse::InnerIterator it(K, r); it && measured; ++it) measured = local_[sz(it.col())] >= 0;
    if (measured) {
      rows_.push_back(r);
    } else if (lambda(r) != 0.0) {
      return false;
    }
  }
  return true;
}

void ComplementaryCorrection::form_schur(const RowSparse& K) {
  const Index m = ix(rows_.size());
  KG_.setZero(m, gram_.cols());
  for (Index i = 0; i < m; ++i) {
    for (RowSparse::InnerIterator it(K, rows_[sz(i)]); it; ++it) {
      KG_.row(i).noalias() += it.value() * gram_.row(local_[sz(it.col())]);
    }
  }
  S_.setZero(m, m);
  for (Index j = 0; j < m; ++j) {
    for (RowSparse::InnerIterator it(K, rows_[sz(j)]); it; ++it) {
      S_.col(j).noalias() += it.value() * KG_.col(local_[sz(it.col())]);
    }
  }
  for (Index j = 0; j < m; ++j) {
    for (Index i = j + 1; i < m; ++i) S_(i, j) = S_(j, i) = 0.5 * (S_(i, j) + S_(j, i));
  }
}

ComplementaryCorrection::Result ComplementaryCorrection::evaluate(const RowSparse& K, const Eigen::VectorXd& slack,
                                                                  const Eigen::VectorXd& lambda, double t) {
  Result out;
  if (local_.empty() || !(t > 0.0) || !gather_rows(K, lambda) || rows_.empty()) return out;
  if (gram_.size() == 0) form_gram();
  form_schur(K);
  const Index m = ix(rows_.size());
  lam_.resize(m);
  q_.resize(m);
  warm_.clear();
  for (Index i = 0; i < m; ++i) {
    lam_(i) = lambda(rows_[sz(i)]);
    q_(i) = slack(rows_[sz(i)]);
    if (lam_(i) > 0.0) warm_.push_back(static_cast<int>(i));
  }
  S_ /= t;
  q_.noalias() -= S_ * lam_;
  // min 1/2 z' (S/t) z + q' z over z >= 0 is the complementarity problem of the header.
  const solve::QPResult& qp = qp_.solve(S_, -q_, warm_);
  if (qp.status != solve::QPStatus::Solved) return out;
  c_ = lam_ - qp.x;
  Sc_.noalias() = S_ * c_;  // (S / t) c: the gap change of the correction on the measured rows
  // A row outside the measured DOFs cannot be corrected: the correction must leave it open. Its
  // gap change is taken as at most the largest on the measured rows (the response to loads on
  // the contact zone is largest there).
  const double largest_change = Sc_.cwiseAbs().maxCoeff();
  Index next = 0;
  for (Index r = 0; r < K.rows(); ++r) {
    if (next < m && rows_[sz(next)] == r) {
      ++next;
      continue;
    }
    if (K.row(r).nonZeros() > 0 && slack(r) < largest_change) return out;
  }
  out.available = true;
  out.v_norm = std::sqrt(std::max(0.0, t * c_.dot(Sc_)));
  out.rows = static_cast<int>(m);
  return out;
}

}  // namespace contactrb::online
