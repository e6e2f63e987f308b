#include "contactrb/contact/master_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb::contact {

namespace {

using Vec3 = Eigen::Vector3d;

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

// Interior angle of triangle f at its vertex i.
double corner_angle(const MasterSurface& m, int f, int i) {
  const auto& t = m.face[sz(f)];
  const Vec3& p = m.y[sz(t[sz(i)])];
  const Vec3 e1 = m.y[sz(t[sz((i + 1) % 3)])] - p, e2 = m.y[sz(t[sz((i + 2) % 3)])] - p;
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

// Vertex normals weighted by the triangle angles at the vertex (Thuermer-Wuethrich): unlike
// uniform or area weights they depend only on the surface around the vertex, not on how it is
// cut into triangles (splitting a triangle does not change them), which matters for the
// non-matching, graded meshes of contact. A vertex whose triangles are all coplanar gets
// exactly their normal; a vanishing sum (a fold) keeps the first triangle's normal.
void vertex_normals(MasterSurface& m) {
  const std::size_t V = m.y.size();
  std::vector<Vec3> sum(V, Vec3::Zero());
  std::vector<int> first(V, -1);
  std::vector<char> flat(V, 1);
  for (int f = 0; f < m.num_facets(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const int v = m.face[sz(f)][sz(i)];
      sum[sz(v)] += corner_angle(m, f, i) * m.normal[sz(f)];
      if (first[sz(v)] < 0) {
        first[sz(v)] = f;
      } else if (m.normal[sz(f)] != m.normal[sz(first[sz(v)])]) {
        flat[sz(v)] = 0;
      }
    }
  }
  m.vertex_normal.assign(V, Vec3::Zero());
  for (std::size_t v = 0; v < V; ++v) {
    if (first[v] < 0) continue;  // not on a master triangle
    const Vec3& n0 = m.normal[sz(first[v])];
    const double len = sum[v].norm();
    m.vertex_normal[v] = flat[v] ? n0 : len > 0.0 ? Vec3(sum[v] / len) : n0;
  }
}

void rim_geometry(MasterSurface& m, const ContactPair3& pair) {
  const std::size_t R = pair.master_rim.size();
  m.face_rim.assign(m.face.size(), {-1, -1, -1});
  m.rim_conormal.resize(R);
  m.rim_length.resize(R);
  std::vector<int> count(m.y.size() + 1, 0);
  for (std::size_t r = 0; r < R; ++r) {
    const auto [f, i] = pair.master_rim[r];
    m.face_rim[sz(f)][sz(i)] = static_cast<int>(r);
    const auto& t = m.face[sz(f)];
    const int a = t[sz((i + 1) % 3)], b = t[sz((i + 2) % 3)];
    const Vec3 e = m.y[sz(b)] - m.y[sz(a)];  // in the triangle's counter-clockwise order
    m.rim_length[r] = e.norm();
    m.rim_conormal[r] = e.cross(m.normal[sz(f)]).normalized();
    ++count[sz(a) + 1];
    ++count[sz(b) + 1];
  }
  for (std::size_t v = 0; v + 1 < count.size(); ++v) count[v + 1] += count[v];
  m.vertex_rim_start = count;
  m.vertex_rim.resize(2 * R);
  for (std::size_t r = 0; r < R; ++r) {
    const auto [f, i] = pair.master_rim[r];
    const auto& t = m.face[sz(f)];
    for (const int v : {t[sz((i + 1) % 3)], t[sz((i + 2) % 3)]}) m.vertex_rim[sz(count[sz(v)]++)] = static_cast<int>(r);
  }
}

}  // namespace

Vec3 MasterSurface::normal_at(int f, const Vec3& phi) const {
  const auto& t = face[sz(f)];
  for (int i = 0; i < 3; ++i) {
    if (phi(i) == 1.0) return vertex_normal[sz(t[sz(i)])];
  }
  const Vec3 n = phi(0) * vertex_normal[sz(t[0])] + phi(1) * vertex_normal[sz(t[1])] + phi(2) * vertex_normal[sz(t[2])];
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : normal[sz(f)];
}

MasterSurface deformed_master(const mesh::Mesh3& mesh, const ContactPair3& pair, const Eigen::VectorXd& w) {
  MasterSurface m;
  m.y.reserve(pair.master.size());
  for (int v : pair.master) m.y.push_back(mesh.nodes[sz(v)] + w.segment<3>(3 * v));
  m.face = pair.master_faces;
  m.normal.reserve(m.face.size());
  for (std::size_t f = 0; f < m.face.size(); ++f) {
    const auto& t = m.face[f];
    const Vec3 n = (m.y[sz(t[1])] - m.y[sz(t[0])]).cross(m.y[sz(t[2])] - m.y[sz(t[0])]);
    const double len = n.norm();
    if (!(len > 0.0)) {
      throw Error("project_slave_nodes: deformed master triangle " + std::to_string(f) + " (nodes " +
                  std::to_string(pair.master[sz(t[0])]) + ", " + std::to_string(pair.master[sz(t[1])]) + ", " +
                  std::to_string(pair.master[sz(t[2])]) + ") has zero area; its normal is undefined");
    }
    m.normal.push_back(n / len);
  }
  vertex_normals(m);
  rim_geometry(m, pair);
  return m;
}

}  // namespace contactrb::contact
