// The extension module contactrb._contactrb: the exception class, the conversions shared by the
// binding files, and the PYBIND11_MODULE entry point (docs/python.md).
#include "bindings.hpp"

namespace contactrb::python {

cases::Mu mu_from_python(const py::handle& mu) {
  if (py::isinstance<py::float_>(mu) || py::isinstance<py::int_>(mu)) {
    return cases::Mu::Constant(1, mu.cast<double>());
  }
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(mu);
  require(a && a.ndim() <= 1, "mu must be a number or a sequence of numbers (one per parameter)");
  cases::Mu out(a.size());
  for (py::ssize_t i = 0; i < a.size(); ++i) out(i) = a.data()[i];
  return out;
}

Eigen::MatrixXd points_from_python(const py::handle& points, int p) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  require(a && (a.ndim() == 1 || a.ndim() == 2), "parameter points must be a 1-D or 2-D array of numbers");
  Eigen::Index rows = 0, cols = 0;
  if (a.ndim() == 2) {
    rows = a.shape(0);
    cols = a.shape(1);
  } else if (p == 1) {
    rows = a.shape(0);
    cols = 1;
  } else {
    rows = 1;
    cols = a.shape(0);
  }
  require(cols == p, "parameter points have " + std::to_string(cols) + " columns, the model has " + std::to_string(p) +
                         " parameters");
  Eigen::MatrixXd out(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) out(i, j) = a.data()[i * cols + j];
  }
  return out;
}

py::array_t<double> node_vectors(const Eigen::VectorXd& u) {
  py::array_t<double> a({static_cast<py::ssize_t>(u.size() / 2), static_cast<py::ssize_t>(2)});
  std::copy(u.data(), u.data() + u.size(), a.mutable_data());  // DOF 2 i + c: row i, column c
  return a;
}

py::array_t<double> node_coordinates(const mesh::Mesh& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.num_nodes()), static_cast<py::ssize_t>(2)});
  double* d = a.mutable_data();
  for (const Eigen::Vector2d& x : m.nodes) {
    *d++ = x.x();
    *d++ = x.y();
  }
  return a;
}

py::array_t<int> triangle_array(const mesh::Mesh& m) {
  py::array_t<int> a({static_cast<py::ssize_t>(m.num_triangles()), static_cast<py::ssize_t>(3)});
  int* d = a.mutable_data();
  for (const auto& t : m.triangles) {
    for (int v : t) *d++ = v;
  }
  return a;
}

py::list parameter_list(const std::vector<cases::ParameterSpec>& parameters) {
  py::list l;
  for (const cases::ParameterSpec& p : parameters) l.append(py::cast(p));
  return l;
}

}  // namespace contactrb::python

PYBIND11_MODULE(_contactrb, m) {
  namespace py = pybind11;
  using namespace contactrb::python;
  m.doc() =
      "contactrb: reduced-basis models of 2-D elastic frictionless contact (docs/python.md).\n\n"
      "Cases and HF solves (cases, Case), snapshots (snapshots, Snapshots), the offline stage (offline),\n"
      "reduced models (Model.load, Model.solve, Model.solve_many, Model.fields) and evaluate.\n"
      "Every contactrb error is raised as contactrb.Error (a RuntimeError) with the CLI's message.";
  m.attr("__version__") = contactrb::kVersion;
  // contactrb::Error -> contactrb.Error, a subclass of RuntimeError, same message.
  py::register_exception<contactrb::Error>(m, "Error", PyExc_RuntimeError);
  bind_cases(m);
  bind_offline(m);
  bind_online(m);
}
