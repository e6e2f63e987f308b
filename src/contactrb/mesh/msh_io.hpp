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
Mesh read_msh(const std::string& path, const MshGroups& groups = {});

// Writes format 4.1 ASCII with physical groups "body1", "body2" and one 1D group per
// boundary group, so that read_msh(write_msh(m)) == m up to node order.
void write_msh(const Mesh& mesh, const std::string& path);

}  // namespace contactrb::mesh
