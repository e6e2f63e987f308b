#include "contactrb/study/solution_fields.hpp"

#include <array>
#include <cmath>
#include <filesystem>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/recorded_mesh.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/vtu_writer.hpp"

namespace contactrb::study {

using model::ReducedModel;
using model::ReducedReconstruction;

mesh::Mesh model_reference_mesh(const cases::CaseSpec& spec, const ReducedModel& model,
                                const ReducedReconstruction& reconstruction, const std::string& origin) {
  return cases::recorded_reference_mesh(spec, {model.level, reconstruction.num_dofs, &reconstruction.mesh}, origin);
}

CellStress cell_stress(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials, const Eigen::VectorXd& u) {
  const Eigen::Matrix3Xd s = fem::element_stress(mesh, materials, u);  // checks the sizes
  const Eigen::Index m = s.cols();
  CellStress c{s.row(0).transpose(), s.row(1).transpose(), s.row(2).transpose(), Eigen::VectorXd(m),
               Eigen::VectorXd(m)};
  for (Eigen::Index t = 0; t < m; ++t) {
    const double nu = materials[static_cast<std::size_t>(mesh.body[static_cast<std::size_t>(t)])].nu;
    c.zz(t) = nu * (c.xx(t) + c.yy(t));  // eps_zz = 0 (plane strain)
    const double a = c.xx(t) - c.yy(t), b = c.yy(t) - c.zz(t), d = c.zz(t) - c.xx(t);
    c.von_mises(t) = std::sqrt(0.5 * (a * a + b * b + d * d) + 3.0 * c.xy(t) * c.xy(t));
  }
  return c;
}

Eigen::VectorXd nodal_pressure(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                               const contact::ContactQuadrature& quadrature, const Eigen::VectorXd& lambda) {
  require(lambda.size() == quadrature.W.rows(), "nodal_pressure: " + std::to_string(lambda.size()) +
                                                    " multipliers for " + std::to_string(quadrature.W.rows()) +
                                                    " constraint rows");
  require(quadrature.W.cols() == static_cast<Eigen::Index>(pair.slave.size()),
          "nodal_pressure: the quadrature has " + std::to_string(quadrature.W.cols()) + " columns for " +
              std::to_string(pair.slave.size()) + " slave nodes");
  Eigen::VectorXd pressure = Eigen::VectorXd::Zero(mesh.num_nodes());
  const Eigen::VectorXd num = quadrature.W.transpose() * lambda;
  const Eigen::VectorXd den = quadrature.W.transpose() * Eigen::VectorXd::Ones(quadrature.W.rows());
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const auto i = static_cast<Eigen::Index>(s);
    if (den(i) > 0.0) pressure(pair.slave[s]) = num(i) / den(i);
  }
  return pressure;
}

VtuFiles write_solution_vtus(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials,
                             const contact::ContactPair& pair, const contact::ContactQuadrature& quadrature,
                             const std::vector<cases::ParameterSpec>& parameters, const cases::Mu& mu,
                             const Eigen::VectorXd& u, const Eigen::VectorXd& lambda, const std::string& dir) {
  require(u.size() == mesh.num_dofs(), "write_solution_vtus: the displacement has " + std::to_string(u.size()) +
                                           " values, the mesh " + std::to_string(mesh.num_dofs()) + " DOFs");
  require(mu.size() == static_cast<Eigen::Index>(parameters.size()),
          "write_solution_vtus: " + std::to_string(mu.size()) + " parameter values for " +
              std::to_string(parameters.size()) + " parameters");
  const Eigen::VectorXd pressure = nodal_pressure(mesh, pair, quadrature, lambda);
  const CellStress stress = cell_stress(mesh, materials, u);
  const auto add_parameters = [&](io::VtuWriter& w) {
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      w.add_field_data(parameters[k].name, mu(static_cast<Eigen::Index>(k)));
    }
  };

  const std::filesystem::path d(dir);
  VtuFiles files{(d / "solution.vtu").string(), (d / "solution_deformed.vtu").string(), (d / "contact.vtu").string()};
  io::VtuWriter vtu(mesh);
  vtu.add_point_vector("displacement", u)
      .add_point_scalar("contact_pressure", pressure)
      .add_cell_scalar("von_mises", stress.von_mises)
      .add_cell_scalar("stress_xx", stress.xx)
      .add_cell_scalar("stress_yy", stress.yy)
      .add_cell_scalar("stress_xy", stress.xy)
      .add_cell_scalar("stress_zz", stress.zz);
  add_parameters(vtu);
  vtu.write(files.vtu);
  vtu.deform_by("displacement").write(files.deformed_vtu);

  // The slave chain: its nodes in chain order, its edges as line cells.
  const std::size_t S = pair.slave.size();
  const contact::ContactMaps maps = contact::evaluate_contact_maps(mesh, pair, quadrature, u);
  const Eigen::VectorXd gap = maps.pointwise.g - maps.pointwise.K * u;  // (28) - (27) at w = u
  std::vector<Eigen::Vector2d> points(S);
  std::vector<std::array<int, 2>> edges;
  Eigen::VectorXd slave_u(2 * static_cast<Eigen::Index>(S));
  Eigen::VectorXd slave_pressure(static_cast<Eigen::Index>(S));
  for (std::size_t s = 0; s < S; ++s) {
    const int node = pair.slave[s];
    const auto i = static_cast<Eigen::Index>(s);
    points[s] = mesh.nodes[static_cast<std::size_t>(node)];
    slave_u.segment<2>(2 * i) = u.segment<2>(2 * node);
    slave_pressure(i) = pressure(node);
    if (s + 1 < S) edges.push_back({static_cast<int>(s), static_cast<int>(s + 1)});
  }
  io::VtuWriter surface = io::VtuWriter::lines(std::move(points), std::move(edges));
  surface.add_point_vector("displacement", slave_u)
      .add_point_scalar("contact_pressure", slave_pressure)
      .add_point_scalar("gap", gap);
  add_parameters(surface);
  surface.write(files.contact_vtu);
  return files;
}

SolutionFiles solution_file_names(const std::string& dir) {
  const std::filesystem::path d(dir);
  return {(d / "solution.vtu").string(), (d / "solution_deformed.vtu").string(), (d / "contact.vtu").string(),
          (d / "multipliers.csv").string()};
}

SolutionFiles write_solution_fields(const cases::CaseSpec& spec, const mesh::Mesh& reference, const cases::Mu& mu,
                                    contact::Discretization discretization, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& lambda, const std::string& dir) {
  const mesh::Mesh m = cases::mapped_mesh(spec, reference, mu);
  require(u.size() == m.num_dofs(), "write_solution_fields: the displacement has " + std::to_string(u.size()) +
                                        " values, the mesh " + std::to_string(m.num_dofs()) + " DOFs");
  const contact::ContactPair pair = contact::make_contact_pair(m);
  const contact::ContactQuadrature q = contact::make_quadrature(m, pair, discretization);
  require(lambda.size() == q.weight.size(), "write_solution_fields: " + std::to_string(lambda.size()) +
                                                " multipliers for " + std::to_string(q.weight.size()) +
                                                " constraint rows");
  SolutionFiles files = solution_file_names(dir);
  const VtuFiles vtus =
      write_solution_vtus(m, cases::materials(spec, mu), pair, q, spec.parameters, mu, u, lambda, dir);
  files.vtu = vtus.vtu;
  files.deformed_vtu = vtus.deformed_vtu;
  files.contact_vtu = vtus.contact_vtu;

  io::CsvWriter csv({"r", "x", "y", "lambda"});
  for (Eigen::Index r = 0; r < lambda.size(); ++r) {
    const Eigen::Vector2d& X = reference.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])];
    csv.add_row({static_cast<long long>(r), X.x(), X.y(), lambda(r)});
  }
  csv.write(files.multipliers);
  return files;
}

}  // namespace contactrb::study
