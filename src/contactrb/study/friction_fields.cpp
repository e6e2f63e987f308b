#include "contactrb/study/friction_fields.hpp"

#include <array>
#include <filesystem>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_linearization.hpp"
#include "contactrb/contact/tangential_rows.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/pvd_writer.hpp"
#include "contactrb/io/vtu_writer.hpp"
#include "contactrb/study/solution_fields_3d.hpp"

namespace contactrb::study {

namespace {

inline std::size_t sz(Eigen::Index i) { return static_cast<std::size_t>(i); }

template <int Dim>
void check_sizes(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactPairOf<Dim>& pair,
                 const contact::ContactQuadrature& q, const hf::BasicFrictionalSolution<Dim>& s) {
  const auto R = q.weight.size();
  require(q.discretization == contact::Discretization::Collocation &&
              R == static_cast<Eigen::Index>(pair.slave.size()) && q.center_node.size() == pair.slave.size(),
          "write_friction_fields: the frictional files need the collocation rows (one per slave node)");
  require(s.u.size() == mesh.num_dofs() && s.lambda.size() == R && s.lambda_t.size() == (Dim - 1) * R &&
              s.slip.size() == (Dim - 1) * R && static_cast<Eigen::Index>(s.state.size()) == R,
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

// The cells of contact.vtu on its points (the rows' slave nodes, in row order): 2D, the slave
// chain's segments; 3D, the slave triangles.
io::VtuWriter contact_surface(const mesh::Mesh& mesh, const contact::ContactQuadrature& q) {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<int, 2>> edges;
  for (std::size_t r = 0; r < q.center_node.size(); ++r) {
    points.push_back(mesh.nodes[static_cast<std::size_t>(q.center_node[r])]);
    if (r + 1 < q.center_node.size()) edges.push_back({static_cast<int>(r), static_cast<int>(r + 1)});
  }
  return io::VtuWriter::lines(std::move(points), std::move(edges));
}

io::VtuWriter contact_surface(const mesh::Mesh3& mesh, const contact::ContactQuadrature& q) {
  std::vector<Eigen::Vector3d> points;
  for (int node : q.center_node) points.push_back(mesh.nodes[static_cast<std::size_t>(node)]);
  return io::VtuWriter::triangles(std::move(points), slave_triangles(mesh, q.center_node));
}

// A tangential field of Dim - 1 components per row as a VTU array: 2D, the signed value along
// tau; 3D, the vector sum_j v_j tau_j (tau at the projection of the row's node at u,
// contact::tangent_basis).
template <int Dim>
void add_tangential(io::VtuWriter& w, const std::string& name, const Eigen::VectorXd& v,
                    const contact::PointwiseContactOf<Dim>& at_u) {
  if constexpr (Dim == 2) {
    w.add_point_scalar(name, v);
  } else {
    const auto R = static_cast<Eigen::Index>(at_u.projection.size());
    Eigen::VectorXd cartesian(3 * R);
    for (Eigen::Index r = 0; r < R; ++r) {
      const Eigen::Matrix<double, 3, 2> tau = contact::tangent_basis<3>(at_u.projection[sz(r)].normal);
      cartesian.segment<3>(3 * r) = tau * v.segment<2>(2 * r);
    }
    w.add_point_vector(name, cartesian);
  }
}

template <int Dim>
void write_contact_vtu(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactQuadrature& q,
                       const hf::BasicFrictionalSolution<Dim>& s, const contact::PointwiseContactOf<Dim>& at_u,
                       const std::string& path) {
  const auto R = static_cast<Eigen::Index>(q.center_node.size());
  Eigen::VectorXd slave_u(Dim * R), state(R);
  for (Eigen::Index r = 0; r < R; ++r) {
    slave_u.segment<Dim>(Dim * r) = s.u.template segment<Dim>(Dim * q.center_node[sz(r)]);
    state(r) = state_code(s.state[sz(r)]);
  }
  io::VtuWriter surface = contact_surface(mesh, q);
  surface.add_point_vector("displacement", slave_u).add_point_scalar("contact_pressure", s.lambda);
  add_tangential<Dim>(surface, "tangential_traction", s.lambda_t, at_u);
  surface.add_point_scalar("state", state);
  add_tangential<Dim>(surface, "slip", s.slip, at_u);
  surface.write(path);
}

// solution.vtu and contact.vtu (names.vtu, names.contact_vtu), the deformed configuration when
// names.deformed_vtu is not empty; the contact maps at u for the caller.
template <int Dim>
contact::ContactMapsOf<Dim> write_vtus(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactPairOf<Dim>& pair,
                                       const contact::ContactQuadrature& q, const hf::BasicFrictionalSolution<Dim>& s,
                                       const FrictionFiles& names) {
  check_sizes(mesh, pair, q, s);
  io::VtuWriter vtu(mesh);
  vtu.add_point_vector("displacement", s.u);
  vtu.write(names.vtu);
  if (!names.deformed_vtu.empty()) vtu.deform_by("displacement").write(names.deformed_vtu);
  contact::ContactMapsOf<Dim> maps = contact::evaluate_contact_maps(mesh, pair, q, s.u);
  write_contact_vtu(mesh, q, s, maps.pointwise, names.contact_vtu);
  return maps;
}

// The columns of `contactrb solve`'s multipliers.csv (2D: no geometric map, abscissa = x; 3D:
// no abscissa), with the tangential traction and the state before the weight.
template <int Dim>
void write_multipliers(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactQuadrature& q,
                       const hf::BasicFrictionalSolution<Dim>& s, const Eigen::VectorXd& gap, const std::string& path) {
  std::vector<std::string> columns{"r"};
  if (Dim == 2) columns.push_back("abscissa");
  const std::array<const char*, 3> axes{"x", "y", "z"};
  for (int k = 0; k < Dim; ++k) columns.push_back(axes[static_cast<std::size_t>(k)]);
  for (const char* c : {"gap", "pressure"}) columns.push_back(c);
  if (Dim == 2) {
    columns.push_back("tangential");
  } else {
    for (const char* c : {"tangential_1", "tangential_2"}) columns.push_back(c);
  }
  for (const char* c : {"state", "weight"}) columns.push_back(c);
  io::CsvWriter csv(std::move(columns));
  for (Eigen::Index r = 0; r < s.lambda.size(); ++r) {
    const auto& X = mesh.nodes[static_cast<std::size_t>(q.center_node[sz(r)])];
    const double w = q.weight(r);
    std::vector<io::CsvCell> row{static_cast<long long>(r)};
    if (Dim == 2) row.emplace_back(X.x());
    for (int k = 0; k < Dim; ++k) row.emplace_back(X(k));
    row.emplace_back(gap(r) / w);
    row.emplace_back(s.lambda(r));
    for (int j = 0; j < Dim - 1; ++j) row.emplace_back(s.lambda_t((Dim - 1) * r + j));
    row.emplace_back(std::string(hf::to_string(s.state[sz(r)])));
    row.emplace_back(w);
    csv.add_row(std::move(row));
  }
  csv.write(path);
}

}  // namespace

template <int Dim>
FrictionFiles write_friction_fields(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactPairOf<Dim>& pair,
                                    const contact::ContactQuadrature& quadrature,
                                    const hf::BasicFrictionalSolution<Dim>& solution, const std::string& dir) {
  const std::filesystem::path d(dir);
  FrictionFiles files{(d / "solution.vtu").string(), (d / "solution_deformed.vtu").string(),
                      (d / "contact.vtu").string(), (d / "multipliers.csv").string()};
  const contact::ContactMapsOf<Dim> maps = write_vtus(mesh, pair, quadrature, solution, files);
  write_multipliers(mesh, quadrature, solution, maps.d, files.multipliers);
  return files;
}

template <int Dim>
FrictionStepSeries<Dim>::FrictionStepSeries(const mesh::SimplexMesh<Dim>& mesh, const contact::ContactPairOf<Dim>& pair,
                                             const contact::ContactQuadrature& quadrature)
    : mesh_(&mesh), pair_(&pair), quadrature_(&quadrature) {}

template <int Dim>
void FrictionStepSeries<Dim>::add(std::size_t step, const hf::BasicFrictionalSolution<Dim>& state) {
  check_sizes(*mesh_, *pair_, *quadrature_, state);
  Step s{step, {}};
  s.state.u = state.u;
  s.state.lambda = state.lambda;
  s.state.lambda_t = state.lambda_t;
  s.state.slip = state.slip;
  s.state.state = state.state;
  steps_.push_back(std::move(s));
}

template <int Dim>
FrictionStepFiles FrictionStepSeries<Dim>::write(const std::string& dir) const {
  const std::filesystem::path d(dir);
  std::filesystem::create_directories(d / "steps");
  FrictionStepFiles files{(d / "solution_steps.pvd").string(), (d / "contact_steps.pvd").string(), {}};
  std::vector<io::PvdDataSet> solution, surface;
  for (const Step& s : steps_) {
    const std::string k = std::to_string(s.index + 1);
    const std::string vtu = "steps/solution_" + k + ".vtu", contact_vtu = "steps/contact_" + k + ".vtu";
    write_vtus(*mesh_, *pair_, *quadrature_, s.state, {(d / vtu).string(), "", (d / contact_vtu).string(), ""});
    solution.push_back({static_cast<double>(s.index + 1), vtu});
    surface.push_back({static_cast<double>(s.index + 1), contact_vtu});
    files.vtus.push_back((d / vtu).string());
    files.vtus.push_back((d / contact_vtu).string());
  }
  io::write_pvd(files.solution_pvd, solution);
  io::write_pvd(files.contact_pvd, surface);
  return files;
}

template FrictionFiles write_friction_fields(const mesh::SimplexMesh<2>&, const contact::ContactPairOf<2>&,
                                             const contact::ContactQuadrature&, const hf::BasicFrictionalSolution<2>&,
                                             const std::string&);
template FrictionFiles write_friction_fields(const mesh::SimplexMesh<3>&, const contact::ContactPairOf<3>&,
                                             const contact::ContactQuadrature&, const hf::BasicFrictionalSolution<3>&,
                                             const std::string&);
template class FrictionStepSeries<2>;
template class FrictionStepSeries<3>;

}  // namespace contactrb::study
