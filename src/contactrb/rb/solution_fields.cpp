#include "contactrb/rb/solution_fields.hpp"

#include <filesystem>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/vtu_writer.hpp"

namespace contactrb::rb {

mesh::Mesh model_reference_mesh(const cases::CaseSpec& spec, const ReducedModel& model,
                                const ReducedReconstruction& reconstruction) {
  mesh::Mesh reference = cases::reference_mesh(spec, model.level);
  require(reference.num_dofs() == reconstruction.num_dofs,
          "the mesh of case '" + spec.name + "' at level " + std::to_string(model.level) + " has " +
              std::to_string(reference.num_nodes()) + " nodes (" + std::to_string(reference.num_dofs()) +
              " DOFs), the model's reconstruction data " + std::to_string(reconstruction.num_dofs) +
              " DOFs: the case's mesh changed since the model was built (rebuild the snapshots and the model)");
  return reference;
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
  Eigen::VectorXd pressure = Eigen::VectorXd::Zero(m.num_nodes());
  const Eigen::VectorXd num = q.W.transpose() * lambda;
  const Eigen::VectorXd den = q.W.transpose() * Eigen::VectorXd::Ones(q.W.rows());
  for (std::size_t s = 0; s < pair.slave.size(); ++s) {
    const auto i = static_cast<Eigen::Index>(s);
    if (den(i) > 0.0) pressure(pair.slave[s]) = num(i) / den(i);
  }

  const std::filesystem::path d(dir);
  SolutionFiles files{(d / "solution.vtu").string(), (d / "solution_deformed.vtu").string(),
                      (d / "multipliers.csv").string()};
  io::VtuWriter vtu(m);
  vtu.add_point_vector("displacement", u).add_point_scalar("contact_pressure", pressure);
  vtu.write(files.vtu);
  vtu.deform_by("displacement").write(files.deformed_vtu);

  io::CsvWriter csv({"r", "x", "y", "lambda"});
  for (Eigen::Index r = 0; r < lambda.size(); ++r) {
    const Eigen::Vector2d& X = reference.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])];
    csv.add_row({static_cast<long long>(r), X.x(), X.y(), lambda(r)});
  }
  csv.write(files.multipliers);
  return files;
}

}  // namespace contactrb::rb
