// contactrb.Model (load, save, solve, solve_many, fields, write_fields) and contactrb.evaluate: the
// library calls of `contactrb online` and `contactrb evaluate` (apps/contactrb/cmd_online.cpp,
// cmd_evaluate.cpp). solve_many loops in C++ with the GIL released, on one OnlineSolver (jobs = 1)
// or on online::for_each_query's threads, one solver each, as `contactrb online --batch --jobs` does.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>

#include "bindings.hpp"

namespace contactrb::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct OnlineResult {
  cases::Mu mu;
  Eigen::VectorXd coefficients, multipliers;
  double energy = 0.0, force = 0.0, estimate = kNaN, time_s = 0.0;
  py::object estimate_parts;
  int iterations = 0;
  std::string status, message;
  bool converged = false;
  int N = 0, R = 0, Mk = 0, Mg = 0;
};

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// --n, --r, --mk, --mg of the CLI: absent is the model's maximum; a given value is checked here
// (-1 would otherwise pass as "the maximum") and by the solver against the model.
online::OnlineSizes online_sizes(const std::optional<int>& N, const std::optional<int>& R, const std::optional<int>& Mk,
                                 const std::optional<int>& Mg) {
  require(!N || *N >= 1, "N must be >= 1 (got " + std::to_string(N.value_or(0)) + ")");
  require(!R || *R >= 0, "R must be >= 0 (got " + std::to_string(R.value_or(0)) + ")");
  require(!Mk || *Mk >= 0, "Mk must be >= 0 (got " + std::to_string(Mk.value_or(0)) + ")");
  require(!Mg || *Mg >= 0, "Mg must be >= 0 (got " + std::to_string(Mg.value_or(0)) + ")");
  return {N.value_or(-1), R.value_or(-1), Mk.value_or(-1), Mg.value_or(-1)};
}

// --iteration of `contactrb online`: newton only for a row-cone model (it needs the exact rows).
online::OnlineIteration checked_iteration(const contactrb::model::ReducedModel& model, const std::string& name) {
  const online::OnlineIteration iteration = online::online_iteration_from_string(name);
  require(iteration != online::OnlineIteration::Newton || model.dual_method == contactrb::model::kRowCone,
          "iteration 'newton' needs a model built with dual 'rows' (`contactrb offline --dual rows`; its dual cone "
          "is '" + model.dual_method + "')");
  return iteration;
}

// The settings of `contactrb online` (--alpha, --tol, --iteration, --start); max_iterations is
// ours. Any of alpha, tol, max_iterations given: the relaxed iteration with them (as the CLI's
// --alpha, --tol) unless `iteration` names another.
online::OnlineSettings online_settings(const contactrb::model::ReducedModel& model, const std::optional<double>& alpha,
                                       const std::optional<double>& tol, const std::optional<int>& max_iterations,
                                       const std::string& iteration, const std::string& start) {
  online::OnlineSettings settings;
  settings.initial_guess = online::initial_guess_from_string(start);
  settings.iteration = checked_iteration(model, iteration);
  if (alpha || tol || max_iterations) {
    solve::KacanovSettings k{model.kacanov_alpha, model.kacanov_tolerance, model.kacanov_max_iterations};
    if (alpha) k.alpha = *alpha;
    if (tol) k.tolerance = *tol;
    if (max_iterations) k.max_iterations = *max_iterations;
    solve::check_settings(k);
    settings.kacanov = k;
  }
  return settings;
}

OnlineResult model_solve(PyModel& m, const py::object& mu_in, const std::optional<int>& N, const std::optional<int>& R,
                         const std::optional<int>& Mk, const std::optional<int>& Mg, const std::optional<double>& alpha,
                         const std::optional<double>& tol, const std::optional<int>& max_iterations,
                         const std::string& iteration, const std::string& start) {
  const cases::Mu mu = mu_from_python(mu_in);
  const online::OnlineSettings settings = online_settings(m.model, alpha, tol, max_iterations, iteration, start);
  const online::OnlineSizes sizes = online_sizes(N, R, Mk, Mg);
  online::OnlineSolution s;
  int n_sizes[4] = {0, 0, 0, 0};
  {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(m.solver_mutex);
    online::OnlineSolver& solver = m.online(sizes);
    s = solver.solve(mu, settings);
    n_sizes[0] = solver.N();
    n_sizes[1] = solver.R();
    n_sizes[2] = solver.Mk();
    n_sizes[3] = solver.Mg();
  }
  OnlineResult r;
  r.mu = mu;
  r.coefficients = s.u_hat;
  r.multipliers = s.lambda_hat;
  r.energy = s.energy;
  r.force = s.contact_force;
  r.estimate = s.estimate.available ? s.estimate.energy : kNaN;
  r.estimate_parts = to_python(to_json(s.estimate));
  r.time_s = s.time_s;
  r.iterations = s.iterations;
  r.status = solve::to_string(s.status);
  r.message = s.message;
  r.converged = s.converged();
  r.N = n_sizes[0];
  r.R = n_sizes[1];
  r.Mk = n_sizes[2];
  r.Mg = n_sizes[3];
  return r;
}

// The arrays of solve_many, one row per point; rows of different points are written by
// different threads (jobs != 1), never the same row by two.
struct ManyArrays {
  RowMatrix U, L, displacement;
  Eigen::VectorXd energy, force, estimate, time_s;
  Eigen::VectorXi iterations;
  Eigen::Matrix<std::int8_t, Eigen::Dynamic, 1> status;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> converged;

  ManyArrays(Eigen::Index n, const contactrb::model::ReducedReconstruction* rec)
      : energy(n), force(n), estimate(n), time_s(n), iterations(n), status(n), converged(n) {
    if (rec != nullptr) displacement.resize(n, rec->num_dofs);
  }
  // Row i, except coefficients and multipliers (sized once the solver's N and R are known).
  void set(Eigen::Index i, const online::OnlineSolution& s, const contactrb::model::ReducedReconstruction* rec,
           const cases::Mu& mu) {
    energy(i) = s.energy;
    force(i) = s.contact_force;
    estimate(i) = s.estimate.available ? s.estimate.energy : kNaN;
    time_s(i) = s.time_s;
    iterations(i) = s.iterations;
    status(i) = static_cast<std::int8_t>(s.status);
    converged(i) = s.converged();
    if (rec != nullptr) displacement.row(i) = online::reconstruct_displacement(*rec, mu, s.u_hat).transpose();
  }
};

// The largest contact pressure max_r (Xi lambda_hat)_r on the HF rows of each converged answer
// (as `contactrb sample`): NaN for the others, and for all when the model holds no
// reconstruction data.
Eigen::VectorXd peak_pressures(PyModel& m, const ManyArrays& a) {
  Eigen::VectorXd peak = Eigen::VectorXd::Constant(a.L.rows(), kNaN);
  const bool has_data = m.reconstruction.has_value() || (!m.path.empty() && io::has_reconstruction(m.path));
  if (!has_data || a.L.cols() == 0) return peak;
  const Eigen::MatrixXd& Xi = m.reconstruction_data().Xi;
  for (Eigen::Index i = 0; i < a.L.rows(); ++i) {
    if (a.converged(i)) peak(i) = (Xi.leftCols(a.L.cols()) * a.L.row(i).transpose()).maxCoeff();
  }
  return peak;
}

// jobs == 1: the Model's own solver, under its lock (the solver holds per-query workspaces).
void solve_many_serial(PyModel& m, const Eigen::MatrixXd& P, const online::OnlineSizes& sizes,
                       const online::OnlineSettings& settings, const contactrb::model::ReducedReconstruction* rec,
                       ManyArrays& a) {
  const std::lock_guard<std::mutex> lock(m.solver_mutex);
  online::OnlineSolver& solver = m.online(sizes);
  a.U.resize(P.rows(), solver.N());
  a.L.resize(P.rows(), solver.R());
  cases::Mu mu(P.cols());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    mu = P.row(i).transpose();
    online::OnlineSolution s;
    try {
      s = solver.solve(mu, settings);
    } catch (const Error& e) {
      throw Error("point " + std::to_string(i) + ": " + e.what());
    }
    a.U.row(i) = s.u_hat.transpose();
    a.L.row(i) = s.lambda_hat.transpose();
    a.set(i, s, rec, mu);
  }
}

// jobs > 1: online::for_each_query, one OnlineSolver per thread built from the (read-only) model, so
// the Model's solver and its lock are not used and two Python threads do not wait for each
// other. A solver's answer at mu does not depend on its earlier queries (online_many.hpp), so
// every row equals the serial one bit for bit. A point the solver refuses: every point is still
// tried, and the lowest such index is reported, as the serial loop would report it.
void solve_many_threads(const PyModel& m, const Eigen::MatrixXd& P, const online::OnlineSizes& sizes,
                        const online::OnlineSettings& settings, const contactrb::model::ReducedReconstruction* rec,
                        int jobs, ManyArrays& a) {
  const auto n = static_cast<std::size_t>(P.rows());
  std::vector<Eigen::VectorXd> u(n), lambda(n);
  std::mutex error_mutex;
  std::size_t error_index = n;
  std::string error_message;
  online::for_each_query(m.model, sizes, n, jobs, [&](online::OnlineSolver& solver, std::size_t k) {
    const auto i = static_cast<Eigen::Index>(k);
    const cases::Mu mu = P.row(i).transpose();
    online::OnlineSolution s;
    try {
      s = solver.solve(mu, settings);
    } catch (const Error& e) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (k < error_index) {
        error_index = k;
        error_message = e.what();
      }
      return;
    }
    a.set(i, s, rec, mu);
    u[k] = std::move(s.u_hat);
    lambda[k] = std::move(s.lambda_hat);
  });
  if (error_index < n) throw Error("point " + std::to_string(error_index) + ": " + error_message);
  // Every solver has the same sizes: those of the first answer.
  a.U.resize(P.rows(), u[0].size());
  a.L.resize(P.rows(), lambda[0].size());
  for (std::size_t k = 0; k < n; ++k) {
    a.U.row(static_cast<Eigen::Index>(k)) = u[k].transpose();
    a.L.row(static_cast<Eigen::Index>(k)) = lambda[k].transpose();
  }
}

py::dict model_solve_many(PyModel& m, const py::object& points, const std::optional<int>& N, const std::optional<int>& R,
                          const std::optional<int>& Mk, const std::optional<int>& Mg,
                          const std::optional<double>& alpha, const std::optional<double>& tol,
                          const std::optional<int>& max_iterations, const std::string& iteration,
                          const std::string& start, bool fields, int jobs) {
  require(jobs >= 0, "jobs must be >= 0 (0: every hardware thread), got " + std::to_string(jobs));
  const Eigen::MatrixXd P = points_from_python(points, static_cast<int>(m.model.parameters.size()));
  const online::OnlineSettings settings = online_settings(m.model, alpha, tol, max_iterations, iteration, start);
  const online::OnlineSizes sizes = online_sizes(N, R, Mk, Mg);
  const contactrb::model::ReducedReconstruction* rec =
      fields ? &m.reconstruction_data() : nullptr;  // may read the file
  const Eigen::Index n = P.rows();
  // 0, and any value above the hardware threads (a thread and a solver each, no faster): every thread.
  if (jobs == 0 || jobs > online::hardware_jobs()) jobs = online::hardware_jobs();
  ManyArrays a(n, rec);
  {
    py::gil_scoped_release release;  // no Python object is touched in the loop
    if (jobs == 1 || n == 0) {  // n == 0: the Model's solver checks the sizes and gives N and R
      solve_many_serial(m, P, sizes, settings, rec, a);
    } else {
      solve_many_threads(m, P, sizes, settings, rec, jobs, a);
    }
  }
  py::dict d;
  d["mu"] = P;
  // The same array under the CLI's name (online --batch: u_hat, lambda_hat, contact_force) and
  // the module's own.
  const py::object U = py::cast(a.U), L = py::cast(a.L), force = py::cast(a.force);
  d["coefficients"] = U;
  d["u_hat"] = U;
  d["multipliers"] = L;
  d["lambda_hat"] = L;
  d["energy"] = a.energy;
  d["force"] = force;
  d["contact_force"] = force;
  d["estimate"] = a.estimate;
  d["iterations"] = a.iterations;
  d["status"] = a.status;
  d["converged"] = a.converged;
  d["time_s"] = a.time_s;
  d["peak_pressure"] = peak_pressures(m, a);
  if (rec != nullptr) {
    // (n, n_nodes, 2): DOF 2 i + c of row k is [k, i, c].
    py::array_t<double> arr({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(a.displacement.cols() / 2),
                             static_cast<py::ssize_t>(2)});
    std::copy(a.displacement.data(), a.displacement.data() + a.displacement.size(), arr.mutable_data());
    d["displacement"] = arr;
  }
  return d;
}

// The displacement and multipliers of a reduced solution on the HF mesh.
py::dict model_fields(PyModel& m, const OnlineResult& r) {
  const contactrb::model::ReducedReconstruction& rec = m.reconstruction_data();
  const mesh::Mesh& reference = m.reference_mesh();
  const cases::CaseSpec spec = m.spec();
  const mesh::Mesh mapped = cases::mapped_mesh(spec, reference, r.mu);
  py::dict d;
  d["nodes"] = node_coordinates(mapped);
  d["reference_nodes"] = node_coordinates(reference);
  d["triangles"] = triangle_array(reference);
  d["body"] = py::array_t<int>(static_cast<py::ssize_t>(reference.body.size()), reference.body.data());
  d["displacement"] = node_vectors(online::reconstruct_displacement(rec, r.mu, r.coefficients));
  d["multipliers"] = online::reconstruct_multipliers(rec, r.mu, r.multipliers);
  return d;
}

py::dict model_write_fields(PyModel& m, const OnlineResult& r, const std::string& dir) {
  const contactrb::model::ReducedReconstruction& rec = m.reconstruction_data();
  const mesh::Mesh& reference = m.reference_mesh();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  require(std::filesystem::is_directory(dir), "cannot create the directory '" + dir + "'");
  const study::SolutionFiles f =
      study::write_solution_fields(m.spec(), reference, r.mu, m.model.surface.discretization,
                                   online::reconstruct_displacement(rec, r.mu, r.coefficients),
                                   online::reconstruct_multipliers(rec, r.mu, r.multipliers), dir);
  py::dict d;
  d["vtu"] = f.vtu;
  d["deformed_vtu"] = f.deformed_vtu;
  d["contact_vtu"] = f.contact_vtu;
  d["multipliers"] = f.multipliers;
  return d;
}

py::dict evaluate(PyModel& m, const py::object& set, const std::optional<int>& N, const std::optional<int>& R,
                  const std::optional<int>& Mk, const std::optional<int>& Mg, const std::string& iteration, int jobs,
                  int repeats, bool progress) {
  require(jobs >= 1, "jobs must be >= 1 (got " + std::to_string(jobs) + ")");
  require(repeats >= 1, "repeats must be >= 1 (got " + std::to_string(repeats) + ")");
  const cases::CaseSpec spec = m.spec();
  std::vector<cases::Mu> mus;
  if (py::isinstance<py::str>(set)) {
    mus = spec.set(set.cast<std::string>());
  } else if (py::isinstance<PySnapshots>(set)) {
    for (const io::Snapshot& snap : set.cast<const PySnapshots&>().set.snapshots) mus.push_back(snap.mu);
  } else {
    const Eigen::MatrixXd P = points_from_python(set, spec.num_parameters());
    for (Eigen::Index i = 0; i < P.rows(); ++i) mus.push_back(P.row(i).transpose());
  }
  const contactrb::model::ReducedReconstruction& rec = m.reconstruction_data();
  study::EvaluationOptions options;
  options.sizes = online_sizes(N, R, Mk, Mg);
  options.online.iteration = checked_iteration(m.model, iteration);
  options.online_repeats = repeats;
  options.jobs = jobs;
  options.progress = progress ? offline::ProgressMode::Lines : offline::ProgressMode::None;
  std::optional<study::Evaluation> e;
  {
    py::gil_scoped_release release;
    e.emplace(study::evaluate_model(m.model, rec, spec, mus, options));
  }
  const auto n = static_cast<Eigen::Index>(e->rows.size());
  const auto column = [&](double study::EvaluationRow::*f) {
    Eigen::VectorXd v(n);
    for (Eigen::Index i = 0; i < n; ++i) v(i) = e->rows[static_cast<std::size_t>(i)].*f;
    return v;
  };
  // evaluation.json's content (study::evaluation_json) and the rows as arrays, named as the columns
  // of evaluation.csv.
  py::dict d = to_python_dict(study::evaluation_json(*e, m.model, mus, options));
  Eigen::MatrixXd mu(n, spec.num_parameters());
  Eigen::VectorXi hf_it(n), rb_it(n);
  Eigen::Matrix<bool, Eigen::Dynamic, 1> hf_ok(n), rb_ok(n);
  std::vector<std::string> hf_status, rb_status;
  for (Eigen::Index i = 0; i < n; ++i) {
    const study::EvaluationRow& r = e->rows[static_cast<std::size_t>(i)];
    mu.row(i) = r.mu.transpose();
    hf_it(i) = r.hf_iterations;
    rb_it(i) = r.rb_iterations;
    hf_ok(i) = r.hf_converged;
    rb_ok(i) = r.rb_converged;
    hf_status.push_back(r.hf_status);
    rb_status.push_back(r.rb_status);
  }
  d["mu"] = mu;
  d["hf_converged"] = hf_ok;
  d["hf_status"] = hf_status;
  d["hf_iterations"] = hf_it;
  d["rb_converged"] = rb_ok;
  d["rb_status"] = rb_status;
  d["rb_iterations"] = rb_it;
  using Row = study::EvaluationRow;
  const std::vector<std::pair<const char*, double Row::*>> columns = {
      {"hf_time_s", &Row::hf_time_s},     {"online_time_s", &Row::online_time_s}, {"speedup", &Row::speedup},
      {"e_ener", &Row::e_ener},           {"e_displ", &Row::e_displ},             {"e_inter", &Row::e_inter},
      {"e_press", &Row::e_press},         {"e_force", &Row::e_force},             {"e_peak", &Row::e_peak},
      {"e_press_cone", &Row::e_press_cone}, {"force_hf", &Row::force_hf},         {"force_rb", &Row::force_rb},
      {"peak_hf", &Row::peak_hf},         {"peak_rb", &Row::peak_rb},             {"energy_hf", &Row::energy_hf},
      {"energy_rb", &Row::energy_rb},     {"e_energy_norm", &Row::e_energy_norm}, {"estimate", &Row::estimate},
      {"effectivity", &Row::effectivity}};
  for (const auto& [name, f] : columns) d[name] = column(f);
  // The summary's numbers also under flat names (summary["max_e_displ"]), as docs/python.md
  // shows them.
  const study::EvaluationSummary& s = e->summary;
  py::dict sum = d["summary"].cast<py::dict>();
  sum["max_e_ener"] = s.max_e_ener;
  sum["mean_e_ener"] = s.mean_e_ener;
  sum["max_e_displ"] = s.max_e_displ;
  sum["mean_e_displ"] = s.mean_e_displ;
  sum["max_e_inter"] = s.max_e_inter;
  sum["mean_e_inter"] = s.mean_e_inter;
  sum["max_e_press"] = s.max_e_press;
  sum["mean_e_press"] = s.mean_e_press;
  sum["max_e_force"] = s.max_e_force;
  sum["mean_e_force"] = s.mean_e_force;
  sum["max_e_peak"] = s.max_e_peak;
  sum["mean_e_peak"] = s.mean_e_peak;
  sum["max_e_press_cone"] = s.max_e_press_cone;
  sum["effectivity_count"] = s.effectivity_count;
  sum["min_effectivity"] = s.min_effectivity;
  sum["median_effectivity"] = s.median_effectivity;
  sum["max_effectivity"] = s.max_effectivity;
  return d;
}

std::shared_ptr<PyModel> load_model(const std::string& path) {
  auto m = std::make_shared<PyModel>();
  m->model = io::read_reduced_model_file(path);
  m->path = path;
  m->greedy = py::none();
  return m;
}

}  // namespace

online::OnlineSolver& PyModel::online(const online::OnlineSizes& sizes) {
  const auto same = [](const online::OnlineSizes& a, const online::OnlineSizes& b) {
    return a.N == b.N && a.R == b.R && a.Mk == b.Mk && a.Mg == b.Mg;
  };
  if (!solver || !same(sizes, solver_sizes)) {
    solver.reset();
    solver = std::make_unique<online::OnlineSolver>(model, sizes);
    solver_sizes = sizes;
  }
  return *solver;
}

const contactrb::model::ReducedReconstruction& PyModel::reconstruction_data() {
  if (!reconstruction) {
    require(!path.empty(), "this model holds no reconstruction data");
    contactrb::model::ReducedReconstruction rec = io::read_reconstruction(path);
    online::check_reconstruction(model, rec);
    reconstruction = std::move(rec);
  }
  return *reconstruction;
}

cases::CaseSpec PyModel::spec() const {
  return cases::case_from_record(model.case_kind, model.case_spec, path.empty() ? "reduced model" : path);
}

const mesh::Mesh& PyModel::reference_mesh() {
  if (!reference) {
    const cases::CaseSpec s = spec();
    const contactrb::model::ReducedReconstruction& rec = reconstruction_data();
    py::gil_scoped_release release;
    reference = std::make_shared<const mesh::Mesh>(study::model_reference_mesh(s, model, rec, path.empty() ? "reduced model" : path));
  }
  return *reference;
}

void bind_online(py::module_& m) {
  {
    // Status codes of solve_many()['status']: contactrb.STATUS[code] is its name.
    py::tuple names(4);
    for (int k = 0; k < 4; ++k) names[static_cast<std::size_t>(k)] = solve::to_string(static_cast<solve::KacanovStatus>(k));
    m.attr("STATUS") = names;
  }

  py::class_<OnlineResult>(m, "OnlineResult",
                           "A reduced (online) solve (Model.solve). A solve that did not converge has\n"
                           "converged = False, its status and message, and estimate NaN: never a silent value.")
      .def_readonly("mu", &OnlineResult::mu)
      .def_readonly("coefficients", &OnlineResult::coefficients, "reduced coordinates u_hat (N)")
      .def_readonly("multipliers", &OnlineResult::multipliers, "reduced multipliers lambda_hat (R), >= 0")
      .def_readonly("energy", &OnlineResult::energy)
      .def_readonly("force", &OnlineResult::force, "total contact force")
      .def_readonly("estimate", &OnlineResult::estimate,
                    "a posteriori estimate of |u_hf - u_rb|_A(mu) (NaN: not available)")
      .def_readonly("estimate_parts", &OnlineResult::estimate_parts,
                    "the estimate and its parts (dict: the 'estimate' of `contactrb online`), or None")
      .def_readonly("iterations", &OnlineResult::iterations)
      .def_readonly("status", &OnlineResult::status, "converged | max_iterations | step_failed | non_finite")
      .def_readonly("message", &OnlineResult::message)
      .def_readonly("converged", &OnlineResult::converged)
      .def_readonly("time_s", &OnlineResult::time_s)
      .def_property_readonly("sizes",
                             [](const OnlineResult& r) {
                               py::dict d;
                               d["N"] = r.N;
                               d["R"] = r.R;
                               d["Mk"] = r.Mk;
                               d["Mg"] = r.Mg;
                               return d;
                             })
      .def("__repr__", [](const OnlineResult& r) {
        return "OnlineResult(mu=" + cases::mu_values_text(r.mu) + ", status=" + r.status + ", iterations=" +
               std::to_string(r.iterations) + ")";
      });

  py::class_<PyModel, std::shared_ptr<PyModel>>(m, "Model",
                                                 "A reduced model: contactrb.offline() or Model.load(path).")
      .def_static("load", &load_model, py::arg("path"),
                  "Reads a model file written by contactrb.offline or `contactrb offline`.")
      .def(
          "save",
          [](PyModel& mm, const std::string& path) {
            io::write_reduced_model_file(mm.model, mm.reconstruction_data(), path);
            mm.path = path;
          },
          py::arg("path"), "Writes the model and its reconstruction data (atomically).")
      .def_readonly("path", &PyModel::path)
      .def_readonly("report", &PyModel::report,
                    "offline.json's content, but for the CLI's paths and times (a model from offline())")
      .def_readonly("greedy", &PyModel::greedy,
                    "offline(method='greedy'): greedy.json's content, the selected and excluded points as\n"
                    "(n, p) arrays and the selected snapshots; None otherwise")
      .def_property_readonly("case_name", [](const PyModel& mm) { return mm.model.case_name; })
      .def_property_readonly("level", [](const PyModel& mm) { return mm.model.level; })
      .def_property_readonly("parameters", [](const PyModel& mm) { return parameter_list(mm.model.parameters); })
      .def_property_readonly("parameter_names",
                             [](const PyModel& mm) {
                               std::vector<std::string> n;
                               for (const auto& p : mm.model.parameters) n.push_back(p.name);
                               return n;
                             })
      .def_property_readonly("sizes",
                             [](const PyModel& mm) {
                               py::dict d;
                               d["N"] = mm.model.N_max;
                               d["R"] = mm.model.online_R_max();
                               d["Mk"] = mm.model.Mk_max;
                               d["Mg"] = mm.model.Mg_max;
                               return d;
                             },
                             "the maximal sizes {'N', 'R', 'Mk', 'Mg'}")
      .def_property_readonly("training_mu", [](const PyModel& mm) { return Eigen::MatrixXd(mm.model.training_mu.transpose()); },
                             "(P, p) training points")
      .def("solve", &model_solve, py::arg("mu"), py::kw_only(), py::arg("N") = py::none(), py::arg("R") = py::none(),
           py::arg("Mk") = py::none(), py::arg("Mg") = py::none(), py::arg("alpha") = py::none(),
           py::arg("tol") = py::none(), py::arg("max_iterations") = py::none(), py::arg("iteration") = "automatic",
           py::arg("start") = "interpolated",
           "Online solve at mu, as `contactrb online --mu`: returns an OnlineResult. N, R, Mk, Mg: sizes\n"
           "(default: the model's maxima). alpha, tol, max_iterations: the relaxed Kacanov iteration with\n"
           "these (default: the model's, accelerated). iteration: 'automatic' | 'relaxed' | 'accelerated' |\n"
           "'newton' (row-cone models), as `online --iteration`. start: 'interpolated' | 'zero'.")
      .def("solve_many", &model_solve_many, py::arg("mu"), py::kw_only(), py::arg("N") = py::none(),
           py::arg("R") = py::none(), py::arg("Mk") = py::none(), py::arg("Mg") = py::none(),
           py::arg("alpha") = py::none(), py::arg("tol") = py::none(), py::arg("max_iterations") = py::none(),
           py::arg("iteration") = "automatic", py::arg("start") = "interpolated", py::arg("fields") = false,
           py::arg("jobs") = 1,
           "Online solves at the rows of an (n, p) array (or n values for p = 1), looped in C++ with the GIL\n"
           "released; equal to a loop of solve(). jobs: threads, one solver each (0: every hardware\n"
           "thread); the rows are in input order and bitwise those of jobs=1 (time_s aside). Returns\n"
           "a dict of numpy arrays, one row per point:\n"
           "mu, coefficients (n, N), multipliers (n, R), energy, force, estimate (NaN: none), iterations,\n"
           "(u_hat, lambda_hat, contact_force: the same arrays under the names of `online --batch`),\n"
           "status (codes: contactrb.STATUS[code]), converged, time_s; with fields=True also\n"
           "displacement (n, n_nodes, 2), the reconstructed displacement on the HF mesh. A point outside\n"
           "the domain raises contactrb.Error naming the point.")
      .def("fields", &model_fields, py::arg("result"),
           "The reduced solution on the HF mesh: {'nodes' (Omega(mu)), 'reference_nodes', 'triangles',\n"
           "'body', 'displacement' (n_nodes, 2), 'multipliers' (one per HF constraint row)}.")
      .def("write_fields", &model_write_fields, py::arg("result"), py::arg("directory"),
           "Writes solution.vtu, solution_deformed.vtu, contact.vtu and multipliers.csv of a result into\n"
           "`directory` (created if missing), as `contactrb online --out`; returns their paths.")
      .def("__repr__", [](const PyModel& mm) {
        return "Model(case='" + mm.model.case_name + "', N=" + std::to_string(mm.model.N_max) + ", R=" +
               std::to_string(mm.model.online_R_max()) + ", Mk=" + std::to_string(mm.model.Mk_max) + ", Mg=" +
               std::to_string(mm.model.Mg_max) + ")";
      });

  m.def("evaluate", &evaluate, py::arg("model"), py::arg("set") = "verification", py::kw_only(),
        py::arg("N") = py::none(), py::arg("R") = py::none(), py::arg("Mk") = py::none(), py::arg("Mg") = py::none(),
        py::arg("iteration") = "automatic", py::arg("jobs") = 1, py::arg("repeats") = 5, py::arg("progress") = false,
        "Errors (64)-(66), estimates and speed-ups of a model against HF solves over a named set of its\n"
        "case, an (n, p) array of points or the points of a Snapshots (solved again), as `contactrb\n"
        "evaluate`. Returns evaluation.json's content (summary, sizes, values, ...) and one numpy array\n"
        "per column of evaluation.csv (one row per point). iteration: the reduced iteration, as solve().");
}

}  // namespace contactrb::python
