// contactrb.snapshots(), contactrb.Snapshots and contactrb.offline(): the library calls of
// `contactrb snapshots` and `contactrb offline` (POD path and --greedy), apps/contactrb/cmd_snapshots.cpp
// and cmd_offline.cpp, with the same settings and defaults.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bindings.hpp"
#include "contactrb/cases/recorded_mesh.hpp"

namespace contactrb::python {

namespace {

// The HF solves a call asks for: a named set of the case, or explicit points (set "custom").
contactrb::offline::SnapshotRequest snapshot_request(const PyCase& c, const py::object& set, int level,
                                                     const std::optional<std::string>& constraint_name, double alpha,
                                                     double tolerance, int max_iterations,
                                                     const std::optional<std::string>& solver, int sequence) {
  require(level >= 0, "level must be >= 0 (got " + std::to_string(level) + ")");
  require(sequence >= -1, "sequence must be >= 0, or -1 for automatic (got " + std::to_string(sequence) + ")");
  std::optional<contact::Discretization> constraint;
  if (constraint_name) constraint = contact::discretization_from_string(*constraint_name);
  std::string set_name = "training";
  std::optional<std::vector<cases::Mu>> values;
  if (py::isinstance<py::str>(set)) {
    set_name = set.cast<std::string>();
  } else {
    const Eigen::MatrixXd points = points_from_python(set, c.spec.num_parameters());
    values.emplace();
    for (Eigen::Index i = 0; i < points.rows(); ++i) values->push_back(points.row(i).transpose());
  }
  contactrb::offline::SnapshotRequest request =
      contactrb::offline::make_snapshot_request(c.spec, set_name, level, constraint, values);
  request.settings.kacanov.alpha = alpha;
  request.settings.kacanov.tolerance = tolerance;
  request.settings.kacanov.max_iterations = max_iterations;
  solve::check_settings(request.settings.kacanov);
  // None: the request's default (offline::default_snapshot_method), as the CLI's --solver.
  if (solver) request.settings.method = contactrb::hf::hf_method_from_string(*solver);
  contactrb::offline::set_snapshot_sequence(request, sequence);  // as the CLI's --sequence
  return request;
}

// None (the default): progress on stderr when it is a terminal (a line updated in place), none
// otherwise (a script, a notebook, a test); True: a line per solve; False: none.
contactrb::offline::ProgressMode progress_mode(const std::optional<bool>& progress) {
  if (!progress) {
    return ::isatty(STDERR_FILENO) ? contactrb::offline::ProgressMode::Terminal : contactrb::offline::ProgressMode::None;
  }
  return *progress ? contactrb::offline::ProgressMode::Lines : contactrb::offline::ProgressMode::None;
}

io::SnapshotSet run_snapshots(const contactrb::offline::SnapshotRequest& request, int jobs,
                              const std::optional<bool>& progress) {
  require(jobs >= 1, "jobs must be >= 1 (got " + std::to_string(jobs) + ")");
  contactrb::offline::SnapshotRunOptions run;
  run.jobs = std::min(jobs, contactrb::online::hardware_jobs());  // more threads than the hardware's: no faster
  run.progress = progress_mode(progress);
  py::gil_scoped_release release;
  return contactrb::offline::generate_snapshots(request, run);
}

PySnapshots make_snapshots(PyCase& c, const py::object& set, int jobs, int level,
                           const std::optional<std::string>& constraint, double alpha, double tolerance,
                           int max_iterations, const std::optional<std::string>& solver, int sequence,
                           const std::optional<std::string>& path, const std::optional<bool>& progress) {
  const contactrb::offline::SnapshotRequest request =
      snapshot_request(c, set, level, constraint, alpha, tolerance, max_iterations, solver, sequence);
  PySnapshots s{run_snapshots(request, jobs, progress), {}};
  if (path) {
    io::write_snapshot_file(s.set, *path);
    s.path = *path;
  }
  return s;
}

// The failed solves of a set (as `contactrb offline` reports them).
std::string failure_report(const io::SnapshotSet& set, const std::string& where) {
  std::ostringstream os;
  os << set.num_failed() << " of " << set.snapshots.size() << " snapshot solves failed (" << where
     << "); no model built:";
  for (const io::Snapshot& snap : set.snapshots) {
    if (!snap.converged) os << "\n  mu = " << cases::mu_values_text(snap.mu) << ": " << snap.status << ": " << snap.message;
  }
  return os.str();
}

// The offline settings of `contactrb offline`'s flags (settings_from in cmd_offline.cpp).
contactrb::offline::OfflineSettings offline_settings(const py::dict& kw) {
  contactrb::offline::OfflineSettings s;
  const auto get = [&](const char* key) -> py::object { return kw.contains(key) ? py::object(kw[key]) : py::none(); };
  if (!get("eps_pod").is_none()) s.eps_pod = get("eps_pod").cast<double>();
  if (!get("N").is_none()) {
    const int n = get("N").cast<int>();
    require(n >= 1, "N must be >= 1 (got " + std::to_string(n) + ")");
    s.pod_modes = n;
  }
  if (!get("inner_product").is_none()) {
    s.inner_product = contactrb::offline::inner_product_from_string(get("inner_product").cast<std::string>());
  }
  if (!get("dual").is_none())
    s.dual_method = contactrb::offline::dual_cone_method_from_string(get("dual").cast<std::string>());
  if (!get("R").is_none()) {
    const int r = get("R").cast<int>();
    require(r >= 1, "R must be >= 1 (got " + std::to_string(r) + ")");
    s.dual_size = r;
  }
  if (!get("eps_du").is_none()) s.eps_du = get("eps_du").cast<double>();
  if (!get("eps_eim_k").is_none()) s.eps_eim_k = get("eps_eim_k").cast<double>();
  if (!get("eps_eim_g").is_none()) s.eps_eim_g = get("eps_eim_g").cast<double>();
  require(s.eps_pod >= 0.0, "eps_pod must be >= 0");
  require(s.eps_du >= 0.0, "eps_du must be >= 0");
  require(s.eps_eim_k >= 0.0, "eps_eim_k must be >= 0");
  require(s.eps_eim_g >= 0.0, "eps_eim_g must be >= 0");
  if (!get("absolute_tolerances").is_none() && get("absolute_tolerances").cast<bool>()) s.set_absolute();
  if (!get("compression").is_none()) s.compression = get("compression").cast<bool>();
  if (!get("supremizers").is_none()) s.supremizers = get("supremizers").cast<bool>();
  contactrb::offline::check_settings(s);
  return s;
}

// greedy.json's content, with the selected and excluded points as (n, p) arrays and the selected
// HF snapshots as a Snapshots.
py::dict greedy_dict(const contactrb::offline::GreedyOfflineResult& g,
                     const contactrb::offline::SnapshotRequest& request,
                     const contactrb::offline::GreedyOfflineSettings& settings, int p) {
  py::dict d = to_python_dict(contactrb::offline::greedy_json(g, request, settings));
  const auto points = [&](const std::vector<int>& idx) {
    Eigen::MatrixXd a(static_cast<Eigen::Index>(idx.size()), p);
    for (std::size_t k = 0; k < idx.size(); ++k) a.row(static_cast<Eigen::Index>(k)) = request.mu[static_cast<std::size_t>(idx[k])].transpose();
    return a;
  };
  d["selected"] = points(g.selected);
  d["excluded"] = points(g.excluded);
  d["snapshots"] = PySnapshots{g.snapshots, {}};
  return d;
}

std::shared_ptr<PyModel> offline_from_set(const io::SnapshotSet& set, const std::string& origin,
                                          const contactrb::offline::OfflineSettings& settings) {
  require(set.num_failed() == 0, failure_report(set, origin));
  const cases::CaseSpec spec = cases::case_from_record(set.case_kind, set.case_spec, origin);
  cases::recorded_reference_mesh(spec, {set.level, set.num_dofs, &set.mesh}, origin.empty() ? "snapshot set" : origin);
  std::optional<contactrb::offline::OfflineResult> result;
  {
    py::gil_scoped_release release;
    result.emplace(contactrb::offline::build_reduced_model(set, spec, settings));
  }
  auto m = std::make_shared<PyModel>();
  m->report = to_python_dict(contactrb::offline::offline_json(set, settings, *result));
  m->model = std::move(result->model);
  m->reconstruction = std::move(result->reconstruction);
  m->greedy = py::none();
  return m;
}

// A Case object, or a new one from a name or TOML path.
py::object as_case(const py::object& source) {
  if (py::isinstance<PyCase>(source)) return source;
  require(py::isinstance<py::str>(source), "expected a Case, a case name or a TOML case file path");
  return py::type::of<PyCase>()(source);
}

std::shared_ptr<PyModel> offline(const py::object& source, const std::string& method, const py::object& set, int jobs,
                                 int level, const std::optional<std::string>& constraint, double alpha,
                                 double tolerance, int max_iterations, const std::optional<std::string>& solver,
                                 int sequence, double greedy_tol, int max_hf, int greedy_batch,
                                 double greedy_saturation, int greedy_preconditioner_points,
                                 const std::optional<std::string>& path, const std::optional<bool>& progress,
                                 const py::kwargs& kw) {
  for (const auto& item : kw) {
    static const std::vector<std::string> known = {"eps_pod", "N", "inner_product", "dual", "R", "eps_du",
                                                   "eps_eim_k", "eps_eim_g", "absolute_tolerances",
                                                   "compression", "supremizers"};
    const std::string key = py::str(item.first);
    require(std::find(known.begin(), known.end(), key) != known.end(), "offline: unknown setting '" + key + "'");
  }
  const contactrb::offline::OfflineSettings settings = offline_settings(kw);
  std::shared_ptr<PyModel> m;
  if (method == "pod") {
    if (py::isinstance<PySnapshots>(source)) {
      const PySnapshots& s = source.cast<const PySnapshots&>();
      m = offline_from_set(s.set, s.path.empty() ? "snapshot set" : s.path, settings);
    } else if (py::isinstance<py::str>(source) && io::is_snapshot_file(source.cast<std::string>())) {
      const std::string p = source.cast<std::string>();
      m = offline_from_set(io::read_snapshot_file(p), p, settings);
    } else {
      // A case (or its name / TOML path): its training snapshots first, as `offline --case`.
      const py::object case_object = as_case(source);
      PyCase& c = case_object.cast<PyCase&>();
      const contactrb::offline::SnapshotRequest request =
          snapshot_request(c, set, level, constraint, alpha, tolerance, max_iterations, solver, sequence);
      m = offline_from_set(run_snapshots(request, jobs, progress), "snapshot set", settings);
    }
  } else if (method == "greedy") {
    require(!py::isinstance<PySnapshots>(source), "offline(method='greedy') needs a case (it computes its own snapshots)");
    const py::object case_object = as_case(source);
    PyCase& c = case_object.cast<PyCase&>();
    require(std::isfinite(greedy_tol) && greedy_tol > 0.0, "greedy_tol must be a finite number > 0");
    require(max_hf >= 1, "max_hf must be >= 1 (got " + std::to_string(max_hf) + ")");
    require(greedy_batch >= 1, "greedy_batch must be >= 1 (got " + std::to_string(greedy_batch) + ")");
    require(jobs >= 1, "jobs must be >= 1 (got " + std::to_string(jobs) + ")");
    contactrb::offline::GreedyOfflineSettings gs;
    gs.offline = settings;
    gs.tolerance = greedy_tol;
    gs.max_hf = max_hf;
    gs.batch = greedy_batch;
    gs.saturation = greedy_saturation;
    gs.preconditioner_points = greedy_preconditioner_points;
    gs.jobs = jobs;
    gs.progress = progress_mode(progress);
    contactrb::offline::check_settings(gs);
    const contactrb::offline::SnapshotRequest request =
        snapshot_request(c, set, level, constraint, alpha, tolerance, max_iterations, solver, sequence);
    std::optional<contactrb::offline::GreedyOfflineResult> g;
    {
      py::gil_scoped_release release;
      g.emplace(contactrb::offline::run_offline_greedy(c.spec, request, gs));
    }
    m = std::make_shared<PyModel>();
    m->model = g->offline.model;
    m->reconstruction = g->offline.reconstruction;
    m->report = to_python_dict(contactrb::offline::offline_json(g->snapshots, settings, g->offline));
    m->greedy = greedy_dict(*g, request, gs, c.spec.num_parameters());
  } else {
    throw Error("method must be 'pod' or 'greedy', got '" + method + "'");
  }
  if (path) {
    io::write_reduced_model_file(m->model, *m->reconstruction, *path);
    m->path = *path;
  }
  return m;
}

py::array_t<double> snapshot_rows(const io::SnapshotSet& set, Eigen::VectorXd io::Snapshot::*field) {
  py::ssize_t cols = 0;
  for (const io::Snapshot& s : set.snapshots) cols = std::max<py::ssize_t>(cols, (s.*field).size());
  py::array_t<double> a({static_cast<py::ssize_t>(set.snapshots.size()), cols});
  double* d = a.mutable_data();
  for (const io::Snapshot& s : set.snapshots) {
    const Eigen::VectorXd& v = s.*field;
    for (py::ssize_t j = 0; j < cols; ++j) *d++ = j < v.size() ? v(j) : std::nan("");  // a failed solve: NaN
  }
  return a;
}

}  // namespace

void bind_offline(py::module_& m) {
  py::class_<PySnapshots>(m, "Snapshots",
                          "A snapshot set: HF solutions of one case over one parameter set (contactrb.snapshots,\n"
                          "Snapshots.load). Arrays have one row per parameter point; a failed solve is recorded\n"
                          "(converged False, its status and message), never dropped.")
      .def_static(
          "load", [](const std::string& path) { return PySnapshots{io::read_snapshot_file(path), path}; },
          py::arg("path"), "Reads a snapshot file (written by contactrb.snapshots or `contactrb snapshots`).")
      .def(
          "save",
          [](PySnapshots& s, const std::string& path) {
            io::write_snapshot_file(s.set, path);
            s.path = path;
          },
          py::arg("path"), "Writes the set to an HDF5 snapshot file (atomically).")
      .def_readonly("path", &PySnapshots::path)
      .def_property_readonly("case_name", [](const PySnapshots& s) { return s.set.case_name; })
      .def_property_readonly("set_name", [](const PySnapshots& s) { return s.set.set_name; })
      .def_property_readonly("constraint", [](const PySnapshots& s) { return s.set.constraint; })
      .def_property_readonly("level", [](const PySnapshots& s) { return s.set.level; })
      .def_property_readonly("solver", [](const PySnapshots& s) { return s.set.solver; },
                             "the HF method of the solves: 'kacanov' | 'newton'")
      .def_property_readonly("num_dofs", [](const PySnapshots& s) { return s.set.num_dofs; })
      .def_property_readonly("num_failed", [](const PySnapshots& s) { return s.set.num_failed(); })
      .def_property_readonly("mu", [](const PySnapshots& s) { return snapshot_rows(s.set, &io::Snapshot::mu); },
                             "(P, p) parameter points")
      .def_property_readonly("u", [](const PySnapshots& s) { return snapshot_rows(s.set, &io::Snapshot::u); },
                             "(P, num_dofs) total displacements (DOF 2 i + c: node i, component c)")
      .def_property_readonly("multipliers", [](const PySnapshots& s) { return snapshot_rows(s.set, &io::Snapshot::lambda); },
                             "(P, R) contact pressures")
      .def_property_readonly("converged",
                             [](const PySnapshots& s) {
                               py::array_t<bool> a(static_cast<py::ssize_t>(s.set.snapshots.size()));
                               for (std::size_t i = 0; i < s.set.snapshots.size(); ++i) a.mutable_data()[i] = s.set.snapshots[i].converged;
                               return a;
                             })
      .def_property_readonly("status",
                             [](const PySnapshots& s) {
                               std::vector<std::string> v;
                               for (const auto& x : s.set.snapshots) v.push_back(x.status);
                               return v;
                             })
      .def_property_readonly("iterations",
                             [](const PySnapshots& s) {
                               py::array_t<int> a(static_cast<py::ssize_t>(s.set.snapshots.size()));
                               for (std::size_t i = 0; i < s.set.snapshots.size(); ++i) a.mutable_data()[i] = s.set.snapshots[i].iterations;
                               return a;
                             })
      .def("__len__", [](const PySnapshots& s) { return s.set.snapshots.size(); })
      .def("__repr__", [](const PySnapshots& s) {
        return "Snapshots(case='" + s.set.case_name + "', set='" + s.set.set_name + "', " +
               std::to_string(s.set.snapshots.size()) + " points, " + std::to_string(s.set.num_failed()) + " failed)";
      });

  const solve::KacanovSettings k{};
  m.def("snapshots", &make_snapshots, py::arg("case"), py::arg("set") = "training", py::kw_only(), py::arg("jobs") = 1,
        py::arg("level") = 0, py::arg("constraint") = py::none(), py::arg("alpha") = k.alpha, py::arg("tol") = k.tolerance,
        py::arg("max_iterations") = k.max_iterations, py::arg("solver") = py::none(), py::arg("sequence") = -1,
        py::arg("path") = py::none(), py::arg("progress") = py::none(),
        "HF snapshots of a case (a Case, or its name or TOML path) over a named parameter set or an (n, p)\n"
        "array of points, on `jobs` threads, as `contactrb snapshots`. solver: 'kacanov' | 'newton' (None:\n"
        "kacanov on 2D level 0, newton otherwise); sequence: the grid sequencing of the cold solves, as\n"
        "--sequence (-1: 2 with newton on 2D level >= 4, else 0). Returns a Snapshots; with path=, also\n"
        "writes the snapshot file.");
  m.def("offline", &offline, py::arg("source"), py::arg("method") = "pod", py::kw_only(), py::arg("set") = "training",
        py::arg("jobs") = 1, py::arg("level") = 0, py::arg("constraint") = py::none(), py::arg("alpha") = k.alpha,
        py::arg("tol") = k.tolerance, py::arg("max_iterations") = k.max_iterations, py::arg("solver") = py::none(),
        py::arg("sequence") = -1, py::arg("greedy_tol") = contactrb::offline::GreedyOfflineSettings{}.tolerance,
        py::arg("max_hf") = contactrb::offline::GreedyOfflineSettings{}.max_hf,
        py::arg("greedy_batch") = contactrb::offline::GreedyOfflineSettings{}.batch,
        py::arg("greedy_saturation") = contactrb::offline::GreedyOfflineSettings{}.saturation,
        py::arg("greedy_preconditioner_points") = contactrb::offline::GreedyOfflineSettings{}.preconditioner_points,
        py::arg("path") = py::none(), py::arg("progress") = py::none(),
        "The offline stage, as `contactrb offline`: returns a Model (saved to path= when given).\n"
        "method='pod': source is a Snapshots, a snapshot file path, or a case (its `set` snapshots are\n"
        "computed first). method='greedy': source is a case; the weak greedy on the error estimate over\n"
        "the set's points (greedy_tol, max_hf; greedy_batch HF solves per step, on `jobs` threads;\n"
        "greedy_saturation: the lazy sweep's constant, as --greedy-saturation, float('inf') for the full sweep;\n"
        "greedy_preconditioner_points: the row-cone model's online start and preconditioner points, as\n"
        "--greedy-preconditioner-points, 0 for the snapshots only);\n"
        "model.greedy holds its table and selected snapshots. solver: the HF method of the snapshots\n"
        "('kacanov' | 'newton'; None: kacanov on 2D level 0, newton otherwise); sequence: their grid\n"
        "sequencing, as --sequence (-1: automatic).\n"
        "Offline settings (keywords, the CLI's defaults): eps_pod, N, inner_product ('energy'|'h1'),\n"
        "dual ('cpg'|'angle'|'nmf'|'rows'|'registered'), eps_du, R, eps_eim_k, eps_eim_g, absolute_tolerances,\n"
        "compression, supremizers.");
}

}  // namespace contactrb::python
