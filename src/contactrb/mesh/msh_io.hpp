#pragma once
// Gmsh .msh (format 4) import and export.
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh {

// Which physical groups of a .msh file make up the two bodies and which boundary groups
// must be present. 2D physical groups named body_groups[0] (slave) and body_groups[1]
// (master); every named 1D physical group becomes a boundary group of the same name.
struct MshGroups {
  std::vector<std::string> body_groups{"body1", "body2"};
  std::vector<std::string> required_boundaries{kSlaveBoundary, kMasterBoundary};
};

// Reads a .msh file (format 4). Throws contactrb::Error with one clear message naming the
// file and the problem: missing file, not a Gmsh mesh, wrong format version, missing
// physical group, inverted or zero-area triangle, unreferenced node. Triangles are
// reoriented counter-clockwise only if ALL of a body's triangles are clockwise
// (a consistently mirrored file); a mix of orientations is an error.
// Details (docs/meshes.md):
//  - Only ASCII format 4.1 is read (binary, 2.x and 4.0 files are rejected with a hint).
//  - Elements: 3-node triangles (type 2), 2-node lines (type 1) and points (type 15);
//    any other type is an error. body_groups may name 1 or 2 groups; every triangle must
//    be in exactly one of them; the bodies must not share nodes.
//  - Unreferenced nodes: a node used by no triangle is dropped when it lies on a
//    geometry point or curve entity (dim 0 or 1, e.g. Gmsh's corner-point nodes) and is
//    used by no line element; a surface node used by no triangle is an error. A line of
//    a boundary group must be an edge of exactly one triangle; it is reoriented with its
//    body on the left.
//  - Node indices follow the order of the $Nodes section (unused nodes skipped).
Mesh read_msh(const std::string& path, const MshGroups& groups = {});

// Writes format 4.1 ASCII with physical groups "body1", "body2" and one 1D group per
// boundary group, so that read_msh(write_msh(m)) == m up to node order.
void write_msh(const Mesh& mesh, const std::string& path);

}  // namespace contactrb::mesh
