// contactrb.cases(), contactrb.Parameter, contactrb.Case and its high-fidelity solve (the
// library calls of `contactrb solve`, apps/contactrb/cmd_solve.cpp).
#include <filesystem>

#include "bindings.hpp"

namespace contactrb::python {

namespace {

// One HF solve, as numpy arrays (Case.solve).
struct HFResult {
  cases::Mu mu;
  bool converged = false;
  std::string status, message, solver, constraint;
  int iterations = 0;
  double energy = 0.0, force = 0.0, gap_violation = 0.0, time_s = 0.0;
  int active_constraints = 0;
  py::dict kkt;
  py::array_t<double> u, nodes, reference_nodes;
  py::array_t<int> triangles;
  Eigen::VectorXd multipliers;
};

// A built-in name, or a path to a TOML case file (an existing file, or a name ending in .toml).
PyCase make_case(const std::string& name_or_path) {
  PyCase c;
  std::error_code ec;
  const bool toml = (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".toml") ||
                    name_or_path.find('/') != std::string::npos || std::filesystem::exists(name_or_path, ec);
  c.spec = toml ? cases::case_from_toml_file(name_or_path) : cases::builtin_case_spec(name_or_path);
  c.source = name_or_path;
  return c;
}

py::array_t<double> points_array(const std::vector<cases::Mu>& points, int p) {
  py::array_t<double> a({static_cast<py::ssize_t>(points.size()), static_cast<py::ssize_t>(p)});
  double* d = a.mutable_data();
  for (const cases::Mu& mu : points) {
    for (Eigen::Index k = 0; k < mu.size(); ++k) *d++ = mu(k);
  }
  return a;
}

HFResult solve_case(PyCase& c, const py::object& mu_in, int level, const std::optional<std::string>& constraint_name,
                    const std::string& method, double alpha, double tolerance, int max_iterations,
                    int newton_max_iterations) {
  // The checks of `contactrb solve`, in its order, with its messages.
  const cases::Mu mu = mu_from_python(mu_in);
  const bool from_file = c.spec.origin != "built-in" && !c.spec.origin.empty();
  cases::check_mu(c.spec.parameters, mu, "case '" + c.spec.name + "'" + (from_file ? " (" + c.source + ")" : ""));
  hf::HFSettings settings;
  settings.kacanov.alpha = alpha;
  settings.kacanov.tolerance = tolerance;
  settings.kacanov.max_iterations = max_iterations;
  solve::check_settings(settings.kacanov);
  settings.method = hf::hf_method_from_string(method);
  settings.newton.max_iterations = newton_max_iterations;
  hf::check_settings(settings.newton);
  std::optional<contact::Discretization> constraint;
  if (constraint_name) constraint = contact::discretization_from_string(*constraint_name);
  require(level >= 0, "level must be >= 0 (got " + std::to_string(level) + ")");

  const mesh::Mesh& reference = c.reference(level);
  std::optional<hf::HFSolver> solver;
  hf::HFSolution s;
  {
    py::gil_scoped_release release;
    solver.emplace(cases::make_problem(c.spec, reference, mu, constraint));
    s = solver->solve(settings);
  }
  HFResult r;
  r.mu = mu;
  r.converged = s.converged;
  r.status = solve::to_string(s.status);
  r.message = s.message;
  r.solver = hf::to_string(settings.method);
  r.constraint = contact::to_string(solver->problem().discretization);
  r.iterations = s.iterations;
  r.energy = s.energy;
  r.force = s.contact_force;
  r.gap_violation = s.gap_violation;
  r.time_s = s.time_s;
  r.active_constraints = s.active_constraints;
  r.kkt = to_python_dict(hf::to_json(s.kkt));
  r.u = node_vectors(s.u);
  r.nodes = node_coordinates(solver->problem().mesh);
  r.reference_nodes = node_coordinates(reference);
  r.triangles = triangle_array(reference);
  r.multipliers = s.lambda;
  return r;
}

}  // namespace

const mesh::Mesh& PyCase::reference(int level) {
  require(level >= 0, "level must be >= 0 (got " + std::to_string(level) + ")");
  if (meshes.size() <= static_cast<std::size_t>(level)) meshes.resize(static_cast<std::size_t>(level) + 1);
  auto& slot = meshes[static_cast<std::size_t>(level)];
  if (!slot) {
    py::gil_scoped_release release;
    slot = std::make_shared<const mesh::Mesh>(cases::reference_mesh(spec, level));
  }
  return *slot;
}

void bind_cases(py::module_& m) {
  m.def(
      "cases",
      [] {
        std::vector<std::string> names;
        for (const auto& c : cases::builtin_cases()) names.push_back(c.name);
        return names;
      },
      "The names of the built-in cases (paper Section 6), as `contactrb cases` lists them.");
  m.def(
      "case_summaries",
      [] {
        py::dict d;
        for (const auto& c : cases::builtin_cases()) d[py::str(c.name)] = c.summary;
        return d;
      },
      "{name: one-line summary} of the built-in cases.");

  py::class_<cases::ParameterSpec>(m, "Parameter", "One parameter of a case or model: name, units, kind, domain.")
      .def_readonly("name", &cases::ParameterSpec::name)
      .def_readonly("units", &cases::ParameterSpec::units)
      .def_property_readonly("kind", [](const cases::ParameterSpec& p) { return std::string(cases::to_string(p.kind)); },
                             "dirichlet-scale | body-scaling | young-modulus | traction | body-force | friction-coefficient")
      .def_readonly("min", &cases::ParameterSpec::min)
      .def_readonly("max", &cases::ParameterSpec::max)
      .def_readonly("reference", &cases::ParameterSpec::reference)
      .def("__repr__", [](const cases::ParameterSpec& p) {
        return "Parameter('" + p.name + "', " + cases::to_string(p.kind) + ", [" + cases::mu_values_text(cases::Mu::Constant(1, p.min)) +
               ", " + cases::mu_values_text(cases::Mu::Constant(1, p.max)) + "]" + (p.units.empty() ? "" : " " + p.units) + ")";
      });

  py::class_<HFResult>(m, "HFResult",
                       "A high-fidelity solve (Case.solve). u and nodes are (n, 2) arrays over the mesh nodes;\n"
                       "multipliers has one contact pressure per constraint row. A solve that did not converge\n"
                       "has converged = False, its status and message (never an exception).")
      .def_readonly("mu", &HFResult::mu)
      .def_readonly("converged", &HFResult::converged)
      .def_readonly("status", &HFResult::status, "converged | max_iterations | step_failed | non_finite")
      .def_readonly("message", &HFResult::message)
      .def_readonly("solver", &HFResult::solver)
      .def_readonly("constraint", &HFResult::constraint)
      .def_readonly("iterations", &HFResult::iterations)
      .def_readonly("energy", &HFResult::energy, "1/2 u'Au - f'u of the total displacement")
      .def_readonly("force", &HFResult::force, "total contact force sum_r lambda_r |I_r|")
      .def_readonly("gap_violation", &HFResult::gap_violation)
      .def_readonly("active_constraints", &HFResult::active_constraints)
      .def_readonly("kkt", &HFResult::kkt)
      .def_readonly("time_s", &HFResult::time_s)
      .def_readonly("u", &HFResult::u, "total displacement, (n_nodes, 2)")
      .def_readonly("nodes", &HFResult::nodes, "node coordinates of Omega(mu), (n_nodes, 2)")
      .def_readonly("reference_nodes", &HFResult::reference_nodes, "node coordinates of the reference mesh")
      .def_readonly("triangles", &HFResult::triangles, "node indices of the triangles, (n_triangles, 3)")
      .def_readonly("multipliers", &HFResult::multipliers, "contact pressures, one per constraint row")
      .def("__repr__", [](const HFResult& r) {
        return "HFResult(mu=" + cases::mu_values_text(r.mu) + ", status=" + r.status + ", iterations=" +
               std::to_string(r.iterations) + ")";
      });

  py::class_<PyCase>(m, "Case",
                     "A contact case: a built-in one by name (contactrb.cases()) or a TOML case file\n"
                     "(docs/cases.md). Case('hertz-a'), Case('examples/hertz-a/case.toml').")
      .def(py::init(&make_case), py::arg("name_or_path"))
      .def_property_readonly("name", [](const PyCase& c) { return c.spec.name; })
      .def_property_readonly("description", [](const PyCase& c) { return c.spec.description; })
      .def_property_readonly("origin", [](const PyCase& c) { return c.spec.origin; })
      .def_property_readonly("constraint", [](const PyCase& c) { return std::string(contact::to_string(c.spec.constraint)); })
      .def_property_readonly("parameters", [](const PyCase& c) { return parameter_list(c.spec.parameters); },
                             "the parameters (contactrb.Parameter), in the order of mu")
      .def_property_readonly("parameter_names",
                             [](const PyCase& c) {
                               std::vector<std::string> n;
                               for (const auto& p : c.spec.parameters) n.push_back(p.name);
                               return n;
                             })
      .def_property_readonly("num_parameters", [](const PyCase& c) { return c.spec.num_parameters(); })
      .def_property_readonly("reference_mu", [](const PyCase& c) { return cases::reference_mu(c.spec.parameters); })
      .def_property_readonly(
          "sets",
          [](const PyCase& c) {
            py::dict d;
            for (const auto& s : c.spec.sets) d[py::str(s.name)] = points_array(s.points, c.spec.num_parameters());
            return d;
          },
          "{set name: (n, p) array of its points}")
      .def(
          "set", [](const PyCase& c, const std::string& name) { return points_array(c.spec.set(name), c.spec.num_parameters()); },
          py::arg("name"), "The (n, p) points of a named parameter set (training, verification, ...).")
      .def("to_toml", [](const PyCase& c) { return cases::to_toml(c.spec); }, "The TOML text of the case.")
      .def(
          "mesh",
          [](PyCase& c, int level) {
            const mesh::Mesh& r = c.reference(level);
            py::dict d;
            d["nodes"] = node_coordinates(r);
            d["triangles"] = triangle_array(r);
            d["body"] = py::array_t<int>(static_cast<py::ssize_t>(r.body.size()), r.body.data());
            return d;
          },
          py::arg("level") = 0, "The reference mesh: {'nodes': (n, 2), 'triangles': (t, 3), 'body': (t,)}.")
      .def("solve", &solve_case, py::arg("mu"), py::kw_only(), py::arg("level") = 0,
           py::arg("constraint") = py::none(), py::arg("solver") = "kacanov",
           py::arg("alpha") = solve::KacanovSettings{}.alpha, py::arg("tol") = solve::KacanovSettings{}.tolerance,
           py::arg("max_iterations") = solve::KacanovSettings{}.max_iterations,
           py::arg("newton_max_iterations") = hf::NewtonSettings{}.max_iterations,
           "High-fidelity solve at mu (a number, or p numbers), as `contactrb solve`: returns an HFResult.\n"
           "constraint: collocation | lac | lac-simpson (default: the case's); solver: kacanov | newton.")
      .def("__repr__", [](const PyCase& c) { return "Case('" + c.spec.name + "')"; });
  py::implicitly_convertible<std::string, PyCase>();
}

}  // namespace contactrb::python
