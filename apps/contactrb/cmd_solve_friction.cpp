// `contactrb solve` on a frictional case, built-in or a case file with friction keys, 2D or 3D
// (cases/frictional_cases.hpp; docs/cases.md, "Frictional cases"): the load path solved step by
// step (hf::solve_load_path), then DIR/solution.json (hf::to_json of the solution and of the
// friction law), DIR/multipliers.csv with the tangential traction and the state of each row, the
// VTU files (study::write_friction_fields) and the VTU files of each load step with their .pvd
// collections (study::FrictionStepSeries). A path that fails (not converged, full sliding) still
// writes solution.json, with converged = false and its status, and exits with code 3.
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>

#include "commands.hpp"
#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/catalog.hpp"
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

// The built-in cases' one parameter: their friction coefficient f (docs/cases.md, "Frictional cases").
std::vector<cases::ParameterSpec> coefficient_parameter(double reference) {
  cases::ParameterSpec f;
  f.name = "f";
  f.kind = cases::ParameterKind::FrictionCoefficient;
  f.min = 0.0;
  f.max = 1.0;
  f.reference = reference;
  return {f};
}

// The case at --mu: its name, parameters, point and problem with its path and friction law.
template <int Dim>
struct LoadedCase {
  std::string name;
  std::vector<cases::ParameterSpec> parameters;
  cases::Mu mu;
  cases::BasicFrictionalCase<Dim> c;
  std::string msh_file;  // a case file's .msh (an input)
};

template <int Dim>
LoadedCase<Dim> with_mu(const FrictionalSolveRequest& request, std::string name,
                        std::vector<cases::ParameterSpec> parameters) {
  LoadedCase<Dim> l{std::move(name), std::move(parameters), {}, {}, {}};
  l.mu = parse_mu_option(request.mu_text, "--mu", l.parameters);
  cases::check_mu(l.parameters, l.mu, "case '" + l.name + "'");
  return l;
}

// cattaneo (2D) and cattaneo-3d at f = --mu.
LoadedCase<2> load_builtin(const FrictionalSolveRequest& request, std::integral_constant<int, 2>) {
  cases::CattaneoData data;
  LoadedCase<2> l = with_mu<2>(request, request.case_name, coefficient_parameter(data.coefficient));
  data.coefficient = l.mu(0);
  l.c = cases::cattaneo_case(request.level, data);
  return l;
}

LoadedCase<3> load_builtin(const FrictionalSolveRequest& request, std::integral_constant<int, 3>) {
  cases::Cattaneo3dData data;
  LoadedCase<3> l = with_mu<3>(request, request.case_name, coefficient_parameter(data.coefficient));
  data.coefficient = l.mu(0);
  l.c = cases::cattaneo_3d_case(request.level, data);
  return l;
}

template <int Dim>
LoadedCase<Dim> load_file(const FrictionalSolveRequest& request, const cases::FrictionalCaseFile& file) {
  LoadedCase<Dim> l{file.spec.name, file.spec.parameters, {}, {}, file.spec.mesh.msh_file};
  l.mu = parse_mu_option(request.mu_text, "--mu", l.parameters);
  file.spec.check_mu(l.mu);
  if constexpr (Dim == 2) {
    l.c = cases::frictional_case(file, cases::reference_mesh(file.spec, request.level), l.mu);
  } else {
    l.c = cases::frictional_case(file, cases::reference_mesh3(file.spec, request.level), l.mu);
  }
  return l;
}

// 2D: the signed force; 3D: its two components, "(F_1, F_2)".
std::string force_text(const Eigen::VectorXd& f) {
  std::ostringstream os;
  if (f.size() == 1) {
    os << f(0);
  } else if (f.size() == 2) {
    os << "(" << f(0) << ", " << f(1) << ")";
  } else {
    os << 0.0;
  }
  return os.str();
}

template <int Dim>
void print_summary(const LoadedCase<Dim>& l, const hf::BasicFrictionalSolution<Dim>& s, int dofs, int rows) {
  const bool coulomb = l.c.friction.law == hf::FrictionLaw::Coulomb;
  std::cout << "case " << l.name << " (" << Dim << "D, frictional: " << hf::to_string(l.c.friction.law)
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
              << force_text(r.tangential_force) << ", " << r.stick << " stick, " << r.slip << " slip\n";
  }
}

struct OutputNames {
  std::string json;
  study::FrictionFiles fields;
  std::string solution_pvd, contact_pvd;
};

OutputNames output_names(const std::string& dir) {
  return {dir + "/solution.json",
          {dir + "/solution.vtu", dir + "/solution_deformed.vtu", dir + "/contact.vtu", dir + "/multipliers.csv"},
          dir + "/solution_steps.pvd",
          dir + "/contact_steps.pvd"};
}

// The load path of a loaded case, solved and written (docs/cli.md, "Frictional cases").
template <int Dim>
int solve_and_write(const FrictionalSolveRequest& request, LoadedCase<Dim> l) {
  l.c.friction.max_iterations = request.newton_max_iterations;
  hf::check_settings(l.c.friction);
  const cases::BasicFrictionalCase<Dim>& c = l.c;
  const OutputNames names = output_names(request.out_dir);
  check_file_roles({{"--case-file", request.case_file}, {"the case's mesh file", l.msh_file}},
                   {{"solution.json in --out", names.json},
                    {"multipliers.csv in --out", names.fields.multipliers},
                    {"solution.vtu in --out", names.fields.vtu},
                    {"solution_deformed.vtu in --out", names.fields.deformed_vtu},
                    {"contact.vtu in --out", names.fields.contact_vtu},
                    {"solution_steps.pvd in --out", names.solution_pvd},
                    {"contact_steps.pvd in --out", names.contact_pvd}});
  ensure_output_directory(request.out_dir);

  const contact::ContactPairOf<Dim> pair = contact::make_contact_pair(c.problem.mesh);
  const contact::ContactQuadrature quadrature =
      contact::make_quadrature(c.problem.mesh, pair, contact::Discretization::Collocation);
  study::FrictionStepSeries<Dim> series(c.problem.mesh, pair, quadrature);
  // f = 0 is the frictionless solve of the last step: by the semi-smooth Newton method, as every
  // frictional step (--solver newton only).
  hf::HFSettings frictionless;
  frictionless.method = hf::HFMethod::Newton;
  frictionless.newton.max_iterations = request.newton_max_iterations;
  const hf::BasicFrictionalSolution<Dim> s = hf::solve_load_path<Dim>(
      c.problem, c.path, c.friction, frictionless,
      [&series](std::size_t step, const hf::BasicFrictionalSolution<Dim>& state) { series.add(step, state); });

  // Written under a lock on DIR and committed together (common/output_file.hpp, OutputSet).
  const OutputLock lock(request.out_dir);
  OutputSet outputs;
  nlohmann::json j = hf::to_json(s);
  j.update(hf::to_json(c.friction));
  j["case"] = l.name;
  if (!request.case_file.empty()) j["case_file"] = request.case_file;
  j["mu"] = cases::mu_json(l.parameters, l.mu);
  j["level"] = request.level;
  j["dimension"] = Dim;
  j["load_steps"] = c.path.size();
  io::write_json(j, names.json);
  if (s.converged) {
    study::write_friction_fields<Dim>(c.problem.mesh, pair, quadrature, s, request.out_dir);
    series.write(request.out_dir);
  }
  outputs.commit();
  if (!s.converged) {
    // No fields of this run: the files of an earlier run would sit beside its solution.json.
    for (const std::string& stale : {names.fields.multipliers, names.fields.vtu, names.fields.deformed_vtu,
                                     names.fields.contact_vtu, names.solution_pvd, names.contact_pvd}) {
      std::error_code ignored;
      std::filesystem::remove(stale, ignored);
    }
  }
  print_summary(l, s, c.problem.mesh.num_dofs(), static_cast<int>(quadrature.weight.size()));
  if (!s.converged) {
    std::cerr << "contactrb: error: " << hf::to_string(s.status) << ": " << s.message << "\n";
    std::cout << "wrote " << names.json << " (converged = false, status " << hf::to_string(s.status) << ")\n";
    return 3;
  }
  std::cout << "contact force " << s.contact_force << ", tangential force " << force_text(s.tangential_force) << ", "
            << s.stick_nodes << " stick, " << s.slip_nodes << " slip, max KKT residual " << s.kkt.max() << "\n"
            << "wrote " << names.json << "\nwrote " << names.fields.multipliers << "\nwrote " << names.fields.vtu
            << "\nwrote " << names.fields.deformed_vtu << "\nwrote " << names.fields.contact_vtu << "\nwrote "
            << names.solution_pvd << " and " << names.contact_pvd << " (" << series.size() << " load steps, in "
            << request.out_dir << "/steps)\n";
  return 0;
}

template <int Dim>
int solve_builtin(const FrictionalSolveRequest& request) {
  return solve_and_write<Dim>(request, load_builtin(request, std::integral_constant<int, Dim>{}));
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
  // The case at --mu (its mesh and load path), then --out.
  if (request.case_file.empty()) {
    return cases::frictional_case_info(request.case_name).dimension == 3 ? solve_builtin<3>(request)
                                                                          : solve_builtin<2>(request);
  }
  const std::optional<cases::FrictionalCaseFile> file = cases::frictional_case_from_toml_file(request.case_file);
  require(file.has_value(), "case file " + request.case_file + " has no friction keys");  // checked by the caller
  if (cases::case_dimension(file->spec) == 3) return solve_and_write<3>(request, load_file<3>(request, *file));
  return solve_and_write<2>(request, load_file<2>(request, *file));
}

}  // namespace contactrb::app
