#pragma once
// Small structured meshes for tests, examples and benchmarks (no Gmsh needed).
#include <string>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh {

// Rectangle [x0, x1] x [y0, y1], nx by ny cells, each cut into two counter-clockwise
// triangles along alternating diagonals. All triangles get body id `body`. Boundary groups:
// "bottom", "right", "top", "left" (edges oriented counter-clockwise).
Mesh rectangle(double x0, double y0, double x1, double y1, int nx, int ny, int body = kSlaveBody);

// Box [lo, hi] of nx by ny by nz cells, each cut into six positive tetrahedra around its
// diagonal from the lowest to the highest corner (a conforming mesh: neighbouring cubes cut
// their shared face along the same diagonal). All tetrahedra get body id `body`. Boundary
// groups (triangles oriented with the outward normal): "bottom" (z = lo.z), "top" (z = hi.z),
// "left" (x = lo.x), "right" (x = hi.x), "front" (y = lo.y), "back" (y = hi.y).
Mesh3 box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz, int body = kSlaveBody);

// Two stacked boxes with non-matching meshes on their common plane, a 3D two-block patch
// geometry (docs/meshes.md, "Three-dimensional meshes"): the master block (body 1)
// [0, 1]^2 x [-h, 0] of n = 4 * 2^level cubes across and n / 2 high, the slave block (body 0)
// [0, 1]^2 x [gap, gap + h] of m = 3 n / 2 + 1 cubes across (odd: no slave node inside the
// contact face lies on a master node) and (m + 1) / 2 high, h = 0.5. Groups: "slave" (slave
// bottom face), "master" (master top face), "top" (slave top), "bottom" (master bottom),
// "slave_sides" and "master_sides" (the four vertical faces of each block). level in [0, 4].
Mesh3 stacked_blocks(int level, double gap = 0.0);

// Disjoint union: b's nodes are appended after a's. Boundary group names must differ.
template <int Dim>
SimplexMesh<Dim> merge(const SimplexMesh<Dim>& a, const SimplexMesh<Dim>& b);

// Renames boundary group `from` to `to` (throws if `from` is missing or `to` exists).
template <int Dim>
void rename_boundary(SimplexMesh<Dim>& mesh, const std::string& from, const std::string& to);

// The mesh joined with its mirror image about the plane x_axis = 0 (a full or half model from a
// symmetric part): the nodes on the plane (|x_axis| <= 1e-12 times the mesh's extent) are shared,
// the mirrored cells and facets keep their orientation (two vertices swapped), each group holds
// its facets and their images, and `plane_group` (the facets on the plane, now inside) is dropped.
// Throws contactrb::Error if `plane_group` is missing or one of its facets is off the plane.
template <int Dim>
SimplexMesh<Dim> mirror(const SimplexMesh<Dim>& mesh, int axis, const std::string& plane_group);

// Moves the interior nodes (not on any cell's boundary facet) by a deterministic
// pseudo-random offset of at most `fraction` times the local edge length, to make a
// structured mesh unstructured for patch tests. Keeps the cells positive for small fractions
// (about 0.3 in 2D, 0.15 in 3D on the structured meshes above).
template <int Dim>
void perturb_interior(SimplexMesh<Dim>& mesh, double fraction, unsigned seed = 1);

}  // namespace contactrb::mesh
