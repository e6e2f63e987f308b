#pragma once
// The Python module `contactrb` (pybind11; docs/python.md). Every contactrb header the bindings
// use is included here and only here, so that a move of a library header changes this one file.
// The bindings call the same library functions as the CLI (apps/contactrb/cmd_*.cpp), in the
// same order and with the same settings, so that their results are bitwise the CLI's
// (tests/python/test_cases_hf.py, test_online.py, test_three_parameters.py).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/cases/case_record.hpp"
#include "contactrb/cases/case_spec.hpp"
#include "contactrb/cases/case_toml.hpp"
#include "contactrb/cases/catalog.hpp"
#include "contactrb/cases/parameter.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/version.hpp"
#include "contactrb/hf/hf_solution_json.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/io/snapshot_file.hpp"
#include "contactrb/study/evaluation.hpp"
#include "contactrb/study/evaluation_json.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/offline_greedy.hpp"
#include "contactrb/offline/offline_greedy_json.hpp"
#include "contactrb/offline/offline_report_json.hpp"
#include "contactrb/online/online_many.hpp"
#include "contactrb/online/online_solution_json.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/offline/snapshot_generation.hpp"
#include "contactrb/study/solution_fields.hpp"

namespace contactrb::python {

namespace py = pybind11;

// A case specification with its reference meshes (generated once per level, on first use).
struct PyCase {
  cases::CaseSpec spec;
  std::string source;  // the built-in name or the TOML path it came from
  std::vector<std::shared_ptr<const mesh::Mesh>> meshes;  // by level (null: not generated yet)
  const mesh::Mesh& reference(int level);
};

// A snapshot set in memory, and the file it was read from or written to (empty: none).
struct PySnapshots {
  io::SnapshotSet set;
  std::string path;
};

// A reduced model, its reconstruction data (loaded on first use when it came from a file) and
// one online solver per set of sizes (the last one used is kept). The solver is used with the GIL
// released: `solver_mutex` serializes its use (and its replacement) between Python threads.
struct PyModel {
  contactrb::model::ReducedModel model;
  std::optional<contactrb::model::ReducedReconstruction> reconstruction;
  std::string path;       // the file it was loaded from or saved to (empty: none)
  py::dict report;        // offline report (offline(): offline.json's content), empty for a loaded model
  py::object greedy;      // greedy table (offline(method='greedy')), None otherwise
  std::unique_ptr<contactrb::online::OnlineSolver> solver;
  contactrb::online::OnlineSizes solver_sizes;
  std::mutex solver_mutex;
  std::shared_ptr<const mesh::Mesh> reference;  // the HF reference mesh (fields), on first use
  contactrb::online::OnlineSolver& online(const contactrb::online::OnlineSizes& sizes);
  const contactrb::model::ReducedReconstruction& reconstruction_data();
  cases::CaseSpec spec() const;  // the case the model records
  const mesh::Mesh& reference_mesh();
};

// mu from Python: a number (p = 1) or a sequence / 1-D array of p numbers.
cases::Mu mu_from_python(const py::handle& mu);
// An (n, p) float array of parameter points from a 2-D array, or a 1-D array (p = 1: n points;
// p > 1: one point); `p` is the number of parameters.
Eigen::MatrixXd points_from_python(const py::handle& points, int p);
// The numpy (n, 2) array of a DOF vector (DOF 2 i + c: node i, component c).
py::array_t<double> node_vectors(const Eigen::VectorXd& u);
py::array_t<double> node_coordinates(const mesh::Mesh& m);
py::array_t<int> triangle_array(const mesh::Mesh& m);
py::list parameter_list(const std::vector<cases::ParameterSpec>& parameters);
// A JSON value of the library (a record's to_json) as Python: dict, list, float, int, bool, str
// or None (json_to_python.cpp); to_python_dict for an object.
py::object to_python(const nlohmann::json& j);
py::dict to_python_dict(const nlohmann::json& j);

void bind_cases(py::module_& m);
void bind_offline(py::module_& m);
void bind_online(py::module_& m);

}  // namespace contactrb::python
