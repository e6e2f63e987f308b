#include "contactrb/online/online_magic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/segment_hit.hpp"

namespace contactrb::online {

using model::ContactSurface;

namespace {
using Vec2 = Eigen::Vector2d;
using WRow = Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator;
inline std::size_t sz(int i) { return static_cast<std::size_t>(i); }
// ProjectionOptions::end_tolerance (projection.hpp), the default project_slave_nodes uses.
constexpr double kEndTolerance = 1e-10;

// The same clamped segment distance as project_slave_nodes, so the same segment wins.
using contact::closest_on_segment;
using Hit = contact::SegmentHit;
}  // namespace

void MagicPointEvaluator::setup(const ContactSurface& surface, const std::vector<int>& kappa_row,
                                const std::vector<int>& kappa_dof, const std::vector<int>& gamma_row,
                                const Eigen::MatrixXd& Theta_c) {
  master_ = surface.master;
  slave_chain_ = surface.slave;
  closed_ = master_.size() > 2 && master_.front() == master_.back();
  require(master_.size() >= 2, "OnlineSolver: the master chain has " + std::to_string(master_.size()) +
                                   " node(s); at least 2 are needed");
  kappa_row_ = kappa_row;
  kappa_dof_ = kappa_dof;
  gamma_row_ = gamma_row;
  Theta_c_ = Theta_c;
  node_slot_.assign(surface.reference_nodes.size(), -1);
  pattern_.clear();
  y_.resize(master_.size());
  y_normal_.resize(master_.size());
  y_normal_done_.assign(master_.size(), 0);
  segment_normal_.resize(master_.size());
  segment_normal_done_.assign(master_.size(), 0);
}

void MagicPointEvaluator::rebuild(const contact::ContactQuadrature& q) {
  pattern_.clear();
  slave_position_.clear();
  for (const std::vector<int>* rows : {&kappa_row_, &gamma_row_}) {
    for (int r : *rows) {
      for (WRow it(q.W, r); it; ++it) {
        pattern_.push_back(static_cast<int>(it.col()));
        slave_position_.push_back(static_cast<int>(it.col()));
      }
      pattern_.push_back(-1);  // row separator
    }
  }
  std::sort(slave_position_.begin(), slave_position_.end());
  slave_position_.erase(std::unique(slave_position_.begin(), slave_position_.end()), slave_position_.end());
  slave_node_.clear();
  for (int s : slave_position_) slave_node_.push_back(slave_chain_[sz(s)]);
  // Used nodes: the master chain (a closed chain lists its first node twice), then the slaves.
  std::fill(node_slot_.begin(), node_slot_.end(), -1);
  used_node_.clear();
  auto use = [&](int v) {
    if (node_slot_[sz(v)] < 0) {
      node_slot_[sz(v)] = static_cast<int>(used_node_.size());
      used_node_.push_back(v);
    }
  };
  for (int v : master_) use(v);
  master_slots_ = static_cast<int>(used_node_.size());
  for (int v : slave_node_) use(v);
  const int n_used = static_cast<int>(used_node_.size());
  Theta_r_.resize(2 * n_used, Theta_c_.cols());
  for (int i = 0; i < n_used; ++i) {
    Theta_r_.row(2 * i) = Theta_c_.row(2 * used_node_[sz(i)]);
    Theta_r_.row(2 * i + 1) = Theta_c_.row(2 * used_node_[sz(i)] + 1);
  }
  if (V_.size() > 0) ThetaV_r_.noalias() = Theta_r_ * V_;
  X_.resize(sz(n_used));
  lift_r_.resize(2 * n_used);
  w_r_.resize(2 * n_used);
  projection_.resize(slave_node_.size());
}

void MagicPointEvaluator::prepare(const std::vector<Eigen::Vector2d>& nodes, const contact::ContactQuadrature& q,
                                  const Eigen::VectorXd& lift_mu) {
  // The W pattern does not depend on mu (make_quadrature: only the values do); rebuild the
  // restriction only when it differs from the one in use.
  bool same = !pattern_.empty();
  std::size_t p = 0;
  for (const std::vector<int>* rows : {&kappa_row_, &gamma_row_}) {
    for (int r : *rows) {
      for (WRow it(q.W, r); same && it; ++it) same = p < pattern_.size() && pattern_[p++] == static_cast<int>(it.col());
      same = same && p < pattern_.size() && pattern_[p++] == -1;
    }
  }
  if (!same || p != pattern_.size()) rebuild(q);

  for (std::size_t i = 0; i < used_node_.size(); ++i) {
    const int v = used_node_[i];
    X_[i] = nodes[sz(v)];
    lift_r_.segment<2>(2 * static_cast<Eigen::Index>(i)) = lift_mu.segment<2>(2 * v);
  }
  // Position of a slave chain entry among the restricted slaves (they are few: linear search).
  auto local = [&](int s) {
    return static_cast<int>(std::lower_bound(slave_position_.begin(), slave_position_.end(), s) - slave_position_.begin());
  };
  auto terms = [&](const std::vector<int>& rows, std::vector<Term>& out, std::vector<int>& start) {
    out.clear();
    start.clear();
    for (int r : rows) {
      start.push_back(static_cast<int>(out.size()));
      for (WRow it(q.W, r); it; ++it) out.push_back({local(static_cast<int>(it.col())), it.value()});
    }
    start.push_back(static_cast<int>(out.size()));
  };
  terms(kappa_row_, kappa_terms_, kappa_start_);
  terms(gamma_row_, gamma_terms_, gamma_start_);
  active_.resize(gamma_row_.size());
  for (std::size_t i = 0; i < active_.size(); ++i) active_[i] = static_cast<int>(i);
  slave_needed_.assign(slave_node_.size(), 1);
}

void MagicPointEvaluator::select_rows(const std::vector<int>& rows) {
  active_ = rows;
  slave_needed_.assign(slave_node_.size(), 0);
  for (const Term& term : kappa_terms_) slave_needed_[sz(term.slave)] = 1;
  for (int i : active_) {
    require(i >= 0 && sz(i) < gamma_row_.size(), "MagicPointEvaluator::select_rows: row outside the gamma rows");
    for (int t = gamma_start_[sz(i)]; t < gamma_start_[sz(i) + 1]; ++t) slave_needed_[sz(gamma_terms_[sz(t)].slave)] = 1;
  }
}

Vec2 MagicPointEvaluator::segment_normal(int k) const {
  const Vec2 e = y_[sz(k + 1)] - y_[sz(k)];
  const double len = e.norm();
  return {e.y() / len, -e.x() / len};  // body on the left: outward (dy, -dx)/|e| (master_polyline.cpp)
}

// master_polyline.cpp: interior vertices average their two segments, the ends of an open chain
// take their only segment's normal, a closed chain wraps (vertex 0 == vertex M).
Vec2 MagicPointEvaluator::vertex_normal(int j) {
  const int M = static_cast<int>(master_.size()) - 1;
  auto average = [&](int left, int right) {
    const Vec2 nl = step_segment_normal(left);
    const Vec2 nr = step_segment_normal(right);
    if (nl == nr) return nl;
    const Vec2 sum = nl + nr;
    const double len = sum.norm();
    return len > 0.0 ? Vec2(sum / len) : nl;
  };
  if (j > 0 && j < M) return average(j - 1, j);
  if (closed_) return average(M - 1, 0);
  return step_segment_normal(j == 0 ? 0 : M - 1);
}

const Vec2& MagicPointEvaluator::step_vertex_normal(int j) {
  if (!y_normal_done_[sz(j)]) {
    y_normal_[sz(j)] = vertex_normal(j);
    y_normal_done_[sz(j)] = 1;
  }
  return y_normal_[sz(j)];
}

const Vec2& MagicPointEvaluator::step_segment_normal(int k) {
  if (!segment_normal_done_[sz(k)]) {
    segment_normal_[sz(k)] = segment_normal(k);
    segment_normal_done_[sz(k)] = 1;
  }
  return segment_normal_[sz(k)];
}

// The lexicographic minimum of (squared distance, segment index) over every master segment, as
// the all-pairs search of project_slave_nodes, visiting only the blocks whose box is not
// farther than the best hit so far. The box bound is exact in floating point
// (closest_on_segment clamps into the segment's box), so the answer is the all-pairs one.
namespace {
double box_distance2(const Vec2& x, const Vec2& lo, const Vec2& hi) { return (x - x.cwiseMax(lo).cwiseMin(hi)).squaredNorm(); }
}  // namespace

// The blocks of one group: the nearest first, then those not farther than the best hit (ties
// included, so that the lowest segment index of equally near ones wins as in a full scan).
void MagicPointEvaluator::scan_group(const Vec2& x, int group, Hit& best) {
  const int M = static_cast<int>(master_.size()) - 1;
  const int b0 = group * kGroupBlocks, b1 = std::min(static_cast<int>(block_min_.size()), b0 + kGroupBlocks);
  int first = b0;
  for (int b = b0; b < b1; ++b) {
    block_bound_[sz(b)] = box_distance2(x, block_min_[sz(b)], block_max_[sz(b)]);
    if (block_bound_[sz(b)] < block_bound_[sz(first)]) first = b;
  }
  auto scan = [&](int b) {
    const int k1 = std::min(M, (b + 1) * kBlockSegments);
    for (int k = b * kBlockSegments; k < k1; ++k) {
      const Hit h = closest_on_segment(y_[sz(k)], y_[sz(k + 1)], k, x);
      if (h.d2 < best.d2 || (h.d2 == best.d2 && h.segment < best.segment)) best = h;
    }
  };
  if (block_bound_[sz(first)] <= best.d2) scan(first);
  for (int b = b0; b < b1; ++b) {
    if (b != first && block_bound_[sz(b)] <= best.d2) scan(b);
  }
}

contact::SegmentHit MagicPointEvaluator::nearest_segment(const Vec2& x) {
  const int num_groups = static_cast<int>(group_min_.size());
  int first = 0;
  for (int g = 0; g < num_groups; ++g) {
    group_bound_[sz(g)] = box_distance2(x, group_min_[sz(g)], group_max_[sz(g)]);
    if (group_bound_[sz(g)] < group_bound_[sz(first)]) first = g;
  }
  Hit best;
  scan_group(x, first, best);
  for (int g = 0; g < num_groups; ++g) {
    if (g != first && group_bound_[sz(g)] <= best.d2) scan_group(x, g, best);
  }
  return best;
}

double MagicPointEvaluator::k_entry(const Projection& p, int slave_node, int dof) const {
  // (27): k(w; v)_s = ((1 - xi) v_a + xi v_b - v_s) . n2; zero row for a non-candidate.
  if (!p.candidate) return 0.0;
  const int node = dof / 2, c = dof % 2;
  double v = 0.0;
  if (p.a == node) v += (1.0 - p.xi) * p.normal(c);
  if (p.b == node) v += p.xi * p.normal(c);
  if (slave_node == node) v -= p.normal(c);
  return v;
}

void MagicPointEvaluator::project(const Eigen::VectorXd& u_hat) {
  // The displacement of the master chain and of the slave nodes the selected rows need.
  const Eigen::Index m = 2 * static_cast<Eigen::Index>(master_slots_);
  w_r_.head(m) = lift_r_.head(m);
  w_r_.head(m).noalias() += Theta_r_.topRows(m) * u_hat;
  bool finite = w_r_.head(m).allFinite();
  for (std::size_t l = 0; l < slave_node_.size(); ++l) {
    const int slot = node_slot_[sz(slave_node_[l])];
    if (!slave_needed_[l] || slot < master_slots_) continue;
    w_r_.segment<2>(2 * slot) = lift_r_.segment<2>(2 * slot);
    w_r_.segment<2>(2 * slot).noalias() += Theta_r_.middleRows<2>(2 * slot) * u_hat;
    finite = finite && w_r_.segment<2>(2 * slot).allFinite();
  }
  if (!finite) throw Error("OnlineSolver: the contact-surface displacement is not finite");
  const int M = static_cast<int>(master_.size()) - 1;  // segments
  for (int j = 0; j <= M; ++j) {
    const int slot = node_slot_[sz(master_[sz(j)])];
    y_[sz(j)] = X_[sz(slot)] + w_r_.segment<2>(2 * slot);
  }
  std::fill(y_normal_done_.begin(), y_normal_done_.end(), 0);
  std::fill(segment_normal_done_.begin(), segment_normal_done_.end(), 0);
  for (int k = 0; k < M; ++k) {
    if (!((y_[sz(k + 1)] - y_[sz(k)]).squaredNorm() > 0.0)) {  // norm() > 0 without the square root
      throw Error("project_slave_nodes: deformed master segment " + std::to_string(k) + " (nodes " +
                  std::to_string(master_[sz(k)]) + ", " + std::to_string(master_[sz(k + 1)]) +
                  ") has zero length; its normal is undefined");
    }
  }
  // Bounding boxes of the blocks of kBlockSegments consecutive deformed master segments.
  const int num_blocks = (M + kBlockSegments - 1) / kBlockSegments;
  block_min_.resize(sz(num_blocks));
  block_max_.resize(sz(num_blocks));
  block_bound_.resize(sz(num_blocks));
  for (int b = 0; b < num_blocks; ++b) {
    const int k1 = std::min(M, (b + 1) * kBlockSegments);
    Vec2 mn = y_[sz(b * kBlockSegments)], mx = mn;
    for (int j = b * kBlockSegments + 1; j <= k1; ++j) {
      mn = mn.cwiseMin(y_[sz(j)]);
      mx = mx.cwiseMax(y_[sz(j)]);
    }
    block_min_[sz(b)] = mn;
    block_max_[sz(b)] = mx;
  }
  const int num_groups = (num_blocks + kGroupBlocks - 1) / kGroupBlocks;
  group_min_.resize(sz(num_groups));
  group_max_.resize(sz(num_groups));
  group_bound_.resize(sz(num_groups));
  for (int g = 0; g < num_groups; ++g) {
    const int b1 = std::min(num_blocks, (g + 1) * kGroupBlocks);
    group_min_[sz(g)] = block_min_[sz(g * kGroupBlocks)];
    group_max_[sz(g)] = block_max_[sz(g * kGroupBlocks)];
    for (int b = g * kGroupBlocks + 1; b < b1; ++b) {
      group_min_[sz(g)] = group_min_[sz(g)].cwiseMin(block_min_[sz(b)]);
      group_max_[sz(g)] = group_max_[sz(g)].cwiseMax(block_max_[sz(b)]);
    }
  }
  for (std::size_t l = 0; l < slave_node_.size(); ++l) {
    if (!slave_needed_[l]) continue;
    const int slot = node_slot_[sz(slave_node_[l])];
    const Vec2& X = X_[sz(slot)];
    const Vec2 x = X + w_r_.segment<2>(2 * slot);
    const Hit best = nearest_segment(x);
    // As project_slave_nodes: finite coordinates whose squared distances overflow leave no
    // segment at a finite distance, and the search keeps its initial segment -1.
    if (best.segment < 0 || !std::isfinite(best.d2)) {
      throw Error("OnlineSolver: the distance from slave node " + std::to_string(slave_node_[l]) +
                  " to the master boundary is not finite (positions overflow double precision when squared)");
    }
    Projection& p = projection_[l];
    const int k = best.segment;
    p.a = master_[sz(k)];
    p.b = master_[sz(k + 1)];
    p.xi = best.xi;
    // MasterPolyline::normal_at: the continuous normal field.
    const Vec2 na = step_vertex_normal(k), nb = step_vertex_normal(k + 1);
    if (p.xi == 0.0) {
      p.normal = na;
    } else if (p.xi == 1.0 || na == nb) {
      p.normal = nb;
    } else {
      const Vec2 n = (1.0 - p.xi) * na + p.xi * nb;
      const double len = n.norm();
      p.normal = len > 0.0 ? Vec2(n / len) : step_segment_normal(k);
    }
    const Vec2 rho = (1.0 - p.xi) * X_[sz(node_slot_[sz(p.a)])] + p.xi * X_[sz(node_slot_[sz(p.b)])];
    const bool before_start = k == 0 && best.t_raw < -kEndTolerance;
    const bool after_end = k == M - 1 && best.t_raw > 1.0 + kEndTolerance;
    p.candidate = closed_ || !(before_start || after_end);
    // (28): g = (X_s - rho) . n2; a non-candidate: its distance (never binds).
    p.g = p.candidate ? (X - rho).dot(p.normal) : std::sqrt(best.d2);
  }
}

double MagicPointEvaluator::gamma_term(const Term& term) const {
  const Projection& p = projection_[sz(term.slave)];
  double k_lift = 0.0;
  if (p.candidate) {
    const auto lift = [&](int node) { return lift_r_.segment<2>(2 * node_slot_[sz(node)]); };
    k_lift = p.normal.dot((1.0 - p.xi) * lift(p.a) + p.xi * lift(p.b) - lift(slave_node_[sz(term.slave)]));
  }
  return term.weight * (p.g - k_lift);
}

void MagicPointEvaluator::evaluate_rows(const Eigen::VectorXd& u_hat, RowMatrix& K_Theta, Eigen::VectorXd& gamma) {
  rows(u_hat, &K_Theta, gamma, nullptr);
}

void MagicPointEvaluator::evaluate_solved_rows(const Eigen::VectorXd& u_hat, Eigen::VectorXd& gamma, RowMatrix& K_E) {
  require(whitening_ != nullptr, "MagicPointEvaluator: evaluate_solved_rows before prepare_solved");
  rows(u_hat, nullptr, gamma, &K_E);
}

void MagicPointEvaluator::evaluate_rows(const Eigen::VectorXd& u_hat, RowMatrix& K_Theta, Eigen::VectorXd& gamma,
                                        RowMatrix& K_E) {
  require(whitening_ != nullptr, "MagicPointEvaluator: evaluate_rows with K_E before prepare_solved");
  rows(u_hat, &K_Theta, gamma, &K_E);
}

void MagicPointEvaluator::set_whitening_basis(const Eigen::MatrixXd& V) {
  V_ = V;
  if (Theta_r_.size() > 0) ThetaV_r_.noalias() = Theta_r_ * V_;
}

void MagicPointEvaluator::prepare_solved(const AffineWhitening& whitening) {
  whitening_ = &whitening;
  ThetaL_r_.resize(Theta_r_.rows(), Theta_r_.cols());
  solved_.assign(used_node_.size(), 0);
}

void MagicPointEvaluator::solve_touched_rows() {
  // The nodes the candidate rows touch and not solved yet, solved together (one blocked
  // triangular solve pair, not one per node).
  pending_.clear();
  const auto need = [&](int node) {
    const int slot = node_slot_[sz(node)];
    if (!solved_[sz(slot)]) {
      solved_[sz(slot)] = 1;
      pending_.push_back(slot);
    }
  };
  for (int i : active_) {
    for (int t = gamma_start_[sz(i)]; t < gamma_start_[sz(i) + 1]; ++t) {
      const Term& term = gamma_terms_[sz(t)];
      const Projection& p = projection_[sz(term.slave)];
      if (!p.candidate) continue;
      need(p.a);
      need(p.b);
      need(slave_node_[sz(term.slave)]);
    }
  }
  if (pending_.empty()) return;
  if (whitening_->diagonal()) {  // Theta_c L^-T = Theta_c V diag(d^-1/2)
    const auto scale = whitening_->scale().transpose().array();
    for (const int slot : pending_) {
      ThetaL_r_.row(2 * slot).array() = ThetaV_r_.row(2 * slot).array() * scale;
      ThetaL_r_.row(2 * slot + 1).array() = ThetaV_r_.row(2 * slot + 1).array() * scale;
    }
    return;
  }
  const Eigen::Index m = static_cast<Eigen::Index>(pending_.size());
  solve_work_.resize(Theta_r_.cols(), 2 * m);
  for (Eigen::Index k = 0; k < m; ++k) {
    solve_work_.col(2 * k) = Theta_r_.row(2 * pending_[sz(static_cast<int>(k))]).transpose();
    solve_work_.col(2 * k + 1) = Theta_r_.row(2 * pending_[sz(static_cast<int>(k))] + 1).transpose();
  }
  whitening_->cholesky().matrixL().solveInPlace(solve_work_);  // L^-1 Theta_r': one triangular solve per column
  for (Eigen::Index k = 0; k < m; ++k) {
    ThetaL_r_.row(2 * pending_[sz(static_cast<int>(k))]) = solve_work_.col(2 * k).transpose();
    ThetaL_r_.row(2 * pending_[sz(static_cast<int>(k))] + 1) = solve_work_.col(2 * k + 1).transpose();
  }
}

void MagicPointEvaluator::rows(const Eigen::VectorXd& u_hat, RowMatrix* K_Theta, Eigen::VectorXd& gamma,
                               RowMatrix* K_E) {
  project(u_hat);
  if (K_Theta != nullptr) K_Theta->setZero();
  if (K_E != nullptr) {
    K_E->setZero(static_cast<Eigen::Index>(active_.size()), Theta_r_.cols());
    solve_touched_rows();
  }
  for (std::size_t j = 0; j < active_.size(); ++j) {
    double v = 0.0;
    const Eigen::Index row = static_cast<Eigen::Index>(j);
    const std::size_t i = sz(active_[j]);
    for (int t = gamma_start_[i]; t < gamma_start_[i + 1]; ++t) {
      const Term& term = gamma_terms_[sz(t)];
      const Projection& p = projection_[sz(term.slave)];
      v += gamma_term(term);
      if (!p.candidate) continue;
      // (27): the row k(w; .)_s = ((1 - xi) e_a + xi e_b - e_s) . n2, applied to Theta.
      const auto add = [&](int node, double c) {
        const int slot = node_slot_[sz(node)];
        const double cx = c * p.normal.x(), cy = c * p.normal.y();
        if (K_Theta != nullptr) {
          K_Theta->row(row).noalias() += cx * Theta_r_.row(2 * slot) + cy * Theta_r_.row(2 * slot + 1);
        }
        if (K_E != nullptr) K_E->row(row).noalias() += cx * ThetaL_r_.row(2 * slot) + cy * ThetaL_r_.row(2 * slot + 1);
      };
      add(p.a, term.weight * (1.0 - p.xi));
      add(p.b, term.weight * p.xi);
      add(slave_node_[sz(term.slave)], -term.weight);
    }
    gamma(row) = v;
  }
}

void MagicPointEvaluator::evaluate_slack(const Eigen::VectorXd& u_hat, const Eigen::VectorXd& lambda,
                                         Eigen::VectorXd& slack, Eigen::VectorXd& load) {
  project(u_hat);
  load.setZero();
  const auto w = [&](int node) { return w_r_.segment<2>(2 * node_slot_[sz(node)]); };
  for (std::size_t j = 0; j < active_.size(); ++j) {
    const Eigen::Index row = static_cast<Eigen::Index>(j);
    const std::size_t i = sz(active_[j]);
    double v = 0.0;
    for (int t = gamma_start_[i]; t < gamma_start_[i + 1]; ++t) {
      const Term& term = gamma_terms_[sz(t)];
      const Projection& p = projection_[sz(term.slave)];
      const int s = slave_node_[sz(term.slave)];
      if (!p.candidate) {  // a zero K row: the slack is the gap (the distance)
        v += term.weight * p.g;
        continue;
      }
      // (28) - (27) at w: g - ((1 - xi) w_a + xi w_b - w_s) . n2.
      v += term.weight * (p.g - p.normal.dot((1.0 - p.xi) * w(p.a) + p.xi * w(p.b) - w(s)));
      const double c = lambda(row) * term.weight;
      if (c == 0.0) continue;
      load.segment<2>(2 * p.a) += (c * (1.0 - p.xi)) * p.normal;
      load.segment<2>(2 * p.b) += (c * p.xi) * p.normal;
      load.segment<2>(2 * s) -= c * p.normal;
    }
    slack(row) = v;
  }
}

void MagicPointEvaluator::assemble_rows(Eigen::Index num_dofs, Eigen::SparseMatrix<double, Eigen::RowMajor>& K) const {
  // Row j = sum over the row's slave terms of weight * k_pt(s) (27), merged per DOF in increasing
  // order; the master entries of a zero barycentric weight are left out, as project_slave_nodes does.
  K.resize(static_cast<Eigen::Index>(active_.size()), num_dofs);
  K.reserve(Eigen::VectorXi::Constant(K.rows(), 6));
  std::vector<std::pair<int, double>> entries;
  for (std::size_t j = 0; j < active_.size(); ++j) {
    const std::size_t i = sz(active_[j]);
    entries.clear();
    for (int t = gamma_start_[i]; t < gamma_start_[i + 1]; ++t) {
      const Term& term = gamma_terms_[sz(t)];
      const Projection& p = projection_[sz(term.slave)];
      if (!p.candidate) continue;
      const auto add = [&](int node, double phi) {
        for (int c = 0; c < 2; ++c) entries.emplace_back(2 * node + c, term.weight * (phi * p.normal(c)));
      };
      if (1.0 - p.xi != 0.0) add(p.a, 1.0 - p.xi);
      if (p.xi != 0.0) add(p.b, p.xi);
      add(slave_node_[sz(term.slave)], -1.0);
    }
    std::sort(entries.begin(), entries.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t e = 0; e < entries.size();) {
      double v = 0.0;
      const int dof = entries[e].first;
      for (; e < entries.size() && entries[e].first == dof; ++e) v += entries[e].second;
      K.insert(static_cast<Eigen::Index>(j), dof) = v;
    }
  }
  K.makeCompressed();
}

void MagicPointEvaluator::evaluate(const Eigen::VectorXd& u_hat, Eigen::VectorXd& kappa_hat,
                                   Eigen::VectorXd& gamma_hat) {
  project(u_hat);
  for (std::size_t i = 0; i < kappa_row_.size(); ++i) {
    double v = 0.0;
    for (int t = kappa_start_[i]; t < kappa_start_[i + 1]; ++t) {
      const Term& term = kappa_terms_[sz(t)];
      v += term.weight * k_entry(projection_[sz(term.slave)], slave_node_[sz(term.slave)], kappa_dof_[i]);
    }
    kappa_hat(static_cast<Eigen::Index>(i)) = v;
  }
  // gamma = g - K u_D(mu) (the lift's contact term moved into the gap).
  for (std::size_t i = 0; i < gamma_row_.size(); ++i) {
    double v = 0.0;
    for (int t = gamma_start_[i]; t < gamma_start_[i + 1]; ++t) v += gamma_term(gamma_terms_[sz(t)]);
    gamma_hat(static_cast<Eigen::Index>(i)) = v;
  }
}

}  // namespace contactrb::online
