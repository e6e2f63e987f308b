#pragma once
// Gmsh .msh (format 4) import and export.
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::mesh {

// Which physical groups of a .msh file make up the two bodies and which boundary groups
// must be present. Physical groups of the mesh's dimension (2D: surfaces, 3D: volumes) named
// body_groups[0] (slave) and body_groups[1] (master); every named physical group of one
// dimension less (2D: curves, 3D: surfaces) becomes a boundary group of the same name.
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
//  - A file holding 4-node tetrahedra is a 3D mesh: refused here (read_msh3).
Mesh read_msh(const std::string& path, const MshGroups& groups = {});

// Reads a 3D .msh file (format 4.1) the same way: 4-node tetrahedra (type 4) in the 3D body
// groups, 3-node triangles (type 2) of the 2D physical groups as boundary groups (each a face
// of exactly one tetrahedron, reoriented with the outward normal of its body), lines and points
// ignored, any other element type an error. Tetrahedra are reoriented only if ALL of a body's
// tetrahedra have negative volume; a mix is an error; a zero-volume tetrahedron is an error.
// Nodes inside a volume entity must belong to a tetrahedron. Without 3D physical groups (a 2D
// mesh) the message names the missing 3D group and lists the groups present.
Mesh3 read_msh3(const std::string& path, const MshGroups& groups = {});

// The dimension of the mesh in a .msh file: 3 if it holds a 4-node tetrahedron, else 2.
// Throws like read_msh for a file that is not a readable .msh 4.1 file.
int msh_dimension(const std::string& path);

// Writes format 4.1 ASCII with physical groups "body1", "body2" and one 1D group per
// boundary group, so that read_msh(write_msh(m)) == m up to node order.
void write_msh(const Mesh& mesh, const std::string& path);
// The same for a 3D mesh: 3D groups "body1", "body2", one 2D group per boundary group, so that
// read_msh3(write_msh(m)) == m up to node order.
void write_msh(const Mesh3& mesh, const std::string& path);

}  // namespace contactrb::mesh
