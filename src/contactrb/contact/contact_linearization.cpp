#include "contactrb/contact/contact_linearization.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_derivatives.hpp"
#include "contactrb/contact/lac3d.hpp"

namespace contactrb::contact {

namespace {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

void sort_unique(std::vector<int>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// The sparsity of H = d(K' lambda)/du: DOF i gets the columns of every loaded row r
// (lambda_r != 0) whose inputs hold i.
struct HessianPattern {
  std::vector<int> dof;                   // H row index -> DOF
  std::vector<std::vector<int>> columns;  // H row index -> columns
};

HessianPattern hessian_pattern(const std::vector<std::vector<int>>& inputs, const Eigen::VectorXd& lambda, int N) {
  HessianPattern hp;
  std::vector<int> h_row_of(static_cast<std::size_t>(N), -1);
  for (Eigen::Index r = 0; r < lambda.size(); ++r) {
    if (lambda(r) == 0.0) continue;
    const auto& in = inputs[static_cast<std::size_t>(r)];
    for (int i : in) {
      int& hr = h_row_of[static_cast<std::size_t>(i)];
      if (hr < 0) {
        hr = static_cast<int>(hp.dof.size());
        hp.dof.push_back(i);
        hp.columns.emplace_back();
      }
      auto& cols = hp.columns[static_cast<std::size_t>(hr)];
      cols.insert(cols.end(), in.begin(), in.end());
    }
  }
  for (auto& cols : hp.columns) sort_unique(cols);
  return hp;
}

// Greedy colouring: columns sharing an output row (a row of D or of H) get different colours,
// so that one pair of map evaluations per colour gives all their derivatives.
struct ColumnColouring {
  std::vector<int> columns;  // the DOFs some row depends on, increasing
  std::vector<int> compact;  // DOF -> index in columns (-1: none)
  std::vector<int> colour;   // per column
  int colours = 0;
  bool has(int j, int k) const {
    return colour[static_cast<std::size_t>(compact[static_cast<std::size_t>(j)])] == k;
  }
};

ColumnColouring colour_columns(const std::vector<std::vector<int>>& inputs, const HessianPattern& hp, int N) {
  const int R = static_cast<int>(inputs.size());
  ColumnColouring cc;
  for (const auto& in : inputs) cc.columns.insert(cc.columns.end(), in.begin(), in.end());
  sort_unique(cc.columns);
  cc.compact.assign(static_cast<std::size_t>(N), -1);
  for (std::size_t c = 0; c < cc.columns.size(); ++c) cc.compact[static_cast<std::size_t>(cc.columns[c])] = static_cast<int>(c);
  std::vector<std::vector<int>> column_outputs(cc.columns.size());  // output rows: r, or R + H row
  for (int r = 0; r < R; ++r) {
    for (int j : inputs[static_cast<std::size_t>(r)]) column_outputs[static_cast<std::size_t>(cc.compact[static_cast<std::size_t>(j)])].push_back(r);
  }
  for (std::size_t hr = 0; hr < hp.columns.size(); ++hr) {
    for (int j : hp.columns[hr]) {
      column_outputs[static_cast<std::size_t>(cc.compact[static_cast<std::size_t>(j)])].push_back(R + static_cast<int>(hr));
    }
  }
  std::vector<std::vector<int>> output_colours(static_cast<std::size_t>(R) + hp.columns.size());
  cc.colour.assign(cc.columns.size(), -1);
  std::vector<char> forbidden;
  for (std::size_t c = 0; c < cc.columns.size(); ++c) {
    forbidden.assign(static_cast<std::size_t>(cc.colours) + 1, 0);
    for (int o : column_outputs[c]) {
      for (int k : output_colours[static_cast<std::size_t>(o)]) forbidden[static_cast<std::size_t>(k)] = 1;
    }
    int k = 0;
    while (forbidden[static_cast<std::size_t>(k)]) ++k;
    cc.colour[c] = k;
    cc.colours = std::max(cc.colours, k + 1);
    for (int o : column_outputs[c]) output_colours[static_cast<std::size_t>(o)].push_back(k);
  }
  return cc;
}

// The difference step: relative to the mean reference slave edge length.
double difference_step(const mesh::Mesh& mesh, const ContactPair& pair, double relative_step) {
  double edges = 0.0;
  for (std::size_t p = 0; p + 1 < pair.slave.size(); ++p) {
    edges += (mesh.nodes[static_cast<std::size_t>(pair.slave[p + 1])] - mesh.nodes[static_cast<std::size_t>(pair.slave[p])]).norm();
  }
  const double h = relative_step * edges / static_cast<double>(std::max<std::size_t>(1, pair.slave.size() - 1));
  require(h > 0.0, "linearize_contact: the slave boundary has zero length");
  return h;
}

// 3D: relative to the mean edge length of the reference slave triangles.
double difference_step(const mesh::Mesh3& mesh, const ContactPair3& pair, double relative_step) {
  double edges = 0.0;
  for (const mesh::Face& f : pair.slave_faces) {
    const auto v = f.vertices();
    for (int i = 0; i < 3; ++i) {
      edges += (mesh.nodes[static_cast<std::size_t>(v[static_cast<std::size_t>((i + 1) % 3)])] -
                mesh.nodes[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])])
                   .norm();
    }
  }
  const double h = relative_step * edges / static_cast<double>(std::max<std::size_t>(1, 3 * pair.slave_faces.size()));
  require(h > 0.0, "linearize_contact: the slave surface has zero area");
  return h;
}

// The columns of colour k of `v` set to u + shift, or back to u.
void shift_colour(const ColumnColouring& cc, int k, const Eigen::VectorXd& u, double shift, Eigen::VectorXd& v) {
  for (std::size_t c = 0; c < cc.columns.size(); ++c) {
    if (cc.colour[c] == k) v(cc.columns[c]) = u(cc.columns[c]) + shift;
  }
}
void restore_colour(const ColumnColouring& cc, int k, const Eigen::VectorXd& u, Eigen::VectorXd& v) {
  for (std::size_t c = 0; c < cc.columns.size(); ++c) {
    if (cc.colour[c] == k) v(cc.columns[c]) = u(cc.columns[c]);
  }
}

// The maps at u (both dimensions: project_slave_nodes and constraint_rows of the mesh's own).
template <int Dim>
ContactMapsOf<Dim> maps_at(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                           const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                           const ProjectionOptions& options) {
  ContactMapsOf<Dim> maps;
  maps.pointwise = project_slave_nodes(mesh, pair, u, options);
  maps.rows = constraint_rows(mesh, pair, quadrature, maps.pointwise, u);
  maps.d = maps.rows.g - maps.rows.K * u;
  return maps;
}

// The rows each colour moves: those whose inputs hold a column of the colour.
std::vector<std::vector<int>> rows_of_colours(const std::vector<std::vector<int>>& inputs, const ColumnColouring& cc) {
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(cc.colours));
  for (std::size_t r = 0; r < inputs.size(); ++r) {
    for (int j : inputs[r]) {
      auto& of = rows[static_cast<std::size_t>(cc.colour[static_cast<std::size_t>(cc.compact[static_cast<std::size_t>(j)])])];
      if (of.empty() || of.back() != static_cast<int>(r)) of.push_back(static_cast<int>(r));
    }
  }
  return rows;
}

// The maps at a perturbed u on the rows a colour moves (the others may be zero): the 3D LAC
// rows integrate those rows' cells only (integrate_lac_rows on a row subset, the projections of
// their triangles' vertices), every other discretization evaluates all rows.
template <int Dim>
ContactMapsOf<Dim> maps_on_rows(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                                const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                const std::vector<int>& rows, const ProjectionOptions& options) {
  if constexpr (Dim == 3) {
    if (quadrature.discretization == Discretization::LAC) {
      ContactMapsOf<Dim> maps;
      maps.pointwise = project_slave_nodes(mesh, pair, u, lac_slave_positions(pair, rows), options);
      maps.rows = integrate_lac_rows(mesh, pair, quadrature, maps.pointwise, u, rows);
      maps.d = maps.rows.g - maps.rows.K * u;
      return maps;
    }
  }
  return maps_at(mesh, pair, quadrature, u, options);
}

// D = dd/du and H = d(K' lambda)/du by central differences, one pair of map evaluations per colour.
template <int Dim>
void central_differences(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                         const ContactQuadrature& quadrature,
                         const Eigen::VectorXd& u, const Eigen::VectorXd& lambda,
                         const std::vector<std::vector<int>>& inputs, const HessianPattern& hp,
                         const ColumnColouring& cc, double h, const LinearizationOptions& options,
                         ContactLinearizationOf<Dim>& lin) {
  const int N = mesh.num_dofs();
  const int R = static_cast<int>(inputs.size());
  std::vector<Eigen::Triplet<double>> d_trip, h_trip;
  const std::vector<std::vector<int>> moved = rows_of_colours(inputs, cc);
  Eigen::VectorXd up = u, um = u;
  for (int k = 0; k < cc.colours; ++k) {
    shift_colour(cc, k, u, h, up);
    shift_colour(cc, k, u, -h, um);
    const auto& rows = moved[static_cast<std::size_t>(k)];
    const ContactMapsOf<Dim> plus = maps_on_rows(mesh, pair, quadrature, up, rows, options.projection);
    const ContactMapsOf<Dim> minus = maps_on_rows(mesh, pair, quadrature, um, rows, options.projection);
    lin.evaluations += 2;
    restore_colour(cc, k, u, up);
    restore_colour(cc, k, u, um);
    const Eigen::VectorXd dd = (plus.d - minus.d) / (2.0 * h);
    for (int r = 0; r < R; ++r) {
      for (int j : inputs[static_cast<std::size_t>(r)]) {
        if (cc.has(j, k) && dd(r) != 0.0) d_trip.emplace_back(r, j, dd(r));
      }
    }
    if (hp.columns.empty()) continue;
    const Eigen::VectorXd df =
        (plus.rows.K.transpose() * lambda - minus.rows.K.transpose() * lambda) / (2.0 * h);
    for (std::size_t hr = 0; hr < hp.columns.size(); ++hr) {
      const int i = hp.dof[hr];
      if (df(i) == 0.0) continue;
      for (int j : hp.columns[hr]) {
        if (cc.has(j, k)) h_trip.emplace_back(i, j, df(i));
      }
    }
  }
  lin.D.resize(R, N);
  lin.D.setFromTriplets(d_trip.begin(), d_trip.end());
  lin.H.resize(N, N);
  lin.H.setFromTriplets(h_trip.begin(), h_trip.end());
}

template <int Dim>
void check_linearization_input(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                               const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                               const ContactMapsOf<Dim>& maps_at_u,
                               const LinearizationOptions& options) {
  const int N = mesh.num_dofs();
  const int R = static_cast<int>(quadrature.W.rows());
  require(u.size() == N, "linearize_contact: u has " + std::to_string(u.size()) + " entries for " +
                             std::to_string(N) + " DOFs");
  require(lambda.size() == R, "linearize_contact: lambda has " + std::to_string(lambda.size()) + " entries for " +
                                  std::to_string(R) + " constraint rows");
  require(static_cast<int>(movable.size()) == N, "linearize_contact: movable mask has " +
                                                     std::to_string(movable.size()) + " entries for " +
                                                     std::to_string(N) + " DOFs");
  require(maps_at_u.d.size() == R && static_cast<int>(maps_at_u.pointwise.projection.size()) ==
                                         static_cast<int>(pair.slave.size()),
          "linearize_contact: the maps at u have " + std::to_string(maps_at_u.d.size()) + " rows and " +
              std::to_string(maps_at_u.pointwise.projection.size()) + " projections for " + std::to_string(R) +
              " constraint rows and " + std::to_string(pair.slave.size()) + " slave nodes");
  require(options.relative_step > 0.0, "linearize_contact: relative_step must be > 0");
}

// The movable DOFs of each row (contact_derivatives.hpp).
std::vector<std::vector<int>> inputs_of(const ContactPair& pair, const ContactQuadrature& quadrature,
                                        const ContactMaps& maps, const std::vector<char>& movable) {
  return detail::row_inputs(pair, quadrature, maps.pointwise, movable);
}
std::vector<std::vector<int>> inputs_of(const ContactPair3& pair, const ContactQuadrature& quadrature,
                                        const ContactMaps3& maps, const std::vector<char>& movable) {
  if (quadrature.discretization == Discretization::LAC) {
    return detail::lac_row_inputs(pair, quadrature, maps.pointwise, maps.rows, movable);
  }
  return detail::row_inputs(pair, quadrature, maps.pointwise, movable);
}

// The analytic method covers every row but the clipped 3D LAC rows (docs/solvers.md, "Three
// dimensions"): those take the coloured differences whatever the options say.
template <int Dim>
bool analytic_rows(const ContactQuadrature& quadrature) {
  return Dim == 2 || quadrature.discretization != Discretization::LAC;
}

// linearize_contact with the maps at u given, in either dimension.
template <int Dim>
ContactLinearizationOf<Dim> linearize(const mesh::SimplexMesh<Dim>& mesh, const ContactPairOf<Dim>& pair,
                                      const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                      const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                      ContactMapsOf<Dim> maps_at_u, const LinearizationOptions& options) {
  check_linearization_input(mesh, pair, quadrature, u, lambda, movable, maps_at_u, options);
  ContactLinearizationOf<Dim> lin;
  lin.maps = std::move(maps_at_u);
  if (options.method == LinearizationMethod::Analytic && analytic_rows<Dim>(quadrature)) {
    detail::analytic_linearization(mesh, pair, quadrature, u, lambda, movable, lin);
    return lin;
  }
  const std::vector<std::vector<int>> inputs = inputs_of(pair, quadrature, lin.maps, movable);
  const HessianPattern hp = hessian_pattern(inputs, lambda, mesh.num_dofs());
  const ColumnColouring cc = colour_columns(inputs, hp, mesh.num_dofs());
  lin.colours = cc.colours;
  const double h = difference_step(mesh, pair, options.relative_step);
  central_differences(mesh, pair, quadrature, u, lambda, inputs, hp, cc, h, options, lin);
  return lin;
}

}  // namespace

ContactMaps evaluate_contact_maps(const mesh::Mesh& mesh, const ContactPair& pair, const ContactQuadrature& quadrature,
                                  const Eigen::VectorXd& u, const ProjectionOptions& options) {
  return maps_at(mesh, pair, quadrature, u, options);
}

ContactMaps3 evaluate_contact_maps(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                   const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                   const ProjectionOptions& options) {
  return maps_at(mesh, pair, quadrature, u, options);
}

ContactLinearization linearize_contact(const mesh::Mesh& mesh, const ContactPair& pair,
                                       const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                       const LinearizationOptions& options) {
  require(u.size() == mesh.num_dofs(), "linearize_contact: u has " + std::to_string(u.size()) + " entries for " +
                                           std::to_string(mesh.num_dofs()) + " DOFs");
  return linearize_contact(mesh, pair, quadrature, u, lambda, movable,
                           evaluate_contact_maps(mesh, pair, quadrature, u, options.projection), options);
}

ContactLinearization linearize_contact(const mesh::Mesh& mesh, const ContactPair& pair,
                                       const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                       const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                       ContactMaps maps_at_u, const LinearizationOptions& options) {
  return linearize(mesh, pair, quadrature, u, lambda, movable, std::move(maps_at_u), options);
}

ContactLinearization3 linearize_contact(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                        const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                        const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                        const LinearizationOptions& options) {
  require(u.size() == mesh.num_dofs(), "linearize_contact: u has " + std::to_string(u.size()) + " entries for " +
                                           std::to_string(mesh.num_dofs()) + " DOFs");
  return linearize_contact(mesh, pair, quadrature, u, lambda, movable,
                           evaluate_contact_maps(mesh, pair, quadrature, u, options.projection), options);
}

ContactLinearization3 linearize_contact(const mesh::Mesh3& mesh, const ContactPair3& pair,
                                        const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                        const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                        ContactMaps3 maps_at_u, const LinearizationOptions& options) {
  return linearize(mesh, pair, quadrature, u, lambda, movable, std::move(maps_at_u), options);
}

bool same_branch(const SlaveProjection& a, const SlaveProjection& b) {
  if (a.candidate != b.candidate) return false;
  const auto clamp = [](double xi) { return xi == 0.0 ? 0 : xi == 1.0 ? 1 : 2; };
  if (a.segment == b.segment) return clamp(a.xi) == clamp(b.xi);
  return (a.segment + 1 == b.segment && a.xi == 1.0 && b.xi == 0.0) ||
         (b.segment + 1 == a.segment && b.xi == 1.0 && a.xi == 0.0);
}

ContactLinearization linearize_contact_on_branches(const mesh::Mesh& mesh, const ContactPair& pair,
                                                   const ContactQuadrature& quadrature, const Eigen::VectorXd& u,
                                                   const Eigen::VectorXd& lambda, const std::vector<char>& movable,
                                                   const PointwiseContact& branches) {
  require(quadrature.discretization != Discretization::LAC,
          "linearize_contact_on_branches: the exactly integrated LAC rows have no pointwise branches");
  require(u.size() == mesh.num_dofs() && branches.projection.size() == pair.slave.size(),
          "linearize_contact_on_branches: u has " + std::to_string(u.size()) + " entries for " +
              std::to_string(mesh.num_dofs()) + " DOFs and " + std::to_string(branches.projection.size()) +
              " branches for " + std::to_string(pair.slave.size()) + " slave nodes");
  ContactMaps maps;
  maps.pointwise = detail::pointwise_on_branches(mesh, pair, u, branches);
  maps.rows = constraint_rows(mesh, pair, quadrature, maps.pointwise, u);
  maps.d = maps.rows.g - maps.rows.K * u;
  return linearize_contact(mesh, pair, quadrature, u, lambda, movable, std::move(maps));
}

const char* to_string(LinearizationMethod value) {
  switch (value) {
    case LinearizationMethod::Analytic: return "analytic";
    case LinearizationMethod::FiniteDifference: return "finite-difference";
  }
  return "unknown";
}

LinearizationMethod linearization_method_from_string(const std::string& name) {
  using enum LinearizationMethod;
  return enum_from_string(name, "linearization method", std::array{Analytic, FiniteDifference});
}

}  // namespace contactrb::contact
