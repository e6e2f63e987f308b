#include "contactrb/cases/case_problem.hpp"

#include <utility>

#include "contactrb/cases/catalog.hpp"
#include "contactrb/cases/geometric_map.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/fem/traction.hpp"
#include "contactrb/mesh/geometries.hpp"
#include "contactrb/mesh/msh_io.hpp"
#include "contactrb/mesh/structured.hpp"

namespace contactrb::cases {

namespace {

std::string context(const CaseSpec& spec) { return spec.context(); }

std::string body_name(int body) { return body == 0 ? "slave" : "master"; }

// Renames the user's contact groups to "slave" / "master" (a swap is allowed).
template <int Dim>
void map_contact_groups(mesh::SimplexMesh<Dim>& m, const MeshSpec& ms) {
  auto slave = m.boundary(ms.slave_group);
  auto master = m.boundary(ms.master_group);
  m.boundaries.erase(ms.slave_group);
  m.boundaries.erase(ms.master_group);
  for (const char* name : {mesh::kSlaveBoundary, mesh::kMasterBoundary}) {
    require(!m.has_boundary(name), "the .msh file " + ms.msh_file + " has a group '" + name +
                                       "' that is not the contact group named in the case; rename it");
  }
  m.boundaries[mesh::kSlaveBoundary] = std::move(slave);
  m.boundaries[mesh::kMasterBoundary] = std::move(master);
}

// mesh::stacked_blocks' finest level.
constexpr int kMaxStackedBlocksLevel = 4;

// The case's .msh file as a Dim-dimensional mesh with its contact groups renamed and its
// Dirichlet groups present.
template <int Dim>
mesh::SimplexMesh<Dim> mesh_from_file(const CaseSpec& spec, int level) {
  const MeshSpec& ms = spec.mesh;
  require(level == 0, "refinement level " + std::to_string(level) + " requested, but the mesh of " + context(spec) +
                          " is the file " + ms.msh_file + " (level 0 only)");
  mesh::MshGroups groups;
  groups.body_groups = {ms.body_groups[0], ms.body_groups[1]};
  groups.required_boundaries = {ms.slave_group, ms.master_group};
  mesh::SimplexMesh<Dim> m;
  if constexpr (Dim == 2) {
    m = mesh::read_msh(ms.msh_file, groups);
  } else {
    m = mesh::read_msh3(ms.msh_file, groups);
  }
  require(m.num_bodies() == 2, "the .msh file " + ms.msh_file + " of " + context(spec) + " has " +
                                   std::to_string(m.num_bodies()) + " body, a contact case needs two");
  map_contact_groups(m, ms);
  for (const DirichletSpec& d : spec.dirichlet) {
    if (!m.has_boundary(d.group)) {
      std::string present;
      for (const auto& [name, facets] : m.boundaries) present += " " + name;
      throw Error("Dirichlet group '" + d.group + "' of " + context(spec) + " is not a " + std::to_string(Dim - 1) +
                  "D physical group of " + ms.msh_file + " (groups:" + present + ")");
    }
  }
  mesh::validate(m);
  return m;
}

// "hertz-3d" and "stacked-blocks" at `level` (case_problem.hpp, reference_mesh3).
mesh::Mesh3 generated_mesh3(const std::string& generator, int level) {
  if (generator == "hertz-3d") {
    mesh::Hertz3dGeometry geometry;
    geometry.fine_size = mesh::hertz_3d_fine_size_for_level(level);
    return mesh::generate_hertz_3d(geometry);
  }
  require(level <= kMaxStackedBlocksLevel, "the stacked-blocks mesh level must be in [0, " +
                                              std::to_string(kMaxStackedBlocksLevel) + "] (got " +
                                              std::to_string(level) + ")");
  mesh::Mesh3 m = mesh::stacked_blocks(level);
  for (const auto& [group, axis] : {std::pair{"symmetry_x", 0}, std::pair{"symmetry_y", 1}}) {
    auto& plane = m.boundaries[group];
    for (const char* sides : {"slave_sides", "master_sides"}) {
      for (const mesh::Face& f : m.boundary(sides)) {
        bool on_plane = true;
        for (int v : f.vertices()) on_plane = on_plane && m.nodes[static_cast<std::size_t>(v)](axis) == 0.0;
        if (on_plane) plane.push_back(f);
      }
    }
  }
  return m;
}

void check_no_uz(const CaseSpec& spec) {
  for (const DirichletSpec& d : spec.dirichlet) {
    require(!d.uz, "Dirichlet condition on '" + d.group + "' of " + context(spec) +
                       " gives uz, but the case is two-dimensional (its mesh has triangles)");
  }
}

}  // namespace

mesh::Mesh3 reference_mesh3(const CaseSpec& spec, int level) {
  check_case_spec(spec);
  require(level >= 0, "refinement level must be >= 0 (got " + std::to_string(level) + ")");
  require(case_dimension(spec) == 3, context(spec) + " is two-dimensional (its mesh has triangles), not 3D");
  require(spec.tractions.empty() && spec.bodies[0].load.isZero(0.0) && spec.bodies[1].load.isZero(0.0),
          context(spec) + " is three-dimensional: its loads are Dirichlet data only (tractions and body loads "
                          "are read in 2D cases)");
  for (const ParameterSpec& p : spec.parameters) {
    require(p.kind != ParameterKind::BodyScaling, context(spec) + " is three-dimensional: parameter '" + p.name +
                                                      "' of kind body-scaling is read in 2D cases only");
  }
  mesh::Mesh3 m = spec.mesh.generator.empty() ? mesh_from_file<3>(spec, level) : generated_mesh3(spec.mesh.generator, level);
  for (const DirichletSpec& d : spec.dirichlet) m.boundary(d.group);  // throws naming a missing group
  mesh::validate(m);
  return m;
}

mesh::Mesh reference_mesh(const CaseSpec& spec, int level) {
  check_case_spec(spec);
  require(level >= 0, "refinement level must be >= 0 (got " + std::to_string(level) + ")");
  require(case_dimension(spec) == 2, context(spec) + " is three-dimensional (its mesh has tetrahedra): this "
                                                     "operation supports 2D cases only");
  check_no_uz(spec);
  const MeshSpec& ms = spec.mesh;
  if (ms.generator == "hertz") {
    mesh::HertzGeometry geometry;
    geometry.slave_arc_nodes = mesh::hertz_arc_nodes_for_level(level);
    mesh::Mesh m = mesh::generate_hertz(geometry);
    check_tractions(spec, m);
    return m;
  }
  if (ms.generator == "ring-block") {
    mesh::RingBlockGeometry geometry;
    const int factor = 1 << level;
    geometry.slave_arc_nodes = (geometry.slave_arc_nodes - 1) * factor + 1;
    geometry.master_edge_nodes = (geometry.master_edge_nodes - 1) * factor + 1;
    mesh::Mesh m = mesh::generate_ring_block(geometry);
    check_tractions(spec, m);
    return m;
  }
  mesh::Mesh m = mesh_from_file<2>(spec, level);
  check_tractions(spec, m);
  return m;
}

void check_tractions(const CaseSpec& spec, const mesh::Mesh& reference) {
  for (const TractionSpec& t : spec.tractions) {
    if (!reference.has_boundary(t.group)) {
      std::string present;
      for (const auto& [name, edges] : reference.boundaries) present += " " + name;
      throw Error("traction group '" + t.group + "' of " + context(spec) + " is not a boundary group of its mesh" +
                  (spec.mesh.msh_file.empty() ? std::string() : " " + spec.mesh.msh_file) + " (groups:" + present +
                  ")");
    }
    const int body = fem::traction_body(reference, t.group);
    if (t.body >= 0 && t.body != body) {
      throw Error("traction group '" + t.group + "' of " + context(spec) + " is on the " + body_name(body) +
                  " body, but the case gives body = " + body_name(t.body));
    }
  }
}

mesh::Mesh mapped_mesh(const CaseSpec& spec, const mesh::Mesh& reference, const Mu& mu) {
  mesh::Mesh m = reference;
  const std::array<AffineMap, 2> maps = geometric_maps(spec.parameters, mu);
  for (int body = 0; body < 2; ++body) {
    const AffineMap& h = maps[static_cast<std::size_t>(body)];
    if (!h.is_identity()) mesh::map_body(m, body, h.M, h.b);
  }
  return m;
}

std::vector<fem::DirichletCondition> dirichlet_at(const CaseSpec& spec, const Mu& mu) {
  std::vector<fem::DirichletCondition> out;
  out.reserve(spec.dirichlet.size());
  for (const DirichletSpec& d : spec.dirichlet) {
    fem::DirichletCondition c;
    c.group = d.group;
    if (d.ux) c.ux = d.ux->at(mu);
    if (d.uy) c.uy = d.uy->at(mu);
    if (d.uz) c.uz = d.uz->at(mu);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<fem::Material> materials(const CaseSpec& spec, const Mu& mu) {
  std::vector<fem::Material> m;
  for (int body = 0; body < 2; ++body) {
    const BodySpec& b = spec.bodies[static_cast<std::size_t>(body)];
    const int k = spec.parameter_of_body(ParameterKind::YoungModulus, body);
    m.push_back(fem::Material{k >= 0 ? mu(k) : b.E, b.nu});
  }
  return m;
}

std::vector<Eigen::Vector2d> body_loads_at(const CaseSpec& spec, const Mu& mu) {
  if (spec.bodies[0].load.isZero(0.0) && spec.bodies[1].load.isZero(0.0)) return {};
  std::vector<Eigen::Vector2d> loads;
  for (int body = 0; body < 2; ++body) {
    const int k = spec.parameter_of_body(ParameterKind::BodyForce, body);
    loads.push_back(spec.bodies[static_cast<std::size_t>(body)].load * (k >= 0 ? mu(k) : 1.0));
  }
  return loads;
}

std::vector<fem::TractionLoad> tractions_at(const CaseSpec& spec, const Mu& mu) {
  std::vector<fem::TractionLoad> out;
  for (const TractionSpec& t : spec.tractions) {
    const double factor = t.parameter >= 0 ? mu(t.parameter) : 1.0;
    out.push_back({t.group, t.is_pressure, t.vector * factor, t.pressure * factor});
  }
  return out;
}

hf::ContactProblem make_problem(const CaseSpec& spec, const mesh::Mesh& reference, const Mu& mu,
                                std::optional<contact::Discretization> constraint) {
  check_case_spec(spec);
  spec.check_mu(mu);
  hf::ContactProblem p;
  p.mesh = mapped_mesh(spec, reference, mu);
  p.materials = materials(spec, mu);
  p.body_loads = body_loads_at(spec, mu);
  p.tractions = tractions_at(spec, mu);
  p.dirichlet = dirichlet_at(spec, mu);
  p.discretization = constraint ? *constraint : spec.constraint;
  return p;
}

hf::ContactProblem3 make_problem(const CaseSpec& spec, const mesh::Mesh3& reference, const Mu& mu,
                                 std::optional<contact::Discretization> constraint) {
  check_case_spec(spec);
  spec.check_mu(mu);
  require(case_dimension(spec) == 3, spec.context() + " is a 2D case: its problem is built on a 2D mesh");
  hf::ContactProblem3 p;
  p.mesh = reference;
  p.materials = materials(spec, mu);
  p.dirichlet = dirichlet_at(spec, mu);
  p.discretization = constraint ? *constraint : spec.constraint;
  return p;
}

hf::ContactProblem make_problem(const CaseSpec& spec, const Mu& mu, int level,
                                std::optional<contact::Discretization> constraint) {
  check_case_spec(spec);
  spec.check_mu(mu);  // before the (costly) mesh
  return make_problem(spec, reference_mesh(spec, level), mu, constraint);
}

namespace {
Mu one_parameter(const CaseSpec& spec, double mu) {
  require(spec.num_parameters() == 1, spec.context() + " has " + std::to_string(spec.num_parameters()) +
                                          " parameters: give mu as a point of that many values");
  return Mu::Constant(1, mu);
}
}  // namespace

hf::ContactProblem make_problem(const CaseSpec& spec, double mu, int level,
                                std::optional<contact::Discretization> constraint) {
  return make_problem(spec, one_parameter(spec, mu), level, constraint);
}

mesh::Mesh mapped_mesh(const CaseSpec& spec, const mesh::Mesh& reference, double mu) {
  return mapped_mesh(spec, reference, one_parameter(spec, mu));
}

hf::ContactProblem make_problem(const CaseSpec& spec, const mesh::Mesh& reference, double mu,
                                std::optional<contact::Discretization> constraint) {
  return make_problem(spec, reference, one_parameter(spec, mu), constraint);
}

}  // namespace contactrb::cases
