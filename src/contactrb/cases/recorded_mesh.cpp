#include "contactrb/cases/recorded_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/common/printable.hpp"

namespace contactrb::cases {

namespace {

// Relative to the larger side of the box: the stored mesh is the generated one written as
// doubles and read back exactly, so only a changed mesh differs by more.
constexpr double kBoxTolerance = 1e-9;

struct Box {
  double x_min = std::numeric_limits<double>::infinity(), x_max = -std::numeric_limits<double>::infinity();
  double y_min = std::numeric_limits<double>::infinity(), y_max = -std::numeric_limits<double>::infinity();
};

Box bounding_box(const mesh::Mesh& m) {
  Box b;
  for (const Eigen::Vector2d& p : m.nodes) {
    b.x_min = std::min(b.x_min, p.x());
    b.x_max = std::max(b.x_max, p.x());
    b.y_min = std::min(b.y_min, p.y());
    b.y_max = std::max(b.y_max, p.y());
  }
  return b;
}

bool same_box(const Box& a, const Box& b) {
  const double size = std::max({a.x_max - a.x_min, a.y_max - a.y_min, b.x_max - b.x_min, b.y_max - b.y_min});
  const double tol = kBoxTolerance * size;
  return std::abs(a.x_min - b.x_min) <= tol && std::abs(a.x_max - b.x_max) <= tol &&
         std::abs(a.y_min - b.y_min) <= tol && std::abs(a.y_max - b.y_max) <= tol;
}

std::string box_text(const Box& b) {
  return "[" + number_text(b.x_min) + ", " + number_text(b.x_max) + "] x [" + number_text(b.y_min) + ", " +
         number_text(b.y_max) + "]";
}

std::string case_at(const CaseSpec& spec, int level) {
  return "case '" + printable(spec.name) + "' at level " + std::to_string(level);
}

constexpr const char* kInconsistent = ": the file is inconsistent";

// The regenerated mesh at `level`, or an error as soon as a coarser level is already larger than
// the file's `nodes` (the meshes grow with the level; level 16 of a crafted record is never built).
mesh::Mesh regenerate(const CaseSpec& spec, int level, int nodes, const std::string& holds) {
  for (int k = 0;; ++k) {
    mesh::Mesh m = reference_mesh(spec, k);
    if (k == level) return m;
    if (m.num_nodes() > nodes) {
      throw Error(holds + "; " + case_at(spec, k) + " already has " + std::to_string(m.num_nodes()) + " nodes" +
                  kInconsistent);
    }
  }
}

}  // namespace

mesh::Mesh recorded_reference_mesh(const CaseSpec& spec, const MeshRecord& record, const std::string& origin) {
  const std::string file = "file '" + printable(origin) + "'";
  require(record.level >= 0 && record.level <= mesh::kMaxMeshLevel,
          file + " records level " + std::to_string(record.level) + " (expected 0 to " +
              std::to_string(mesh::kMaxMeshLevel) + ")" + kInconsistent);
  const bool has_stored = record.stored != nullptr && !record.stored->nodes.empty();
  const int nodes = has_stored ? record.stored->num_nodes() : record.num_dofs / 2;
  if (has_stored) {
    require(record.stored->num_dofs() == record.num_dofs,
            file + " holds a mesh of " + std::to_string(nodes) + " nodes (" + std::to_string(2 * nodes) +
                " DOFs) but records " + std::to_string(record.num_dofs) + " DOFs" + kInconsistent);
  }
  const std::string holds = file + " records level " + std::to_string(record.level) + " but holds " +
                            (has_stored ? "a mesh of " : "arrays of a mesh of ") + std::to_string(nodes) + " nodes";
  if (spec.mesh.generator.empty()) {
    require(record.level == 0, holds + "; the mesh of case '" + printable(spec.name) + "' is the file " +
                                   printable(spec.mesh.msh_file) + " (level 0 only)" + kInconsistent);
    std::error_code ec;
    if (has_stored && !std::filesystem::is_regular_file(spec.mesh.msh_file, ec)) return *record.stored;
  }
  mesh::Mesh m = regenerate(spec, record.level, nodes, holds);
  const std::string has = "; " + case_at(spec, record.level) + " has ";
  if (m.num_nodes() != nodes) throw Error(holds + has + std::to_string(m.num_nodes()) + " nodes" + kInconsistent);
  if (!has_stored) return m;
  const mesh::Mesh& stored = *record.stored;
  if (m.num_triangles() != stored.num_triangles()) {
    throw Error(holds + " and " + std::to_string(stored.num_triangles()) + " triangles" + has +
                std::to_string(m.num_triangles()) + " triangles" + kInconsistent);
  }
  const Box mine = bounding_box(m), theirs = bounding_box(stored);
  if (!same_box(mine, theirs)) {
    throw Error(file + " holds a mesh spanning " + box_text(theirs) + "; " + case_at(spec, record.level) + " spans " +
                box_text(mine) + kInconsistent);
  }
  return stored;
}

}  // namespace contactrb::cases
