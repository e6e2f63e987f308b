#include "contactrb/study/friction_fields.hpp"

#include <array>
#include <filesystem>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/vtu_writer.hpp"

namespace contactrb::study {

namespace {

inline std::size_t sz(Eigen::Index i) { return static_cast<std::size_t>(i); }

void check_sizes(const mesh::Mesh& mesh, const contact::ContactPair& pair, const contact::ContactQuadrature& q,
                 const hf::FrictionalSolution& s) {
  const auto R = q.weight.size();
  require(q.discretization == contact::Discretization::Collocation &&
              R == static_cast<Eigen::Index>(pair.slave.size()),
          "write_friction_fields: the frictional files need the collocation rows (one per slave node)");
  require(s.u.size() == mesh.num_dofs() && s.lambda.size() == R && s.lambda_t.size() == R && s.slip.size() == R &&
              static_cast<Eigen::Index>(s.state.size()) == R,
          "write_friction_fields: the solution has " + std::to_string(s.u.size()) + " displacements and " +
              std::to_string(s.lambda.size()) + " multipliers for " + std::to_string(mesh.num_dofs()) + " DOFs and " +
              std::to_string(R) + " rows");
}

double state_code(hf::SlipState state) {
  switch (state) {
    case hf::SlipState::Open: return 0.0;
    case hf::SlipState::Stick: return 1.0;
    case hf::SlipState::Slip: return 2.0;
  }
  return 0.0;
}

// The slave chain as line cells, with the tractions, the state and the slip of its rows.
void write_contact_vtu(const mesh::Mesh& mesh, const contact::ContactPair& pair, const hf::FrictionalSolution& s,
                       const std::string& path) {
  const std::size_t S = pair.slave.size();
  std::vector<Eigen::Vector2d> points(S);
  std::vector<std::array<int, 2>> edges;
  Eigen::VectorXd slave_u(2 * static_cast<Eigen::Index>(S)), state(static_cast<Eigen::Index>(S));
  for (std::size_t q = 0; q < S; ++q) {
    const int node = pair.slave[q];
    points[q] = mesh.nodes[static_cast<std::size_t>(node)];
    slave_u.segment<2>(2 * static_cast<Eigen::Index>(q)) = s.u.segment<2>(2 * node);
    state(static_cast<Eigen::Index>(q)) = state_code(s.state[q]);
    if (q + 1 < S) edges.push_back({static_cast<int>(q), static_cast<int>(q + 1)});
  }
  io::VtuWriter surface = io::VtuWriter::lines(std::move(points), std::move(edges));
  surface.add_point_vector("displacement", slave_u)
      .add_point_scalar("contact_pressure", s.lambda)
      .add_point_scalar("tangential_traction", s.lambda_t)
      .add_point_scalar("state", state)
      .add_point_scalar("slip", s.slip);
  surface.write(path);
}

}  // namespace

FrictionFiles write_friction_fields(const mesh::Mesh& mesh, const contact::ContactPair& pair,
                                    const contact::ContactQuadrature& quadrature,
                                    const hf::FrictionalSolution& solution, const std::string& dir) {
  check_sizes(mesh, pair, quadrature, solution);
  const std::filesystem::path d(dir);
  FrictionFiles files{(d / "solution.vtu").string(), (d / "solution_deformed.vtu").string(),
                      (d / "contact.vtu").string(), (d / "multipliers.csv").string()};
  io::VtuWriter vtu(mesh);
  vtu.add_point_vector("displacement", solution.u);
  vtu.write(files.vtu);
  vtu.deform_by("displacement").write(files.deformed_vtu);
  write_contact_vtu(mesh, pair, solution, files.contact_vtu);
  // The columns of `contactrb solve`'s multipliers.csv (no geometric map: abscissa = x), with the
  // tangential traction and the state before the weight.
  const Eigen::VectorXd gap = contact::evaluate_contact_maps(mesh, pair, quadrature, solution.u).d;
  io::CsvWriter csv({"r", "abscissa", "x", "y", "gap", "pressure", "tangential", "state", "weight"});
  for (Eigen::Index r = 0; r < solution.lambda.size(); ++r) {
    const Eigen::Vector2d& X = mesh.nodes[static_cast<std::size_t>(quadrature.center_node[sz(r)])];
    const double w = quadrature.weight(r);
    csv.add_row({static_cast<long long>(r), X.x(), X.x(), X.y(), gap(r) / w, solution.lambda(r), solution.lambda_t(r),
                 std::string(hf::to_string(solution.state[sz(r)])), w});
  }
  csv.write(files.multipliers);
  return files;
}

}  // namespace contactrb::study
