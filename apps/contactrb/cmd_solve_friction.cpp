// `contactrb solve` on a frictional case, built-in or a case file with friction keys
// (cases/frictional_cases.hpp; docs/cases.md, "Frictional cases"): the load path solved step by
// step (hf::solve_load_path), then DIR/solution.json (hf::to_json of the solution and of the friction law), DIR/multipliers.csv
// with the tangential traction and the state of each row, and the VTU files
// (study::write_friction_fields). A path that fails (not converged, full sliding) still writes
// solution.json, with converged = false and its status, and exits with code 3.
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "commands.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/frictional_cases.hpp"
#include "contactrb/cases/parameter_json.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/contact/contact_pair.hpp"
#include "contactrb/hf/friction_json.hpp"
#include "contactrb/io/json_file.hpp"
#include "contactrb/study/friction_fields.hpp"

namespace contactrb::app {

namespace {

// cattaneo's one parameter: its friction coefficient f (docs/cases.md, "Frictional cases").
std::vector<cases::ParameterSpec> cattaneo_parameters() {
  cases::ParameterSpec f;
  f.name = "f";
  f.kind = cases::ParameterKind::FrictionCoefficient;
  f.min = 0.0;
  f.max = 1.0;
  f.reference = cases::CattaneoData{}.coefficient;
  return {f};
}

// The case at --mu: its name, parameters, point and problem with its path and friction law.
struct LoadedCase {
  std::string name;
  std::vector<cases::ParameterSpec> parameters;
  cases::Mu mu;
  cases::FrictionalCase c;
  std::string msh_file;  // a case file's .msh (an input)
};

LoadedCase load_builtin(const FrictionalSolveRequest& request) {
  LoadedCase l{request.case_name, cattaneo_parameters(), {}, {}, {}};
  l.mu = parse_mu_option(request.mu_text, "--mu", l.parameters);
  cases::check_mu(l.parameters, l.mu, "case '" + l.name + "'");
  cases::CattaneoData data;
  data.coefficient = l.mu(0);
  l.c = cases::cattaneo_case(request.level, data);
  return l;
}

LoadedCase load_file(const FrictionalSolveRequest& request) {
  const std::optional<cases::FrictionalCaseFile> file = cases::frictional_case_from_toml_file(request.case_file);
  require(file.has_value(), "case file " + request.case_file + " has no friction keys");  // checked by the caller
  require(cases::case_dimension(file->spec) == 2,
          file->spec.context() + " is frictional and 3D: friction is solved in 2D only in this build");
  LoadedCase l{file->spec.name, file->spec.parameters, {}, {}, file->spec.mesh.msh_file};
  l.mu = parse_mu_option(request.mu_text, "--mu", l.parameters);
  file->spec.check_mu(l.mu);
  l.c = cases::frictional_case(*file, cases::reference_mesh(file->spec, request.level), l.mu);
  return l;
}

void print_summary(const LoadedCase& l, const hf::FrictionalSolution& s, int dofs, int rows) {
  const bool coulomb = l.c.friction.law == hf::FrictionLaw::Coulomb;
  std::cout << "case " << l.name << " (2D, frictional: " << hf::to_string(l.c.friction.law)
            << (coulomb ? " f = " : " threshold = ") << (coulomb ? l.c.friction.coefficient : l.c.friction.threshold)
            << "), "
            // f alone is in the parentheses already
            << (l.mu.size() == 1 && l.parameters.front().kind == cases::ParameterKind::FrictionCoefficient
                    ? ""
                    : cases::mu_text(l.parameters, l.mu) + ", ")
            << "collocation, "
            << dofs << " DOFs, " << rows << " constraints, " << s.steps.size() << " of " << l.c.path.size()
            << " load steps solved\n";
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    const hf::FrictionStepReport& r = s.steps[i];
    std::cout << "step " << i + 1 << ": " << hf::to_string(r.status) << " in " << r.iterations
              << " Newton iterations, contact force " << r.normal_force << ", tangential force "
              << (r.tangential_force.size() > 0 ? r.tangential_force(0) : 0.0) << ", " << r.stick << " stick, "
              << r.slip << " slip\n";
  }
}

}  // namespace

int run_frictional_solve(const FrictionalSolveRequest& request) {
  const std::string what =
      request.case_file.empty() ? "case '" + request.case_name + "'" : "case file " + request.case_file;
  require(request.constraint.empty() || request.constraint == "collocation",
          what + " is frictional: --constraint " + request.constraint +
              " is not available with friction (collocation only)");
  require(!request.solver || *request.solver == "newton",
          what + " is frictional: --solver " + request.solver.value_or("") +
              " is not available with friction (its semi-smooth Newton method only)");
  require(request.sequence <= 0, what + " is frictional: --sequence " + std::to_string(request.sequence) +
                                     " is not available with friction (no grid sequencing)");
  require(request.level >= 0, "--level must be >= 0 (got " + std::to_string(request.level) + ")");
  // The case at --mu (a 2D mesh and its load path: cheap), then --out.
  LoadedCase l = request.case_file.empty() ? load_builtin(request) : load_file(request);
  l.c.friction.max_iterations = request.newton_max_iterations;
  hf::check_settings(l.c.friction);
  const cases::FrictionalCase& c = l.c;
  const std::string json_path = request.out_dir + "/solution.json";
  const study::FrictionFiles names{request.out_dir + "/solution.vtu", request.out_dir + "/solution_deformed.vtu",
                                   request.out_dir + "/contact.vtu", request.out_dir + "/multipliers.csv"};
  check_file_roles({{"--case-file", request.case_file}, {"the case's mesh file", l.msh_file}},
                   {{"solution.json in --out", json_path},
                    {"multipliers.csv in --out", names.multipliers},
                    {"solution.vtu in --out", names.vtu},
                    {"solution_deformed.vtu in --out", names.deformed_vtu},
                    {"contact.vtu in --out", names.contact_vtu}});
  ensure_output_directory(request.out_dir);

  const hf::FrictionalSolution s = hf::solve_load_path(c.problem, c.path, c.friction);
  const contact::ContactPair pair = contact::make_contact_pair(c.problem.mesh);
  const contact::ContactQuadrature quadrature =
      contact::make_quadrature(c.problem.mesh, pair, contact::Discretization::Collocation);

  // Written under a lock on DIR and committed together (common/output_file.hpp, OutputSet).
  const OutputLock lock(request.out_dir);
  OutputSet outputs;
  nlohmann::json j = hf::to_json(s);
  j.update(hf::to_json(c.friction));
  j["case"] = l.name;
  if (!request.case_file.empty()) j["case_file"] = request.case_file;
  j["mu"] = cases::mu_json(l.parameters, l.mu);
  j["level"] = request.level;
  j["dimension"] = 2;
  j["load_steps"] = c.path.size();
  io::write_json(j, json_path);
  if (s.converged) study::write_friction_fields(c.problem.mesh, pair, quadrature, s, request.out_dir);
  outputs.commit();
  if (!s.converged) {
    // No fields of this run: the files of an earlier run would sit beside its solution.json.
    for (const std::string& stale : {names.multipliers, names.vtu, names.deformed_vtu, names.contact_vtu}) {
      std::error_code ignored;
      std::filesystem::remove(stale, ignored);
    }
  }
  print_summary(l, s, c.problem.mesh.num_dofs(), static_cast<int>(quadrature.weight.size()));
  if (!s.converged) {
    std::cerr << "contactrb: error: " << hf::to_string(s.status) << ": " << s.message << "\n";
    std::cout << "wrote " << json_path << " (converged = false, status " << hf::to_string(s.status) << ")\n";
    return 3;
  }
  std::cout << "contact force " << s.contact_force << ", tangential force " << s.tangential_force(0) << ", "
            << s.stick_nodes << " stick, " << s.slip_nodes << " slip, max KKT residual " << s.kkt.max() << "\n"
            << "wrote " << json_path << "\nwrote " << names.multipliers << "\nwrote " << names.vtu << "\nwrote "
            << names.deformed_vtu << "\nwrote " << names.contact_vtu << "\n";
  return 0;
}

}  // namespace contactrb::app
