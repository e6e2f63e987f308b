#include "contactrb/fem/floating_bodies.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cstddef>

namespace contactrb::fem {

namespace {
// A held motion moves the constrained DOFs by O(1) (motions scaled to unit size on the body):
// its eigenvalue of the Gram matrix below is at least about 1; a free one is round-off.
constexpr double kFreeMotion = 1e-10;
}  // namespace

template <int Dim>
std::vector<int> floating_bodies(const mesh::SimplexMesh<Dim>& mesh, const DofMap& dofs) {
  constexpr int kModes = Dim == 2 ? 3 : 6;
  using Point = typename mesh::SimplexMesh<Dim>::Point;
  using Gram = Eigen::Matrix<double, kModes, kModes>;
  const int num_bodies = mesh.num_bodies();
  std::vector<int> node_body(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (std::size_t c = 0; c < mesh.cells().size(); ++c) {
    for (const int v : mesh.cells()[c]) node_body[static_cast<std::size_t>(v)] = mesh.body[c];
  }
  // Centroid and size of each body: the rotations about the centroid, scaled to unit size.
  std::vector<Point> center(static_cast<std::size_t>(num_bodies), Point::Zero());
  std::vector<int> count(static_cast<std::size_t>(num_bodies), 0);
  std::vector<double> size(static_cast<std::size_t>(num_bodies), 0.0);
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const int b = node_body[static_cast<std::size_t>(v)];
    if (b < 0) continue;
    center[static_cast<std::size_t>(b)] += mesh.nodes[static_cast<std::size_t>(v)];
    ++count[static_cast<std::size_t>(b)];
  }
  for (int b = 0; b < num_bodies; ++b) {
    if (count[static_cast<std::size_t>(b)] > 0) center[static_cast<std::size_t>(b)] /= count[static_cast<std::size_t>(b)];
  }
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const int b = node_body[static_cast<std::size_t>(v)];
    if (b < 0) continue;
    const double d = (mesh.nodes[static_cast<std::size_t>(v)] - center[static_cast<std::size_t>(b)]).norm();
    size[static_cast<std::size_t>(b)] = std::max(size[static_cast<std::size_t>(b)], d);
  }
  // G_b = sum over b's constrained DOFs of m m', m the motions' values at that DOF.
  std::vector<Gram> gram(static_cast<std::size_t>(num_bodies), Gram::Zero());
  for (const int d : dofs.constrained_dofs()) {
    const int v = d / Dim, comp = d % Dim;
    const int b = node_body[static_cast<std::size_t>(v)];
    if (b < 0) continue;
    const double L = size[static_cast<std::size_t>(b)] > 0.0 ? size[static_cast<std::size_t>(b)] : 1.0;
    const Point x = (mesh.nodes[static_cast<std::size_t>(v)] - center[static_cast<std::size_t>(b)]) / L;
    Eigen::Matrix<double, kModes, 1> m = Eigen::Matrix<double, kModes, 1>::Zero();
    m(comp) = 1.0;  // the translation along comp
    if constexpr (Dim == 2) {
      m(2) = comp == 0 ? -x.y() : x.x();  // (-y, x): the rotation
    } else {
      // Rotation about axis k: e_k x x; its component comp.
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d e = Eigen::Vector3d::Zero();
        e(k) = 1.0;
        m(3 + k) = e.cross(Eigen::Vector3d(x.x(), x.y(), x.z()))(comp);
      }
    }
    gram[static_cast<std::size_t>(b)].noalias() += m * m.transpose();
  }
  std::vector<int> floating;
  for (int b = 0; b < num_bodies; ++b) {
    if (count[static_cast<std::size_t>(b)] == 0) continue;
    const Eigen::SelfAdjointEigenSolver<Gram> eig(gram[static_cast<std::size_t>(b)], Eigen::EigenvaluesOnly);
    if (!(eig.eigenvalues()(0) > kFreeMotion)) floating.push_back(b);
  }
  return floating;
}

template std::vector<int> floating_bodies(const mesh::SimplexMesh<2>&, const DofMap&);
template std::vector<int> floating_bodies(const mesh::SimplexMesh<3>&, const DofMap&);

}  // namespace contactrb::fem
