#include "contactrb/study/solution_fields_3d.hpp"

#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "contactrb/common/error.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/vtu_writer.hpp"

namespace contactrb::study {

namespace {

void check_rows(const SlaveSurfaceFields& c, int num_nodes) {
  const auto rows = static_cast<Eigen::Index>(c.nodes.size());
  require(c.pressure.size() == rows && c.gap.size() == rows && c.weight.size() == rows,
          "3D contact fields: " + std::to_string(rows) + " rows but " + std::to_string(c.pressure.size()) +
              " pressures, " + std::to_string(c.gap.size()) + " gaps, " + std::to_string(c.weight.size()) +
              " weights");
  for (int node : c.nodes) {
    require(node >= 0 && node < num_nodes, "3D contact fields: row node " + std::to_string(node) +
                                               " outside the mesh's " + std::to_string(num_nodes) + " nodes");
  }
}

}  // namespace

std::vector<std::array<int, 3>> slave_triangles(const mesh::Mesh3& mesh, const std::vector<int>& nodes) {
  std::unordered_map<int, int> row;
  for (std::size_t r = 0; r < nodes.size(); ++r) row.emplace(nodes[r], static_cast<int>(r));
  std::vector<std::array<int, 3>> triangles;
  for (const mesh::Face& f : mesh.boundary(mesh::kSlaveBoundary)) {
    std::array<int, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = f.vertices()[k];
      const auto it = row.find(v);
      require(it != row.end(), "3D contact fields: slave node " + std::to_string(v) + " has no contact row");
      t[k] = it->second;
    }
    triangles.push_back(t);
  }
  return triangles;
}

CellStress3 cell_stress(const mesh::Mesh3& mesh, const std::vector<fem::Material>& materials, const Eigen::VectorXd& u) {
  const auto s = fem::element_stress(mesh, materials, u);  // (xx, yy, zz, xy, yz, xz) per cell
  const Eigen::Index m = s.cols();
  CellStress3 c{Eigen::VectorXd(9 * m), Eigen::VectorXd(m)};
  for (Eigen::Index t = 0; t < m; ++t) {
    const double xx = s(0, t), yy = s(1, t), zz = s(2, t), xy = s(3, t), yz = s(4, t), xz = s(5, t);
    c.tensor.segment<9>(9 * t) << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    const double a = xx - yy, b = yy - zz, d = zz - xx;
    c.von_mises(t) = std::sqrt(0.5 * (a * a + b * b + d * d) + 3.0 * (xy * xy + yz * yz + xz * xz));
  }
  return c;
}

VtuFiles write_solution_vtus(const mesh::Mesh3& mesh, const std::vector<fem::Material>& materials,
                             const std::vector<cases::ParameterSpec>& parameters, const cases::Mu& mu,
                             const Eigen::VectorXd& u, const SlaveSurfaceFields& contact, const std::string& dir) {
  require(u.size() == mesh.num_dofs(), "write_solution_vtus: the displacement has " + std::to_string(u.size()) +
                                           " values, the mesh " + std::to_string(mesh.num_dofs()) + " DOFs");
  require(mu.size() == static_cast<Eigen::Index>(parameters.size()),
          "write_solution_vtus: " + std::to_string(mu.size()) + " parameter values for " +
              std::to_string(parameters.size()) + " parameters");
  check_rows(contact, mesh.num_nodes());
  const auto add_parameters = [&](io::VtuWriter& w) {
    for (std::size_t k = 0; k < parameters.size(); ++k) w.add_field_data(parameters[k].name, mu(static_cast<Eigen::Index>(k)));
  };
  const auto rows = static_cast<Eigen::Index>(contact.nodes.size());
  Eigen::VectorXd pressure = Eigen::VectorXd::Zero(mesh.num_nodes());
  Eigen::VectorXd slave_u(3 * rows);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index r = 0; r < rows; ++r) {
    const int node = contact.nodes[static_cast<std::size_t>(r)];
    pressure(node) = contact.pressure(r);
    slave_u.segment<3>(3 * r) = u.segment<3>(3 * node);
    points.push_back(mesh.nodes[static_cast<std::size_t>(node)]);
  }
  const CellStress3 stress = cell_stress(mesh, materials, u);

  const std::filesystem::path d(dir);
  VtuFiles files{(d / "solution.vtu").string(), (d / "solution_deformed.vtu").string(), (d / "contact.vtu").string()};
  io::VtuWriter vtu(mesh);
  vtu.add_point_vector("displacement", u)
      .add_point_scalar("contact_pressure", pressure)
      .add_cell_scalar("von_mises", stress.von_mises)
      .add_cell_field("stress", 9, stress.tensor);
  add_parameters(vtu);
  vtu.write(files.vtu);
  vtu.deform_by("displacement").write(files.deformed_vtu);

  io::VtuWriter surface = io::VtuWriter::triangles(std::move(points), slave_triangles(mesh, contact.nodes));
  surface.add_point_vector("displacement", slave_u)
      .add_point_scalar("contact_pressure", contact.pressure)
      .add_point_scalar("gap", contact.gap);
  add_parameters(surface);
  surface.write(files.contact_vtu);
  return files;
}

void write_multipliers_csv(const mesh::Mesh3& mesh, const SlaveSurfaceFields& contact, const std::string& path) {
  check_rows(contact, mesh.num_nodes());
  io::CsvWriter csv({"r", "x", "y", "z", "gap", "pressure", "weight"});
  for (std::size_t r = 0; r < contact.nodes.size(); ++r) {
    const Eigen::Vector3d& X = mesh.nodes[static_cast<std::size_t>(contact.nodes[r])];
    const auto i = static_cast<Eigen::Index>(r);
    csv.add_row({static_cast<long long>(r), X.x(), X.y(), X.z(), contact.gap(i), contact.pressure(i), contact.weight(i)});
  }
  csv.write(path);
}

}  // namespace contactrb::study
