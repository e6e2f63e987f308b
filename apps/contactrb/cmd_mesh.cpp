// `contactrb mesh`: the reference mesh of a built-in case, or a user's Gmsh .msh (2D or 3D), written
// as DIR/mesh.vtu (ParaView) and DIR/mesh.msh (Gmsh format 4.1), with its counts printed.
#include <Eigen/Core>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/vtu_writer.hpp"
#include "contactrb/mesh/msh_io.hpp"

namespace contactrb::app {

namespace {

struct MeshOptions {
  std::string case_name;
  std::string msh_file;
  int level = 0;
  std::string out_dir;
};

// 1 on the nodes of a boundary group, 0 elsewhere: lets ParaView show the contact
// boundaries (Threshold on "slave" / "master").
template <int Dim>
Eigen::VectorXd indicator(const mesh::SimplexMesh<Dim>& m, const std::string& group) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(m.num_nodes());
  for (int node : mesh::boundary_nodes(m, group)) v[node] = 1.0;
  return v;
}

// Checks the mesh, writes mesh.vtu and mesh.msh and prints the counts.
template <int Dim>
int write_mesh(const mesh::SimplexMesh<Dim>& m, const std::string& source, const MeshOptions& opt) {
  using Names = mesh::SimplexNames<Dim>;
  const std::string vtu = opt.out_dir + "/mesh.vtu";
  const std::string msh = opt.out_dir + "/mesh.msh";
  mesh::validate(m);
  // `solve` needs both contact boundaries: a mesh whose slave or master group has no facet
  // would be written here and refused there.
  for (const char* group : {mesh::kSlaveBoundary, mesh::kMasterBoundary}) {
    require(!mesh::boundary_nodes(m, group).empty(),
            "the " + std::to_string(Dim - 1) + "D physical group '" + std::string(group) + "' of " + source + " has no " +
                Names::facet + ": contact needs a non-empty slave and master boundary");
  }

  const OutputLock lock(opt.out_dir);  // the two files of one run, never mixed with another's
  io::VtuWriter(m)
      .add_point_scalar(mesh::kSlaveBoundary, indicator(m, mesh::kSlaveBoundary))
      .add_point_scalar(mesh::kMasterBoundary, indicator(m, mesh::kMasterBoundary))
      .write(vtu);
  mesh::write_msh(m, msh);

  std::cout << "mesh: " << source << "\n"
            << "dimension: " << Dim << "\n"
            << "nodes: " << m.num_nodes() << "\n"
            << "elements: " << m.num_cells() << "\n"
            << "bodies: " << m.num_bodies() << "\n"
            << "slave contact nodes: " << mesh::boundary_nodes(m, mesh::kSlaveBoundary).size() << "\n"
            << "master contact nodes: " << mesh::boundary_nodes(m, mesh::kMasterBoundary).size() << "\n"
            << "boundary groups:";
  for (const auto& [name, facets] : m.boundaries) {
    std::cout << " " << name << " (" << facets.size() << " " << (Dim == 2 ? "edges" : "triangles") << ")";
  }
  std::cout << "\n"
            << "wrote " << vtu << "\n"
            << "wrote " << msh << "\n";
  return 0;
}

int run_mesh(const MeshOptions& opt) {
  // `--msh D/mesh.msh --out D` would replace the input by its own rewrite.
  check_file_roles({{"--msh", opt.msh_file}},
                   {{"mesh.vtu in --out", opt.out_dir + "/mesh.vtu"}, {"mesh.msh in --out", opt.out_dir + "/mesh.msh"}});
  // Cheap checks first (case name, output directory), then the mesh generation.
  if (!opt.case_name.empty()) {
    const cases::CaseInfo& info = cases::find_case(opt.case_name);
    ensure_output_directory(opt.out_dir);
    const std::string source = "case " + opt.case_name + ", level " + std::to_string(opt.level);
    if (info.dimension == 3) return write_mesh(cases::reference_mesh3(opt.case_name, opt.level), source, opt);
    return write_mesh(cases::reference_mesh(opt.case_name, opt.level), source, opt);
  }
  const std::string source = "file " + opt.msh_file;
  if (mesh::msh_dimension(opt.msh_file) == 3) {
    const mesh::Mesh3 m = mesh::read_msh3(opt.msh_file);
    ensure_output_directory(opt.out_dir);
    return write_mesh(m, source, opt);
  }
  const mesh::Mesh m = mesh::read_msh(opt.msh_file);
  ensure_output_directory(opt.out_dir);
  return write_mesh(m, source, opt);
}

}  // namespace

Command add_mesh_command(CLI::App& app) {
  auto opt = std::make_shared<MeshOptions>();
  CLI::App* sub = app.add_subcommand(
      "mesh", "Write the reference mesh of a built-in case (or import a Gmsh .msh) as DIR/mesh.vtu and DIR/mesh.msh");
  // Exactly one input: a built-in case or a .msh file (a usage error otherwise).
  CLI::Option_group* input = sub->add_option_group("input", "Mesh source (exactly one)");
  CLI::Option* case_opt = input->add_option("--case", opt->case_name, "Built-in case (see `contactrb cases`)");
  input->add_option("--msh", opt->msh_file,
                    "Gmsh .msh file (format 4.1) with physical groups body1, body2 (surfaces in 2D, volumes in 3D) "
                    "and slave, master (one dimension less)");
  input->require_option(1);
  sub->add_option("--level", opt->level, "Refinement level of a built-in case (0: the paper's mesh)")
      ->check(CLI::Validator(
          [](std::string& value) {
            return value.find('-') == std::string::npos ? std::string() : "must be >= 0 (got " + value + ")";
          },
          "LEVEL>=0"))
      ->needs(case_opt);
  sub->add_option("--out", opt->out_dir, "Output directory (created if missing)")->required();
  return {sub, [opt] { return run_mesh(*opt); }};
}

}  // namespace contactrb::app
