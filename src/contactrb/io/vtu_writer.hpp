#pragma once
// VTK XML UnstructuredGrid (.vtu) output for ParaView: a triangle or tetrahedron mesh, or a set
// of line segments or surface triangles (a contact boundary), with point, cell and field data. Binary: every array is a
// block of VTK's "appended raw" data (little-endian, each block preceded by its byte count as
// UInt64), so a file is exact (no decimal round trip) and about a third of the ASCII size;
// the XML header stays readable text (docs/file-formats.md, "VTU files (ParaView)"). 2D points are
// written as 3D with z = 0, 2D vectors as 3-component vectors with z = 0. The cell data of a
// triangle or tetrahedron mesh always holds "body" (Int32, mesh.hpp body ids).
//
//   io::VtuWriter(mesh)
//       .add_point_vector("displacement", u)       // u in DOF numbering (Dim i + c)
//       .add_point_scalar("contact_pressure", p)   // one value per node
//       .add_cell_scalar("von_mises", s)           // one value per triangle
//       .add_field_data("delta", 0.3)              // one value for the whole dataset
//       .deform_by("displacement")                 // optional: deformed configuration
//       .write("out/solution.vtu");
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::io {

// One named field: `components` values per entity (1 = scalar, 2 = 2D vector), entity i
// holding values[components * i + c]. Field data: components = 1, one value per tuple.
struct VtuField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

class VtuWriter {
 public:
  // The nodes and triangles of `mesh` (copied), cell data "body".
  explicit VtuWriter(const mesh::Mesh& mesh);
  // The nodes and tetrahedra (VTK_TETRA) of `mesh` (copied), cell data "body".
  explicit VtuWriter(const mesh::Mesh3& mesh);

  // Triangle cells in 3D (a surface, e.g. the slave boundary): triangle k joins the points
  // triangles[k][0..2]. No "body" cell data; vectors have 3 components. Indices are checked by write().
  static VtuWriter triangles(std::vector<Eigen::Vector3d> points, std::vector<std::array<int, 3>> triangles);

  // Line cells (VTK_LINE): segment k joins points[segments[k][0]] and points[segments[k][1]].
  // No "body" cell data. Indices are checked by write().
  static VtuWriter lines(std::vector<Eigen::Vector2d> points, std::vector<std::array<int, 2>> segments);

  // Each add_* copies the values and throws contactrb::Error naming the field when the
  // size is wrong, the name is empty or already used (in the same data section), or a
  // value is not finite (a failed solve's field, not one to look at).
  VtuWriter& add_point_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  // 2 values per node (3 for a 3D writer), in the DOF numbering of mesh.hpp (node i: Dim i + c).
  VtuWriter& add_point_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  VtuWriter& add_cell_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  // 2 values per cell (3 for a 3D writer; cell t: Dim t + c).
  VtuWriter& add_cell_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  // `components` values per cell written as they are (e.g. a 3 x 3 tensor, 9 components, row
  // by row, which ParaView shows as a tensor).
  VtuWriter& add_cell_field(const std::string& name, int components, const Eigen::Ref<const Eigen::VectorXd>& values);
  // Field data: values of the whole dataset (not per point or cell), e.g. the parameter
  // values; one tuple per value, at least one value.
  VtuWriter& add_field_data(const std::string& name, std::span<const double> values);
  VtuWriter& add_field_data(const std::string& name, double value);

  // Writes the points of the deformed configuration X + scale * field, where `point_vector`
  // names a point vector field already added (the field itself is written too). Throws
  // contactrb::Error when there is no such point vector field.
  VtuWriter& deform_by(const std::string& point_vector, double scale = 1.0);

  // Writes the file through a temporary file in the same directory, renamed at the end
  // (common/output_file.hpp: never a half-written file, never over a link or device).
  // Throws contactrb::Error naming the path when it cannot be written (e.g. the directory
  // does not exist) or when a cell refers to a point that does not exist.
  void write(const std::string& path) const;

  int num_points() const { return static_cast<int>(points_.size()); }
  int num_cells() const;
  const std::vector<VtuField>& point_data() const { return point_data_; }
  const std::vector<VtuField>& cell_data() const { return cell_data_; }
  const std::vector<VtuField>& field_data() const { return field_data_; }

 private:
  VtuWriter() = default;
  void add(std::vector<VtuField>& section, const char* section_name, int entities, const std::string& name,
           int components, std::span<const double> values);

  std::vector<Eigen::Vector3d> points_;  // 2D points with z = 0
  int dim_ = 2;                          // components of point and cell vectors
  std::vector<std::int64_t> connectivity_;  // nodes_per_cell_ point indices per cell
  int nodes_per_cell_ = 3;
  std::uint8_t cell_type_ = 0;  // vtkCellType.h
  bool has_body_ = false;           // triangle meshes: cell data "body"
  std::vector<std::int32_t> body_;  // one per cell when has_body_
  std::vector<VtuField> point_data_;
  std::vector<VtuField> cell_data_;
  std::vector<VtuField> field_data_;
  std::string deform_field_;
  double deform_scale_ = 1.0;
};

// The mesh alone (cell data "body").
void write_vtu(const mesh::Mesh& mesh, const std::string& path);
void write_vtu(const mesh::Mesh3& mesh, const std::string& path);

}  // namespace contactrb::io
