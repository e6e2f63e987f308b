#pragma once
// VTK XML UnstructuredGrid (.vtu, ASCII) output of a triangle mesh with point and cell
// fields, for ParaView. 2D points are written as 3D with z = 0, 2D vectors as 3-component
// vectors with z = 0. Cell data always holds "body" (Int32, mesh.hpp body ids).
//
//   io::VtuWriter(mesh)
//       .add_point_vector("displacement", u)       // u in DOF numbering (2i, 2i+1)
//       .add_point_scalar("contact_pressure", p)   // one value per node
//       .deform_by("displacement")                 // optional: deformed configuration
//       .write("out/solution.vtu");
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactrb/mesh/mesh.hpp"

namespace contactrb::io {

// One named field: `components` values per entity (1 = scalar, 2 = 2D vector), entity i
// holding values[components * i + c].
struct VtuField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

class VtuWriter {
 public:
  // Borrows `mesh`: it must outlive the writer.
  explicit VtuWriter(const mesh::Mesh& mesh);

  // Each add_* copies the values and throws contactrb::Error naming the field when the
  // size is wrong, the name is empty or already used (in the same data section), or a
  // value is not finite (ParaView's ASCII reader cannot read nan or inf).
  VtuWriter& add_point_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  // 2 values per node, in the DOF numbering of mesh.hpp (node i: 2i, 2i+1).
  VtuWriter& add_point_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  VtuWriter& add_cell_scalar(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);
  // 2 values per triangle (triangle t: 2t, 2t+1).
  VtuWriter& add_cell_vector(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values);

  // Writes the points of the deformed configuration X + scale * field, where `point_vector`
  // names a point vector field already added (the field itself is written too). Throws
  // contactrb::Error when there is no such point vector field.
  VtuWriter& deform_by(const std::string& point_vector, double scale = 1.0);

  // Writes the file through a temporary file in the same directory, renamed at the end
  // (never a half-written file). Throws contactrb::Error naming the path when it cannot
  // be written (e.g. the directory does not exist).
  void write(const std::string& path) const;

  const std::vector<VtuField>& point_data() const { return point_data_; }
  const std::vector<VtuField>& cell_data() const { return cell_data_; }

 private:
  void add(std::vector<VtuField>& section, const char* section_name, int entities, const std::string& name,
           int components, const Eigen::Ref<const Eigen::VectorXd>& values);

  const mesh::Mesh& mesh_;
  std::vector<VtuField> point_data_;
  std::vector<VtuField> cell_data_;
  std::string deform_field_;
  double deform_scale_ = 1.0;
};

// The mesh alone (cell data "body").
void write_vtu(const mesh::Mesh& mesh, const std::string& path);

}  // namespace contactrb::io
