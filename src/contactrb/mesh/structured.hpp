#pragma once
// Small structured meshes for tests and examples (no Gmsh needed).
#include <string>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh {

// Rectangle [x0, x1] x [y0, y1], nx by ny cells, each cut into two counter-clockwise
// triangles along alternating diagonals. All triangles get body id `body`. Boundary groups:
// "bottom", "right", "top", "left" (edges oriented counter-clockwise).
Mesh rectangle(double x0, double y0, double x1, double y1, int nx, int ny, int body = kSlaveBody);

// Disjoint union: b's nodes are appended after a's. Boundary group names must differ.
Mesh merge(const Mesh& a, const Mesh& b);

// Renames boundary group `from` to `to` (throws if `from` is missing or `to` exists).
void rename_boundary(Mesh& mesh, const std::string& from, const std::string& to);

// Moves the interior nodes (not on any triangle's boundary edge) by a deterministic
// pseudo-random offset of at most `fraction` times the local edge length, to make a
// structured mesh unstructured for patch tests. Keeps triangles counter-clockwise.
void perturb_interior(Mesh& mesh, double fraction, unsigned seed = 1);

}  // namespace contactrb::mesh
