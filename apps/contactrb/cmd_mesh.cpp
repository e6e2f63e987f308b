// `contactrb mesh`: the reference mesh of a built-in case, or a user's Gmsh .msh, written
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
Eigen::VectorXd indicator(const mesh::Mesh& m, const std::string& group) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(m.num_nodes());
  for (int node : mesh::boundary_nodes(m, group)) v[node] = 1.0;
  return v;
}

int run_mesh(const MeshOptions& opt) {
  mesh::Mesh m;
  std::string source;
  const std::string vtu = opt.out_dir + "/mesh.vtu";
  const std::string msh = opt.out_dir + "/mesh.msh";
  // `--msh D/mesh.msh --out D` would replace the input by its own rewrite.
  check_file_roles({{"--msh", opt.msh_file}}, {{"mesh.vtu in --out", vtu}, {"mesh.msh in --out", msh}});
  // Cheap checks first (case name, output directory), then the mesh generation.
  if (!opt.case_name.empty()) {
    cases::find_case(opt.case_name);
    ensure_output_directory(opt.out_dir);
    m = cases::reference_mesh(opt.case_name, opt.level);
    source = "case " + opt.case_name + ", level " + std::to_string(opt.level);
  } else {
    m = mesh::read_msh(opt.msh_file);
    source = "file " + opt.msh_file;
    ensure_output_directory(opt.out_dir);
  }
  mesh::validate(m);
  // `solve` needs both contact boundaries: a mesh whose slave or master group has no edge
  // would be written here and refused there.
  for (const char* group : {mesh::kSlaveBoundary, mesh::kMasterBoundary}) {
    require(!mesh::boundary_nodes(m, group).empty(),
            "the 1D physical group '" + std::string(group) + "' of " + source +
                " has no edge: contact needs a non-empty slave and master boundary");
  }

  const OutputLock lock(opt.out_dir);  // the two files of one run, never mixed with another's
  io::VtuWriter(m)
      .add_point_scalar(mesh::kSlaveBoundary, indicator(m, mesh::kSlaveBoundary))
      .add_point_scalar(mesh::kMasterBoundary, indicator(m, mesh::kMasterBoundary))
      .write(vtu);
  mesh::write_msh(m, msh);

  std::cout << "mesh: " << source << "\n"
            << "nodes: " << m.num_nodes() << "\n"
            << "elements: " << m.num_triangles() << "\n"
            << "bodies: " << m.num_bodies() << "\n"
            << "slave contact nodes: " << mesh::boundary_nodes(m, mesh::kSlaveBoundary).size() << "\n"
            << "master contact nodes: " << mesh::boundary_nodes(m, mesh::kMasterBoundary).size() << "\n"
            << "boundary groups:";
  for (const auto& [name, edges] : m.boundaries) std::cout << " " << name << " (" << edges.size() << " edges)";
  std::cout << "\n"
            << "wrote " << vtu << "\n"
            << "wrote " << msh << "\n";
  return 0;
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
                    "Gmsh .msh file (format 4) with 2D physical groups body1, body2 and 1D groups slave, master");
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
