#pragma once
// Two-body simplex meshes with named boundary groups: triangles in 2D (Mesh), tetrahedra in
// 3D (Mesh3). One template, SimplexMesh<Dim>, serves both dimensions.
//
// Conventions used by every module (Dim = 2 or 3):
//  - DOF numbering: node i carries DOFs Dim*i + c, component c = 0 (x), 1 (y), 2 (z).
//  - A cell has Dim + 1 nodes and positive signed measure: triangles are counter-clockwise,
//    tetrahedra (p0, p1, p2, p3) have det(p1 - p0, p2 - p0, p3 - p0) > 0.
//  - body[c] is 0 for the slave body Omega_1 (carries the multipliers on Gamma_1^c) and
//    1 for the master body Omega_2 (paper Section 3.2). Bodies share no node.
//  - Boundary groups are named lists of boundary facets (Dim nodes each: edges in 2D,
//    triangles in 3D). The contact boundaries are "slave" (Gamma_1^c) and "master"
//    (Gamma_2^c); Dirichlet and traction groups have case-specific names.
//  - A boundary facet is oriented with its outward normal: an edge (a, b) has its body on
//    the left (counter-clockwise traversal of the body's boundary), outward normal
//    (dy, -dx)/|e|; a triangle (a, b, c) has the outward normal (b - a) x (c - a) / |.|
//    (counter-clockwise seen from outside the body).
#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace contactrb::mesh {

// A boundary facet in 2D.
struct Edge {
  int a = 0;
  int b = 0;
  std::array<int, 2> vertices() const { return {a, b}; }
};

// A boundary facet in 3D.
struct Face {
  int a = 0;
  int b = 0;
  int c = 0;
  std::array<int, 3> vertices() const { return {a, b, c}; }
};

inline constexpr int kSlaveBody = 0;
inline constexpr int kMasterBody = 1;
// The finest refinement level of the built-in geometries (--level; the Hertz slave arc has
// 120 * 2^14 + 1 nodes there): a file recording a level above it is damaged or crafted.
inline constexpr int kMaxMeshLevel = 16;
inline constexpr const char* kSlaveBoundary = "slave";
inline constexpr const char* kMasterBoundary = "master";

// The cells under the dimension's own name (mesh.triangles, mesh.tetrahedra); cells() is the
// name dimension-independent code uses.
template <int Dim>
struct CellList;

template <>
struct CellList<2> {
  std::vector<std::array<int, 3>> triangles;
  int num_triangles() const { return static_cast<int>(triangles.size()); }
  std::vector<std::array<int, 3>>& cells() { return triangles; }
  const std::vector<std::array<int, 3>>& cells() const { return triangles; }
};

template <>
struct CellList<3> {
  std::vector<std::array<int, 4>> tetrahedra;
  int num_tetrahedra() const { return static_cast<int>(tetrahedra.size()); }
  std::vector<std::array<int, 4>>& cells() { return tetrahedra; }
  const std::vector<std::array<int, 4>>& cells() const { return tetrahedra; }
};

// Names used in messages: "triangle" / "tetrahedron", "edge" / "triangle", "area" / "volume".
template <int Dim>
struct SimplexNames;
template <>
struct SimplexNames<2> {
  static constexpr const char* cell = "triangle";
  static constexpr const char* facet = "edge";
  static constexpr const char* measure = "area";
};
template <>
struct SimplexNames<3> {
  static constexpr const char* cell = "tetrahedron";
  static constexpr const char* facet = "triangle";
  static constexpr const char* measure = "volume";
};

template <int Dim>
struct SimplexMesh : CellList<Dim> {
  static_assert(Dim == 2 || Dim == 3, "SimplexMesh: Dim is 2 or 3");
  static constexpr int dim = Dim;
  using Point = Eigen::Matrix<double, Dim, 1>;
  using Cell = std::array<int, Dim + 1>;
  using Facet = std::conditional_t<Dim == 2, Edge, Face>;

  std::vector<Point> nodes;
  std::vector<int> body;  // one entry per cell
  std::map<std::string, std::vector<Facet>> boundaries;

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_cells() const { return static_cast<int>(this->cells().size()); }
  int num_dofs() const { return Dim * num_nodes(); }
  int num_bodies() const;

  bool has_boundary(const std::string& name) const { return boundaries.count(name) > 0; }
  // Throws contactrb::Error naming the group and listing the groups present.
  const std::vector<Facet>& boundary(const std::string& name) const;
};

using Mesh = SimplexMesh<2>;
using Mesh3 = SimplexMesh<3>;

// The facets of a cell, each oriented with the cell's outward normal (the orientation of a
// boundary facet, above): facet k is opposite vertex k.
template <int Dim>
inline constexpr std::array<std::array<int, Dim>, Dim + 1> kCellFacets{};
template <>
inline constexpr std::array<std::array<int, 2>, 3> kCellFacets<2>{{{1, 2}, {2, 0}, {0, 1}}};
template <>
inline constexpr std::array<std::array<int, 3>, 4> kCellFacets<3>{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

// The same oriented facet written from another starting vertex gives the same key (3D:
// rotated so that the smallest index comes first; 2D: the edge itself, a reversed edge is
// the opposite orientation).
template <int Dim>
std::array<int, Dim> oriented_key(std::array<int, Dim> v) {
  if constexpr (Dim == 3) {
    while (v[0] > v[1] || v[0] > v[2]) v = {v[1], v[2], v[0]};
  }
  return v;
}

// Signed measure of cell c: area in 2D (positive when counter-clockwise), volume in 3D
// (positive for the orientation above).
template <int Dim>
double signed_volume(const SimplexMesh<Dim>& mesh, int c);
// The 2D name of signed_volume.
double signed_area(const Mesh& mesh, int t);

// Outward normal of a boundary facet times its measure (length in 2D, area in 3D).
template <int Dim>
Eigen::Matrix<double, Dim, 1> facet_area_normal(const SimplexMesh<Dim>& mesh,
                                                const typename SimplexMesh<Dim>::Facet& facet);

// Sorted, unique node indices of a boundary group.
template <int Dim>
std::vector<int> boundary_nodes(const SimplexMesh<Dim>& mesh, const std::string& name);

// Nodes of a 2D group ordered along the single open (or closed) polyline its edges form, in
// the edges' orientation. Throws contactrb::Error if the edges do not form one chain.
std::vector<int> ordered_chain(const Mesh& mesh, const std::string& name);

// Checks the invariants above; throws contactrb::Error naming the first violation
// (inverted or zero-measure cell, node index out of range, unreferenced node, body id
// out of range, boundary facet not an outward-oriented facet of a cell).
template <int Dim>
void validate(const SimplexMesh<Dim>& mesh);

// Applies x -> M x + b to the nodes of one body (a geometric map h_i(mu), paper (32)).
// Nodes shared by both bodies are not allowed (bodies are disjoint).
template <int Dim>
void map_body(SimplexMesh<Dim>& mesh, int body, const std::type_identity_t<Eigen::Matrix<double, Dim, Dim>>& M,
              const std::type_identity_t<Eigen::Matrix<double, Dim, 1>>& b);

extern template struct SimplexMesh<2>;
extern template struct SimplexMesh<3>;

}  // namespace contactrb::mesh
