#pragma once
// The reference mesh of a case rebuilt from the record of a snapshot or model file, checked
// against what the file holds (docs/file-formats.md, "Level and mesh"): the record names a case
// and a mesh level, the file holds arrays on one mesh (and, from format 4/5, the mesh itself).
// A level or case that does not produce that mesh would combine arrays of different meshes;
// one function checks it for every command that rebuilds a case from a file.
#include <string>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::cases {

// What a file records of its mesh: the level of its case, its DOF count, and the stored
// reference mesh (empty when the file stores none).
struct MeshRecord {
  int level = 0;
  int num_dofs = 0;
  const mesh::Mesh* stored = nullptr;  // nullptr or an empty mesh: none stored
};

// The case's mesh at the recorded level, compared with the file's: its node and triangle counts
// and its bounding box with the stored mesh (when there is one), its DOF count with the
// recorded one. Returns the stored mesh when there is one, else the regenerated one.
// A case whose .msh file is gone (cases::MeshFile::Optional) cannot be regenerated: its stored
// mesh is then checked against the recorded level (0) and DOF count only.
// Throws contactrb::Error naming `origin` (the file) when they disagree, e.g. "file 'm.h5'
// records level 0 but holds a mesh of 1652 nodes; case 'hertz-a' at level 0 has 700 nodes: the
// file is inconsistent". A level whose mesh is far larger than the file's is refused without
// generating it: the meshes grow with the level, so the first level above the file's node count
// decides ("... at level 1 already has 810 nodes").
mesh::Mesh recorded_reference_mesh(const CaseSpec& spec, const MeshRecord& record, const std::string& origin);

}  // namespace contactrb::cases
