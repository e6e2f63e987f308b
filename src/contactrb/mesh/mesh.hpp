#pragma once
// Two-body triangle mesh with named boundary edge groups.
//
// Conventions used by every module:
//  - DOF numbering: node i carries DOFs 2*i (x) and 2*i+1 (y).
//  - Triangles are counter-clockwise (positive signed area).
//  - body[t] is 0 for the slave body Omega_1 (carries the multipliers on Gamma_1^c) and
//    1 for the master body Omega_2 (paper Section 3.2).
//  - Boundary groups are named. The contact boundaries are "slave" (Gamma_1^c) and
//    "master" (Gamma_2^c); Dirichlet groups have case-specific names.
//  - A boundary edge (a, b) is oriented with its body on the left (counter-clockwise
//    traversal of the body's boundary), so its outward normal is (dy, -dx)/|e|.
#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace contactrb::mesh {

struct Edge {
  int a = 0;
  int b = 0;
};

inline constexpr int kSlaveBody = 0;
inline constexpr int kMasterBody = 1;
// The finest refinement level of the built-in geometries (--level; the Hertz slave arc has
// 120 * 2^14 + 1 nodes there): a file recording a level above it is damaged or crafted.
inline constexpr int kMaxMeshLevel = 16;
inline constexpr const char* kSlaveBoundary = "slave";
inline constexpr const char* kMasterBoundary = "master";

struct Mesh {
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> body;  // one entry per triangle
  std::map<std::string, std::vector<Edge>> boundaries;

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
  int num_dofs() const { return 2 * num_nodes(); }
  int num_bodies() const;

  bool has_boundary(const std::string& name) const { return boundaries.count(name) > 0; }
  // Throws contactrb::Error naming the group and listing the groups present.
  const std::vector<Edge>& boundary(const std::string& name) const;
};

// Signed area of triangle t (positive when counter-clockwise).
double signed_area(const Mesh& mesh, int t);

// Sorted, unique node indices of a boundary group.
std::vector<int> boundary_nodes(const Mesh& mesh, const std::string& name);

// Nodes of a group ordered along the single open (or closed) polyline its edges form, in
// the edges' orientation. Throws contactrb::Error if the edges do not form one chain.
std::vector<int> ordered_chain(const Mesh& mesh, const std::string& name);

// Checks the invariants above; throws contactrb::Error naming the first violation
// (inverted or zero-area triangle, node index out of range, unreferenced node, body id
// out of range, boundary edge not an edge of a triangle).
void validate(const Mesh& mesh);

// Applies x -> M x + b to the nodes of one body (a geometric map h_i(mu), paper (32)).
// Nodes shared by both bodies are not allowed (bodies are disjoint).
void map_body(Mesh& mesh, int body, const Eigen::Matrix2d& M, const Eigen::Vector2d& b);

}  // namespace contactrb::mesh
