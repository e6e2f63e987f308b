#include "contactrb/online/registered_basis.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::online {

using Eigen::Index;
using model::Registration;

Eigen::VectorXd row_coordinates(const model::ContactSurface& surface) {
  mesh::Mesh mesh;
  mesh.nodes = surface.reference_nodes;
  std::vector<mesh::Edge> slave_edges, master_edges;
  for (std::size_t k = 0; k + 1 < surface.slave.size(); ++k) slave_edges.push_back({surface.slave[k], surface.slave[k + 1]});
  for (std::size_t k = 0; k + 1 < surface.master.size(); ++k) master_edges.push_back({surface.master[k], surface.master[k + 1]});
  mesh.boundaries[mesh::kSlaveBoundary] = slave_edges;
  mesh.boundaries[mesh::kMasterBoundary] = master_edges;
  contact::ContactPair pair;
  pair.slave = surface.slave;
  pair.master = surface.master;
  const contact::ContactQuadrature q = contact::make_quadrature(mesh, pair, surface.discretization);
  std::vector<double> arc(surface.reference_nodes.size(), 0.0);
  double s = 0.0;
  for (std::size_t k = 0; k < surface.slave.size(); ++k) {
    if (k > 0) s += (mesh.nodes[sz(surface.slave[k])] - mesh.nodes[sz(surface.slave[k - 1])]).norm();
    arc[sz(surface.slave[k])] = s;
  }
  Eigen::VectorXd out(ix(q.center_node.size()));
  for (std::size_t r = 0; r < q.center_node.size(); ++r) out(ix(r)) = arc[sz(q.center_node[r])];
  return out;
}

namespace {

// One parameter: the training values sorted, linear interpolation, constant outside.
Eigen::Vector2d interpolate_1d(const Registration& reg, double x) {
  const Index P = reg.points.cols();
  std::vector<Index> order(sz(static_cast<int>(P)));
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return reg.points(0, a) < reg.points(0, b); });
  if (x <= reg.points(0, order.front())) return reg.support.col(order.front());
  if (x >= reg.points(0, order.back())) return reg.support.col(order.back());
  std::size_t k = 1;
  while (reg.points(0, order[k]) < x) ++k;
  const Index a = order[k - 1], b = order[k];
  const double t = (x - reg.points(0, a)) / (reg.points(0, b) - reg.points(0, a));
  return (1.0 - t) * reg.support.col(a) + t * reg.support.col(b);
}

// Several parameters: weighted linear least squares over the nearest points.
Eigen::Vector2d fit_nearest(const Registration& reg, const Eigen::VectorXd& x) {
  const Index p = reg.points.rows(), P = reg.points.cols();
  Eigen::VectorXd d2(P);
  for (Index j = 0; j < P; ++j) d2(j) = (reg.points.col(j) - x).squaredNorm();
  std::vector<Index> order(sz(static_cast<int>(P)));
  std::iota(order.begin(), order.end(), Index{0});
  const Index k = std::min<Index>(P, 2 * (p + 1));
  std::partial_sort(order.begin(), order.begin() + k, order.end(), [&](Index a, Index b) { return d2(a) < d2(b); });
  if (k < p + 1 || d2(order.front()) == 0.0) return reg.support.col(order.front());
  Eigen::MatrixXd A(k, p + 1);
  Eigen::MatrixXd b(k, 2);
  for (Index i = 0; i < k; ++i) {
    const Index j = order[sz(static_cast<int>(i))];
    const double w = 1.0 / d2(j);
    A(i, 0) = w;
    A.row(i).tail(p) = w * (reg.points.col(j) - x).transpose();
    b.row(i) = w * reg.support.col(j).transpose();
  }
  const Eigen::MatrixXd c = A.colPivHouseholderQr().solve(b);
  return c.row(0).transpose();  // the fit at x (local coordinates centred on x)
}

}  // namespace

Eigen::Vector2d predicted_support(const Registration& reg, const cases::Mu& mu) {
  require(mu.size() == reg.points.rows(), "predicted_support: mu has " + std::to_string(mu.size()) +
                                              " entries, the registration " + std::to_string(reg.points.rows()));
  const Eigen::VectorXd x = (mu - reg.point_offset).cwiseProduct(reg.point_scale);
  Eigen::Vector2d s = x.size() == 1 ? interpolate_1d(reg, x(0)) : fit_nearest(reg, x);
  // A fit may cross the ends over: keep the nearest training support's width at least.
  if (!(s(1) > s(0))) {
    Index best = 0;
    (reg.points.colwise() - x).colwise().squaredNorm().minCoeff(&best);
    s = reg.support.col(best);
  }
  return s;
}

void registered_basis(const Registration& reg, const Eigen::Vector2d& support, int R, Eigen::MatrixXd& Xi) {
  const Index rows = reg.row_coordinate.size(), n_g = reg.grid.size();
  Xi.setZero(rows, R);
  const double x0 = reg.grid(0), h = (reg.grid(n_g - 1) - reg.grid(0)) / static_cast<double>(n_g - 1);
  const double width = support(1) - support(0);
  for (Index r = 0; r < rows; ++r) {
    const double t = ((reg.row_coordinate(r) - support(0)) / width - x0) / h;
    if (!(t >= 0.0 && t <= static_cast<double>(n_g - 1))) continue;  // outside the grid: 0
    const Index i = std::min<Index>(static_cast<Index>(t), n_g - 2);
    const double a = t - static_cast<double>(i);
    Xi.row(r) = (1.0 - a) * reg.generators.row(i).head(R) + a * reg.generators.row(i + 1).head(R);
  }
}

Eigen::MatrixXd dual_basis(const model::ReducedReconstruction& rec, const cases::Mu& mu, int R) {
  if (rec.registration.empty()) return rec.Xi.leftCols(R);
  Eigen::MatrixXd Xi;
  registered_basis(rec.registration, predicted_support(rec.registration, mu), R, Xi);
  return Xi;
}

}  // namespace contactrb::online
