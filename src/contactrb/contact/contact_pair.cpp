#include "contactrb/contact/contact_pair.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <tuple>
#include <vector>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::contact {

const char* to_string(Discretization d) {
  switch (d) {
    case Discretization::Collocation:
      return "collocation";
    case Discretization::LAC:
      return "lac";
    case Discretization::LACSimpson:
      return "lac-simpson";
  }
  return "unknown";
}

Discretization discretization_from_string(const std::string& name) {
  using enum Discretization;
  return enum_from_string(name, "contact discretization", std::array{Collocation, LAC, LACSimpson});
}

namespace {

// Body id of every node: -1 unreferenced, 0 / 1 the body, 2 referenced by both bodies.
template <int Dim>
std::vector<int> node_bodies(const mesh::SimplexMesh<Dim>& mesh) {
  std::vector<int> owner(mesh.nodes.size(), -1);
  for (int t = 0; t < mesh.num_cells(); ++t) {
    const int b = mesh.body[static_cast<std::size_t>(t)];
    for (int v : mesh.cells()[static_cast<std::size_t>(t)]) {
      if (v < 0 || v >= mesh.num_nodes()) continue;  // mesh::validate reports these
      int& o = owner[static_cast<std::size_t>(v)];
      o = (o == -1 || o == b) ? b : 2;
    }
  }
  return owner;
}

// Every node of a contact group lies on the group's body only.
template <int Dim>
void check_bodies(const mesh::SimplexMesh<Dim>& mesh, const std::vector<int>& owner, const std::vector<int>& nodes,
                  const char* group, int body, const char* role) {
  for (int v : nodes) {
    if (v < 0 || v >= mesh.num_nodes()) {
      throw Error(std::string(role) + " boundary '" + group + "' references node " + std::to_string(v) +
                  " outside [0, " + std::to_string(mesh.num_nodes()) + ")");
    }
    const int o = owner[static_cast<std::size_t>(v)];
    if (o != body) {
      throw Error(std::string(role) + " boundary '" + group + "' node " + std::to_string(v) +
                  (o == -1  ? " belongs to no triangle"
                   : o == 2 ? " belongs to both bodies"
                            : " belongs to body " + std::to_string(o)) +
                  " (the " + role + " boundary must lie on body " + std::to_string(body) + ")");
    }
  }
}

std::vector<int> checked_chain(const mesh::Mesh& mesh, const std::vector<int>& owner, const char* group,
                               int body, const char* role) {
  std::vector<int> chain = mesh::ordered_chain(mesh, group);
  require(chain.size() >= 2, std::string(role) + " boundary '" + group + "' has " +
                                 std::to_string(chain.size()) + " node(s); at least 2 are needed");
  check_bodies(mesh, owner, chain, group, body, role);
  return chain;
}

// The nodes of a 3D contact group, after checking that it is non-empty and on its body.
std::vector<int> checked_surface(const mesh::Mesh3& mesh, const std::vector<int>& owner, const char* group,
                                 int body, const char* role) {
  require(!mesh.boundary(group).empty(), std::string(role) + " boundary '" + group + "' has no triangle");
  std::vector<int> nodes = mesh::boundary_nodes(mesh, group);
  check_bodies(mesh, owner, nodes, group, body, role);
  return nodes;
}

// The edges of exactly one master triangle, as (face, opposite vertex), in face order.
std::vector<std::array<int, 2>> surface_rim(const std::vector<std::array<int, 3>>& faces) {
  struct EdgeUse {
    int lo, hi, face, opposite;
  };
  std::vector<EdgeUse> edges;
  edges.reserve(3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const int a = faces[f][static_cast<std::size_t>((i + 1) % 3)], b = faces[f][static_cast<std::size_t>((i + 2) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f), i});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.lo, x.hi, x.face, x.opposite) < std::tie(y.lo, y.hi, y.face, y.opposite);
  });
  std::vector<std::array<int, 2>> rim;
  for (std::size_t e = 0; e < edges.size();) {
    std::size_t next = e + 1;
    while (next < edges.size() && edges[next].lo == edges[e].lo && edges[next].hi == edges[e].hi) ++next;
    if (next == e + 1) rim.push_back({edges[e].face, edges[e].opposite});
    e = next;
  }
  std::sort(rim.begin(), rim.end());
  return rim;
}

}  // namespace

ContactPair make_contact_pair(const mesh::Mesh& mesh) {
  require(mesh.body.size() == mesh.triangles.size(),
          "make_contact_pair: mesh has " + std::to_string(mesh.triangles.size()) + " triangles but " +
              std::to_string(mesh.body.size()) + " body ids");
  const std::vector<int> owner = node_bodies(mesh);
  ContactPair pair;
  pair.slave = checked_chain(mesh, owner, mesh::kSlaveBoundary, mesh::kSlaveBody, "slave");
  pair.master = checked_chain(mesh, owner, mesh::kMasterBoundary, mesh::kMasterBody, "master");
  // A closed chain comes back from ordered_chain without repeating its first node.
  const auto closed = [&mesh](const char* group, std::size_t nodes) {
    return mesh.boundary(group).size() == nodes;
  };
  require(!closed(mesh::kSlaveBoundary, pair.slave.size()),
          "slave boundary 'slave' is a closed loop; it must be an open polyline");
  if (closed(mesh::kMasterBoundary, pair.master.size())) pair.master.push_back(pair.master.front());
  return pair;
}

ContactPair3 make_contact_pair(const mesh::Mesh3& mesh) {
  require(mesh.body.size() == mesh.tetrahedra.size(),
          "make_contact_pair: mesh has " + std::to_string(mesh.tetrahedra.size()) + " tetrahedra but " +
              std::to_string(mesh.body.size()) + " body ids");
  const std::vector<int> owner = node_bodies(mesh);
  ContactPair3 pair;
  pair.slave = checked_surface(mesh, owner, mesh::kSlaveBoundary, mesh::kSlaveBody, "slave");
  pair.master = checked_surface(mesh, owner, mesh::kMasterBoundary, mesh::kMasterBody, "master");
  pair.slave_faces = mesh.boundary(mesh::kSlaveBoundary);
  const auto local = [&pair](int v) {
    return static_cast<int>(std::lower_bound(pair.master.begin(), pair.master.end(), v) - pair.master.begin());
  };
  for (const mesh::Face& f : mesh.boundary(mesh::kMasterBoundary)) {
    pair.master_faces.push_back({local(f.a), local(f.b), local(f.c)});
  }
  pair.master_rim = surface_rim(pair.master_faces);
  return pair;
}

namespace {

double edge_length(const mesh::Mesh& mesh, int a, int b) {
  return (mesh.nodes[static_cast<std::size_t>(b)] - mesh.nodes[static_cast<std::size_t>(a)]).norm();
}

}  // namespace

ContactQuadrature make_quadrature(const mesh::Mesh& mesh, const ContactPair& pair, Discretization d) {
  const auto& slave = pair.slave;
  const int S = static_cast<int>(slave.size());
  require(S >= 2, "make_quadrature: the slave chain has " + std::to_string(S) + " node(s); at least 2 are needed");
  for (int v : slave) {
    if (v < 0 || v >= mesh.num_nodes()) {
      throw Error("make_quadrature: slave node " + std::to_string(v) + " outside [0, " +
                  std::to_string(mesh.num_nodes()) + ")");
    }
  }
  const int E = S - 1;  // slave edges, edge e = (slave[e], slave[e + 1])
  std::vector<double> len(static_cast<std::size_t>(E));
  for (int e = 0; e < E; ++e) {
    len[static_cast<std::size_t>(e)] =
        edge_length(mesh, slave[static_cast<std::size_t>(e)], slave[static_cast<std::size_t>(e + 1)]);
  }

  ContactQuadrature q;
  q.discretization = d;
  std::vector<Eigen::Triplet<double>> entries;
  int rows = 0;
  if (d == Discretization::Collocation) {
    // (60)-(61): one-node quadrature at z_r; psi_r is P0 on I_r = half of each adjacent edge.
    rows = S;
    for (int r = 0; r < S; ++r) {
      const double left = r > 0 ? len[static_cast<std::size_t>(r - 1)] : 0.0;
      const double right = r < E ? len[static_cast<std::size_t>(r)] : 0.0;
      entries.emplace_back(r, r, 0.5 * (left + right));
      q.center_node.push_back(slave[static_cast<std::size_t>(r)]);
    }
  } else {
    // Macro-segment r = slave edges 2r and 2r + 1; with an odd number of edges the last
    // macro-segment is one edge (trapezoidal rule: exact slave weights). LACSimpson: (62),
    // Simpson's rule on the three nodes. LAC: the exact weights int_{I_r} phi_s.
    rows = (E + 1) / 2;
    for (int r = 0; r < rows; ++r) {
      const int first = 2 * r;
      if (first + 1 < E) {
        const double h1 = len[static_cast<std::size_t>(first)], h2 = len[static_cast<std::size_t>(first + 1)];
        if (d == Discretization::LACSimpson) {
          const double I = h1 + h2;
          entries.emplace_back(r, first, I / 6.0);
          entries.emplace_back(r, first + 1, 4.0 * I / 6.0);
          entries.emplace_back(r, first + 2, I / 6.0);
        } else {
          entries.emplace_back(r, first, h1 / 2.0);
          entries.emplace_back(r, first + 1, (h1 + h2) / 2.0);
          entries.emplace_back(r, first + 2, h2 / 2.0);
        }
        q.center_node.push_back(slave[static_cast<std::size_t>(first + 1)]);
      } else {
        const double I = len[static_cast<std::size_t>(first)];
        entries.emplace_back(r, first, I / 2.0);
        entries.emplace_back(r, first + 1, I / 2.0);
        q.center_node.push_back(slave[static_cast<std::size_t>(first)]);
      }
    }
  }
  q.W.resize(rows, S);
  q.W.setFromTriplets(entries.begin(), entries.end());
  q.weight = Eigen::VectorXd::Zero(rows);
  for (int r = 0; r < rows; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(q.W, r); it; ++it) q.weight(r) += it.value();
  }
  return q;
}

ContactQuadrature make_quadrature(const mesh::Mesh3& mesh, const ContactPair3& pair, Discretization d) {
  require(d != Discretization::LACSimpson,
          "make_quadrature: the 'lac-simpson' discretization is not available in 3D (use 'lac' or 'collocation')");
  const int S = static_cast<int>(pair.slave.size());
  require(S >= 1, "make_quadrature: the slave surface has no node");
  const auto position = [&pair](int v) {
    const auto it = std::lower_bound(pair.slave.begin(), pair.slave.end(), v);
    require(it != pair.slave.end() && *it == v,
            "make_quadrature: slave triangle node " + std::to_string(v) + " is not a slave node");
    return static_cast<int>(it - pair.slave.begin());
  };
  // Collocation (60)-(61): I_r is the nodal area, a third of each adjacent slave triangle.
  // LAC: I_r is the median dual cell of the node, W_rs = int_{I_r} phi_s, per triangle of area
  // A: 11 A / 54 for the cell's own vertex, 7 A / 108 for each other (docs/contact.md, "LAC in
  // three dimensions"); the row sums are the same nodal areas.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(pair.slave_faces.size() * (d == Discretization::LAC ? 9 : 3));
  for (const mesh::Face& f : pair.slave_faces) {
    for (int v : f.vertices()) {
      require(v >= 0 && v < mesh.num_nodes(), "make_quadrature: slave node " + std::to_string(v) + " outside [0, " +
                                                  std::to_string(mesh.num_nodes()) + ")");
    }
    const double area = mesh::facet_area_normal(mesh, f).norm();
    const std::array<int, 3> s{position(f.a), position(f.b), position(f.c)};
    for (std::size_t a = 0; a < 3; ++a) {
      if (d == Discretization::Collocation) {
        entries.emplace_back(s[a], s[a], area / 3.0);
        continue;
      }
      for (std::size_t b = 0; b < 3; ++b) entries.emplace_back(s[a], s[b], a == b ? 11.0 * area / 54.0 : 7.0 * area / 108.0);
    }
  }
  ContactQuadrature q;
  q.discretization = d;
  q.W.resize(S, S);
  q.W.setFromTriplets(entries.begin(), entries.end());
  q.weight = Eigen::VectorXd::Zero(S);
  for (int r = 0; r < S; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(q.W, r); it; ++it) q.weight(r) += it.value();
  }
  q.center_node = pair.slave;
  return q;
}

}  // namespace contactrb::contact
