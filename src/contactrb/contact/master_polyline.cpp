#include "contactrb/contact/master_polyline.hpp"

#include <cstddef>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::contact {

using Vec2 = Eigen::Vector2d;

Vec2 MasterPolyline::normal_at(int k, double xi) const {
  const Vec2& na = vertex_normal[static_cast<std::size_t>(k)];
  const Vec2& nb = vertex_normal[static_cast<std::size_t>(k + 1)];
  if (xi == 0.0) return na;
  if (xi == 1.0 || na == nb) return nb;
  const Vec2 n = (1.0 - xi) * na + xi * nb;
  const double len = n.norm();
  return len > 0.0 ? Vec2(n / len) : normal[static_cast<std::size_t>(k)];
}

MasterPolyline deformed_master(const mesh::Mesh& mesh, const std::vector<int>& master, const Eigen::VectorXd& w) {
  MasterPolyline m;
  m.closed = master.size() > 2 && master.front() == master.back();
  m.y.reserve(master.size());
  for (int v : master) m.y.push_back(mesh.nodes[static_cast<std::size_t>(v)] + w.segment<2>(2 * v));
  m.abscissa.assign(1, 0.0);
  for (std::size_t k = 0; k + 1 < m.y.size(); ++k) {
    const Vec2 e = m.y[k + 1] - m.y[k];
    const double len = e.norm();
    if (!(len > 0.0)) {
      throw Error("project_slave_nodes: deformed master segment " + std::to_string(k) + " (nodes " +
                  std::to_string(master[k]) + ", " + std::to_string(master[k + 1]) +
                  ") has zero length; its normal is undefined");
    }
    m.normal.emplace_back(e.y() / len, -e.x() / len);  // body on the left: outward (dy, -dx)/|e|
    m.abscissa.push_back(m.abscissa.back() + len);
  }
  // Vertex normals: interior vertices average their two segments, the ends of an open chain
  // take their only segment's normal, a closed chain wraps (vertex 0 == vertex M).
  const int M = m.num_segments();
  const auto average = [&m](int left, int right) {
    const Vec2& nl = m.normal[static_cast<std::size_t>(left)];
    const Vec2& nr = m.normal[static_cast<std::size_t>(right)];
    if (nl == nr) return nl;  // flat: exactly the segment normal
    const Vec2 sum = nl + nr;
    const double len = sum.norm();
    return len > 0.0 ? Vec2(sum / len) : nl;  // anti-parallel segments (a fold): keep the first
  };
  m.vertex_normal.resize(static_cast<std::size_t>(M + 1));
  for (int j = 1; j < M; ++j) m.vertex_normal[static_cast<std::size_t>(j)] = average(j - 1, j);
  if (m.closed) {
    m.vertex_normal.front() = m.vertex_normal.back() = average(M - 1, 0);
  } else {
    m.vertex_normal.front() = m.normal.front();
    m.vertex_normal.back() = m.normal.back();
  }
  return m;
}

}  // namespace contactrb::contact
