#include "contactrb/offline/registration.hpp"

#include <algorithm>
#include <string>

#include "contactrb/cases/unit_box.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"
#include "contactrb/offline/cpg.hpp"
#include "contactrb/online/registered_basis.hpp"

namespace contactrb::offline {

using Eigen::Index;

namespace {

// A pressure below this fraction of its largest value is no contact (the QP's round-off).
constexpr double kActiveFraction = 1e-8;

// [s_left, s_right] of one pressure: half-way from its outermost active rows to the next row
// outwards (any row of the surface, kept or not), or the active row itself at a chain end.
Eigen::Vector2d support_of(const Eigen::VectorXd& lambda, const Eigen::VectorXd& s_kept, const std::vector<double>& s_all,
                           int p) {
  const double top = lambda.maxCoeff();
  require(top > 0.0, "offline: training point " + std::to_string(p) +
                         " has no contact pressure: the registered cone needs a contact support at every training point");
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) <= kActiveFraction * top) continue;
    lo = std::min(lo, s_kept(i));
    hi = std::max(hi, s_kept(i));
  }
  const auto below = std::lower_bound(s_all.begin(), s_all.end(), lo);
  const auto above = std::upper_bound(s_all.begin(), s_all.end(), hi);
  const double left = below == s_all.begin() ? lo : 0.5 * (lo + *(below - 1));
  const double right = above == s_all.end() ? hi : 0.5 * (hi + *above);
  require(right > left, "offline: training point " + std::to_string(p) + " has a contact support of zero width");
  return {left, right};
}

// lambda resampled at s = s_left + xi (s_right - s_left) on the grid: linear between the rows of
// the whole surface sorted by s (0 on the rows not kept), 0 beyond them.
Eigen::VectorXd registered_profile(const Eigen::VectorXd& lambda_rows, const std::vector<Index>& order,
                                   const Eigen::VectorXd& s_rows, const Eigen::Vector2d& support,
                                   const Eigen::VectorXd& grid) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(grid.size());
  std::size_t k = 1;
  for (Index g = 0; g < grid.size(); ++g) {
    const double s = support(0) + grid(g) * (support(1) - support(0));
    if (order.size() < 2 || s < s_rows(order.front()) || s > s_rows(order.back())) continue;
    while (k + 1 < order.size() && s_rows(order[k]) < s) ++k;
    const Index a = order[k - 1], b = order[k];
    const double h = s_rows(b) - s_rows(a);
    const double t = h > 0.0 ? (s - s_rows(a)) / h : 0.0;
    out(g) = (1.0 - t) * lambda_rows(a) + t * lambda_rows(b);
  }
  return out;
}

}  // namespace

RegistrationResult build_registration(const model::ContactSurface& surface, const std::vector<int>& kept,
                                      const Eigen::MatrixXd& Lambda, const Eigen::MatrixXd& training_mu,
                                      const std::vector<cases::ParameterSpec>& parameters,
                                      const DualConeSettings& settings) {
  const Index P = Lambda.cols(), p = training_mu.rows();
  require(Lambda.rows() == ix(kept.size()) && training_mu.cols() == P && p == ix(parameters.size()),
          "build_registration: the pressures, kept rows, training points and parameters disagree in size");
  const Eigen::VectorXd s_rows = online::row_coordinates(surface);
  RegistrationResult out;
  model::Registration& reg = out.registration;
  reg.row_coordinate.resize(ix(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i) reg.row_coordinate(ix(i)) = s_rows(kept[i]);
  std::vector<double> s_all(s_rows.data(), s_rows.data() + s_rows.size());
  std::sort(s_all.begin(), s_all.end());
  std::vector<Index> order(sz(s_rows.size()));  // every row of the surface, by s
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = ix(i);
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return s_rows(a) < s_rows(b); });
  Eigen::VectorXd lambda_rows = Eigen::VectorXd::Zero(s_rows.size());

  reg.grid = Eigen::VectorXd::LinSpaced(kRegistrationGridPoints, -kRegistrationMargin, 1.0 + kRegistrationMargin);
  reg.support.resize(2, P);
  Eigen::MatrixXd profiles(reg.grid.size(), P);
  for (Index j = 0; j < P; ++j) {
    reg.support.col(j) = support_of(Lambda.col(j), reg.row_coordinate, s_all, static_cast<int>(j));
    for (std::size_t i = 0; i < kept.size(); ++i) lambda_rows(kept[i]) = Lambda(ix(i), j);
    profiles.col(j) = registered_profile(lambda_rows, order, s_rows, reg.support.col(j), reg.grid);
  }
  const cases::UnitBox box = cases::unit_box(parameters);
  reg.point_offset = box.offset;
  reg.point_scale = box.scale;
  reg.points = box(training_mu);

  DualConeSettings cs = settings;
  cs.weights.resize(0);  // the grid's uniform L2 norm
  const int R_kept = static_cast<int>(kept.size());
  cs.greedy.max_size = cs.greedy.max_size < 0 ? R_kept : std::min(cs.greedy.max_size, R_kept);
  out.cone = build_cpg(profiles, cs);
  reg.generators = out.cone.generators.cwiseMax(0.0);
  return out;
}

}  // namespace contactrb::offline
