// `contactrb solve`: one high-fidelity contact solve of a built-in case (--case) or a TOML
// case file (--case-file) at one parameter value, in the case's dimension (2D or 3D). Writes DIR/solution.json,
// DIR/multipliers.csv, DIR/solution.vtu (Omega(mu) with displacement, contact pressure and
// stresses), DIR/solution_deformed.vtu (the deformed configuration) and DIR/contact.vtu (the
// slave boundary with pressure and gap) (docs/file-formats.md, "Command outputs"; study/solution_fields.hpp). A solve
// that does not converge still writes solution.json (converged = false) and exits with code 3.
// A frictional case (built-in or a case file with friction keys) runs its load path instead
// (cmd_solve_friction.cpp).
#include <Eigen/Core>
#include <filesystem>
#include <system_error>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>

#include "commands.hpp"
#include "contactrb/cases/builtin_problems.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/cases/level_sequence.hpp"
#include "contactrb/cases/level_sequence_json.hpp"
#include "contactrb/cases/parameter_json.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/hf/hf_solution_json.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/io/json_file.hpp"
#include "contactrb/study/solution_fields.hpp"
#include "contactrb/study/solution_fields_3d.hpp"
#include "hf_solver_option.hpp"

namespace contactrb::app {

namespace {


struct SolveOptions {
  std::string case_name;
  std::string case_file;
  std::string mu_text;  // --mu as given: parsed by parse_mu_option (CLI11 reads '' as 0)
  cases::Mu mu;
  std::vector<cases::ParameterSpec> parameters;
  std::string constraint;  // empty: the case's default
  double alpha = solve::KacanovSettings{}.alpha;
  double tolerance = solve::KacanovSettings{}.tolerance;
  int max_iterations = solve::KacanovSettings{}.max_iterations;
  int level = 0;
  // Grid sequencing: coarse levels level - 2k, ..., level - 2 (cases/level_sequence.hpp); -1: automatic
  // (cases::default_sequence).
  int sequence = -1;
  std::optional<std::string> solver;  // --solver (nullopt: hf::default_method of the mesh)
  int newton_max_iterations = hf::NewtonSettings{}.max_iterations;
  std::string linear_solver = "auto";  // --linear-solver: direct | amg | auto (Newton's systems)
  std::string out_dir;
};

// --linear-solver (docs/solvers.md, "AMG-preconditioned Krylov solve"): direct is the Cholesky of
// A_00 with the selected inverse (hf::NewtonLinearSolver::ActiveSchur).
hf::NewtonLinearSolver linear_solver_option(const std::string& name) {
  if (name == "direct") return hf::NewtonLinearSolver::ActiveSchur;
  if (name == "amg") return hf::NewtonLinearSolver::Amg;
  if (name == "auto") return hf::NewtonLinearSolver::Auto;
  throw Error("unknown --linear-solver '" + name + "' (expected direct, amg or auto)");
}

// solution.json (docs/user-guide.md, "solve"): the run's keys, the solve's and the discretization's
// (hf::to_json, hf::discretization_json) and the grid sequencing's (cases::to_json).
template <int Dim>
nlohmann::json solution_json(const SolveOptions& opt, const hf::BasicHFSolver<Dim>& solver,
                             const hf::BasicHFSolution<Dim>& s, const hf::HFSettings& settings,
                             const cases::SequenceStart& start) {
  nlohmann::json j = hf::to_json(s);
  j.update(hf::discretization_json(solver));
  j.update(cases::to_json(start));
  j["case"] = opt.case_name;
  if (!opt.case_file.empty()) j["case_file"] = opt.case_file;
  j["mu"] = cases::mu_json(opt.parameters, opt.mu);
  j["level"] = opt.level;
  j["dimension"] = Dim;
  j["solver"] = hf::to_string(settings.method);
  j["alpha"] = settings.kacanov.alpha;
  j["tolerance"] = settings.kacanov.tolerance;
  return j;
}

struct SolvePaths {
  std::string json, csv, vtu, deformed, contact;
  explicit SolvePaths(const std::string& dir)
      : json(dir + "/solution.json"), csv(dir + "/multipliers.csv"), vtu(dir + "/solution.vtu"),
        deformed(dir + "/solution_deformed.vtu"), contact(dir + "/contact.vtu") {}
};

// The reference mesh of the case in its dimension.
mesh::Mesh reference_of(const cases::CaseSpec& spec, int level, std::integral_constant<int, 2>) {
  return cases::reference_mesh(spec, level);
}
mesh::Mesh3 reference_of(const cases::CaseSpec& spec, int level, std::integral_constant<int, 3>) {
  return cases::reference_mesh3(spec, level);
}

// 2D: multipliers.csv with the reference abscissa of each row and the three VTU files.
void write_fields(const SolveOptions& opt, const mesh::Mesh& reference, const hf::HFSolver& solver,
                  const hf::HFSolution& s, const SolvePaths& paths) {
  const mesh::Mesh& m = solver.problem().mesh;
  io::CsvWriter csv({"r", "abscissa", "x", "y", "gap", "pressure", "weight"});
  const Eigen::VectorXd slack = s.rows.g - s.rows.K * s.u;  // integrated deformed gap
  const auto& q = solver.quadrature();
  for (int r = 0; r < s.lambda.size(); ++r) {
    const auto node = static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)]);
    csv.add_row({static_cast<long long>(r), reference.nodes[node].x(), m.nodes[node].x(), m.nodes[node].y(),
                 slack(r) / q.weight(r), s.lambda(r), q.weight(r)});
  }
  csv.write(paths.csv);
  study::write_solution_vtus(m, solver.problem().materials, solver.pair(), q, opt.parameters, opt.mu, s.u, s.lambda,
                             opt.out_dir);
}

// 3D: one row per slave node (collocation and LAC), its pressure, deformed gap and nodal area.
void write_fields(const SolveOptions& opt, const mesh::Mesh3&, const hf::HFSolver3& solver, const hf::HFSolution3& s,
                  const SolvePaths& paths) {
  const auto& q = solver.quadrature();
  study::SlaveSurfaceFields contact;
  contact.nodes = q.center_node;
  contact.pressure = s.lambda;
  contact.gap = (s.rows.g - s.rows.K * s.u).cwiseQuotient(q.weight);
  contact.weight = q.weight;
  study::write_multipliers_csv(solver.problem().mesh, contact, paths.csv);
  study::write_solution_vtus(solver.problem().mesh, solver.problem().materials, opt.parameters, opt.mu, s.u, contact,
                             opt.out_dir);
}

template <int Dim>
int solve_case(const SolveOptions& opt, const cases::CaseSpec& spec, const hf::HFSettings& settings,
               std::optional<contact::Discretization> constraint, const SolvePaths& paths) {
  const auto reference = reference_of(spec, opt.level, std::integral_constant<int, Dim>{});
  // The coarse meshes before the analysis thread below starts (cases::CoarseMeshes: Gmsh's 3D
  // mesher is not reproducible beside another thread that allocates).
  const cases::CoarseMeshes<Dim> coarse =
      cases::coarse_meshes<Dim>(spec, cases::sequence_levels(opt.level, opt.sequence));
  // Newton: the analysis of A_00 beside the assembly (hf::HFSetupOptions; the same answer bitwise),
  // and beside the coarse stages of the grid sequencing.
  const hf::BasicHFSolver<Dim> solver(cases::make_problem(spec, reference, opt.mu, constraint),
                                      hf::setup_options_for(settings));
  const cases::SequenceStart start = cases::sequence_start(spec, opt.mu, coarse, constraint, settings, solver);
  const hf::BasicHFSolution<Dim> s = solver.solve(settings, start.guess);
  const auto& m = solver.problem().mesh;

  // The five files of one run are written under a lock on DIR (two runs to the same --out leave
  // the files of one of them, never a mix) and committed together (a failed write leaves the
  // earlier files: common/output_file.hpp, OutputSet).
  const OutputLock lock(opt.out_dir);
  OutputSet outputs;
  io::write_json(solution_json(opt, solver, s, settings, start), paths.json);
  const bool with_fields = s.rows.K.rows() == s.lambda.size() && s.lambda.size() > 0;
  if (with_fields) write_fields(opt, reference, solver, s, paths);
  outputs.commit();
  if (!with_fields) {
    // No fields of this run: the files of an earlier run would sit beside its solution.json.
    for (const std::string& stale : {paths.csv, paths.vtu, paths.deformed, paths.contact}) {
      std::error_code ignored;
      std::filesystem::remove(stale, ignored);
    }
  }

  std::cout << "case " << opt.case_name << " (" << Dim << "D), "
            << (opt.mu.size() == 1 ? "mu = " + cases::mu_values_text(opt.mu) : cases::mu_text(opt.parameters, opt.mu))
            << ", " << contact::to_string(solver.problem().discretization) << ", " << m.num_dofs() << " DOFs, "
            << solver.quadrature().weight.size() << " constraints\n";
  if (!s.converged) {
    std::cerr << "contactrb: error: " << s.message << "\n";
    std::cout << "wrote " << paths.json << " (converged = false)\n";
    return 3;
  }
  if (!start.stages.empty()) {
    std::cout << "grid sequencing:";
    for (const cases::SequenceStage& st : start.stages) {
      std::cout << " level " << st.level << " " << st.iterations << " iterations" << (st.converged ? "" : " (not converged)")
                << ";";
    }
    std::cout << " " << start.time_s * 1e3 << " ms\n";
  }
  std::cout << "converged in " << s.iterations << " " << (s.method == hf::HFMethod::Newton ? "Newton" : "Kacanov")
            << " iterations (" << s.time_s * 1e3 << " ms)\n"
            << "energy " << s.energy << ", contact force " << s.contact_force << ", active constraints "
            << s.active_constraints << ", max KKT residual " << s.kkt.max() << "\n"
            << "wrote " << paths.json << "\nwrote " << paths.csv << "\nwrote " << paths.vtu << "\nwrote "
            << paths.deformed << "\nwrote " << paths.contact << "\n";
  return 0;
}

int run_solve(SolveOptions opt) {
  // A frictional case (docs/cases.md, "Frictional cases"): its load path instead.
  if (opt.case_file.empty() ? cases::is_frictional_case(opt.case_name)
                            : cases::frictional_case_from_toml_file(opt.case_file).has_value()) {
    return run_frictional_solve(
        {opt.case_name, opt.case_file, opt.mu_text, opt.constraint, opt.solver, opt.level, opt.sequence,
         opt.newton_max_iterations, opt.out_dir});
  }
  // Cheap checks first: case (the TOML file is read and checked here), parameter,
  // settings, output directory; the mesh comes later.
  const cases::CaseSpec spec = read_case(opt.case_name, opt.case_file);
  const int dimension = cases::case_dimension(spec);
  if (!opt.case_file.empty()) opt.case_name = spec.name;
  opt.mu = parse_mu_option(opt.mu_text, "--mu", spec.parameters);
  opt.parameters = spec.parameters;
  cases::check_mu(spec.parameters, opt.mu,
                  "case '" + spec.name + "'" + (opt.case_file.empty() ? "" : " (" + opt.case_file + ")"));
  hf::HFSettings settings;
  settings.kacanov.alpha = opt.alpha;
  settings.kacanov.tolerance = opt.tolerance;
  settings.kacanov.max_iterations = opt.max_iterations;
  solve::check_settings(settings.kacanov);
  settings.method = snapshot_solver_option(opt.solver).value_or(hf::default_method(dimension, opt.level));
  settings.newton.max_iterations = opt.newton_max_iterations;
  settings.newton.linear_solver = linear_solver_option(opt.linear_solver);
  hf::check_settings(settings.newton);
  std::optional<contact::Discretization> constraint;
  if (!opt.constraint.empty()) constraint = contact::discretization_from_string(opt.constraint);
  require(opt.level >= 0, "--level must be >= 0 (got " + std::to_string(opt.level) + ")");
  opt.sequence = cases::resolve_sequence(opt.sequence, dimension, settings.method, opt.level);
  const SolvePaths paths(opt.out_dir);
  check_file_roles({{"--case-file", opt.case_file}, {"the case's mesh file", spec.mesh.msh_file}},
                   {{"solution.json in --out", paths.json},
                    {"multipliers.csv in --out", paths.csv},
                    {"solution.vtu in --out", paths.vtu},
                    {"solution_deformed.vtu in --out", paths.deformed},
                    {"contact.vtu in --out", paths.contact}});
  ensure_output_directory(opt.out_dir);
  return dimension == 3 ? solve_case<3>(opt, spec, settings, constraint, paths)
                        : solve_case<2>(opt, spec, settings, constraint, paths);
}

}  // namespace

Command add_solve_command(CLI::App& app) {
  auto opt = std::make_shared<SolveOptions>();
  CLI::App* sub =
      app.add_subcommand("solve", "High-fidelity contact solve of a built-in or TOML case at one parameter value");
  // Exactly one case source (a usage error otherwise).
  CLI::Option_group* input = sub->add_option_group("case", "Case (exactly one)");
  input->add_option("--case", opt->case_name, "Built-in case (see `contactrb cases`)");
  input->add_option("--case-file", opt->case_file, "TOML case file (docs/cases.md)");
  input->require_option(1);
  sub->add_option("--mu", opt->mu_text,
                  "Parameter point inside the case's domain: a number (one parameter), p numbers separated by "
                  "commas, or name=value pairs separated by commas")
      ->required();
  sub->add_option("--constraint", opt->constraint, "collocation | lac | lac-simpson (default: the case's)");
  sub->add_option("--alpha", opt->alpha, "Kacanov relaxation in (0, 1]")->capture_default_str();
  sub->add_option("--tol", opt->tolerance, "Kacanov stopping tolerance eps_KA of (63), > 0")->capture_default_str();
  sub->add_option("--max-iterations", opt->max_iterations, "Kacanov iteration limit")->capture_default_str();
  sub->add_option("--solver", opt->solver,
                  "HF solver: kacanov (the paper's) | newton (semi-smooth Newton); default: kacanov on 2D level 0, "
                  "newton otherwise (docs/solvers.md)");
  sub->add_option("--linear-solver", opt->linear_solver,
                  "Newton's linear systems: direct (Cholesky) | amg (hypre BoomerAMG + GMRES) | auto (amg in 3D from "
                  "40 000 free DOFs; docs/solvers.md)")
      ->capture_default_str();
  sub->add_option("--newton-max-iterations", opt->newton_max_iterations, "Semi-smooth Newton iteration limit")
      ->capture_default_str();
  sub->add_option("--level", opt->level, "Mesh refinement level of a generated mesh (0: the paper's mesh)")
      ->capture_default_str();
  add_sequence_option(sub, opt->sequence);
  sub->add_option("--out", opt->out_dir, "Output directory (created if missing)")->required();
  return {sub, [opt] { return run_solve(*opt); }};
}

}  // namespace contactrb::app
