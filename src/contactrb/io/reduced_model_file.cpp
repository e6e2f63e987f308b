#include "contactrb/io/reduced_model_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/io/hdf5_handle.hpp"
#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::io {

namespace {

using hdf5::check;
using Id = hdf5::Handle;
using H5Failure = hdf5::Failure;
using QuietHdf5 = hdf5::Quiet;

// FNV-1a, 64 bit.
class Checksum {
 public:
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ULL;
    }
  }
  void add_name(const std::string& name) { add(name.data(), name.size() + 1); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

// One dataset of `count` values of `mem_type` with the given dims.
void write_raw(hid_t file, const std::string& name, const void* data, int rank, const hsize_t* dims, hid_t file_type,
               hid_t mem_type) {
  Id space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "cannot create the dataspace of '" + name + "'");
  Id set(H5Dcreate2(file, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
         "cannot create dataset '" + name + "'");
  hsize_t total = 1;
  for (int i = 0; i < rank; ++i) total *= dims[i];
  if (total > 0) check(H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write '" + name + "'");
}

// Reads a dataset of the expected rank; returns its dims; fills `out` (resized by the caller
// through `resize(total)`).
template <typename Resize>
std::vector<hsize_t> read_raw(hid_t file, const std::string& name, int rank, hid_t mem_type, Resize resize) {
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) throw H5Failure{"missing dataset '" + name + "'"};
  Id set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset '" + name + "'");
  Id space(H5Dget_space(set.get()), H5Sclose, "cannot read the shape of '" + name + "'");
  if (H5Sget_simple_extent_ndims(space.get()) != rank) throw H5Failure{"dataset '" + name + "' has the wrong rank"};
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), "cannot read the shape of '" + name + "'");
  // Bounded by the file's size before anything is allocated (a damaged header).
  const hsize_t total = hdf5::checked_element_count(set.get(), dims.data(), rank, H5Tget_size(mem_type), name);
  void* buffer = resize(static_cast<std::size_t>(total), dims);
  if (total > 0) check(H5Dread(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer), "cannot read '" + name + "' (truncated or damaged)");
  return dims;
}

// Both directions visit the fields in the same order (the checksum's order).
class Writer {
 public:
  explicit Writer(hid_t file) : file_(file) {}
  void str(const std::string& name, std::string& s) {
    const hsize_t dims[1] = {s.size()};
    write_raw(file_, name, s.data(), 1, dims, H5T_STD_U8LE, H5T_NATIVE_UCHAR);
    sum_.add_name(name);
    sum_.add(s.data(), s.size());
  }
  void num(const std::string& name, double& v) {
    const hsize_t dims[1] = {1};
    write_raw(file_, name, &v, 1, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
    sum_.add_name(name);
    sum_.add(&v, sizeof v);
  }
  void integer(const std::string& name, int& v) {
    const hsize_t dims[1] = {1};
    write_raw(file_, name, &v, 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT);
    sum_.add_name(name);
    sum_.add(&v, sizeof v);
  }
  void ivec(const std::string& name, std::vector<int>& v) {
    const hsize_t dims[1] = {v.size()};
    write_raw(file_, name, v.data(), 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT);
    sum_.add_name(name);
    sum_.add(v.data(), v.size() * sizeof(int));
  }
  void mat(const std::string& name, Eigen::MatrixXd& m) {
    // Stored column-major as an (cols x rows) C-order array: the bytes of Eigen's storage.
    const hsize_t dims[2] = {static_cast<hsize_t>(m.cols()), static_cast<hsize_t>(m.rows())};
    write_raw(file_, name, m.data(), 2, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
    sum_.add_name(name);
    sum_.add(dims, sizeof dims);
    sum_.add(m.data(), static_cast<std::size_t>(m.size()) * sizeof(double));
  }
  Checksum& checksum() { return sum_; }

 private:
  hid_t file_;
  Checksum sum_;
};

class Reader {
 public:
  explicit Reader(hid_t file) : file_(file) {}
  void str(const std::string& name, std::string& s) {
    read_raw(file_, name, 1, H5T_NATIVE_UCHAR, [&](std::size_t n, const std::vector<hsize_t>&) -> void* {
      s.assign(n, '\0');
      return s.data();
    });
    sum_.add_name(name);
    sum_.add(s.data(), s.size());
  }
  void num(const std::string& name, double& v) {
    read_raw(file_, name, 1, H5T_NATIVE_DOUBLE, [&](std::size_t n, const std::vector<hsize_t>&) -> void* {
      if (n != 1) throw H5Failure{"dataset '" + name + "' is not a scalar"};
      return &v;
    });
    sum_.add_name(name);
    sum_.add(&v, sizeof v);
  }
  void integer(const std::string& name, int& v) {
    read_raw(file_, name, 1, H5T_NATIVE_INT, [&](std::size_t n, const std::vector<hsize_t>&) -> void* {
      if (n != 1) throw H5Failure{"dataset '" + name + "' is not a scalar"};
      return &v;
    });
    sum_.add_name(name);
    sum_.add(&v, sizeof v);
  }
  void ivec(const std::string& name, std::vector<int>& v) {
    read_raw(file_, name, 1, H5T_NATIVE_INT, [&](std::size_t n, const std::vector<hsize_t>&) -> void* {
      v.assign(n, 0);
      return v.data();
    });
    sum_.add_name(name);
    sum_.add(v.data(), v.size() * sizeof(int));
  }
  void mat(const std::string& name, Eigen::MatrixXd& m) {
    const auto dims = read_raw(file_, name, 2, H5T_NATIVE_DOUBLE, [&](std::size_t, const std::vector<hsize_t>& d) -> void* {
      m.resize(static_cast<Eigen::Index>(d[1]), static_cast<Eigen::Index>(d[0]));
      return m.data();
    });
    const hsize_t d[2] = {dims[0], dims[1]};
    sum_.add_name(name);
    sum_.add(d, sizeof d);
    sum_.add(m.data(), static_cast<std::size_t>(m.size()) * sizeof(double));
  }
  Checksum& checksum() { return sum_; }

 private:
  hid_t file_;
  Checksum sum_;
};

// Helpers over the two visitors for the composite fields.
template <typename V>
void vec(V& v, const std::string& name, Eigen::VectorXd& x) {
  Eigen::MatrixXd m = x;
  v.mat(name, m);
  require(m.cols() == 1 || m.size() == 0, "field '" + name + "' is not a vector");
  x = m.size() == 0 ? Eigen::VectorXd() : Eigen::VectorXd(m.col(0));
}
template <typename V>
void dvec(V& v, const std::string& name, std::vector<double>& x) {
  Eigen::MatrixXd m = Eigen::Map<Eigen::MatrixXd>(x.data(), static_cast<Eigen::Index>(x.size()), 1);
  v.mat(name, m);
  x.assign(m.data(), m.data() + m.size());
}
template <typename V>
void mats(V& v, const std::string& name, std::vector<Eigen::MatrixXd>& list) {
  int n = static_cast<int>(list.size());
  v.integer(name + "_count", n);
  require(n >= 0 && n < 1000000, "field '" + name + "_count' is invalid");
  list.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v.mat(name + "_" + std::to_string(i), list[static_cast<std::size_t>(i)]);
}
template <typename V>
void vecs(V& v, const std::string& name, std::vector<Eigen::VectorXd>& list) {
  int n = static_cast<int>(list.size());
  v.integer(name + "_count", n);
  require(n >= 0 && n < 1000000, "field '" + name + "_count' is invalid");
  list.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) vec(v, name + "_" + std::to_string(i), list[static_cast<std::size_t>(i)]);
}
// A theta list: `name` is J x 2 (coefficient, number of factors), `name`_factors is F x 3
// (parameter index, scale, power), the factors of the monomials one after the other.
template <typename V>
void thetas(V& v, const std::string& name, std::vector<cases::ThetaMonomial>& t) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(t.size()), 2);
  std::size_t total = 0;
  for (const cases::ThetaMonomial& x : t) total += x.factors.size();
  Eigen::MatrixXd f(static_cast<Eigen::Index>(total), 3);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    m.row(static_cast<Eigen::Index>(i)) << t[i].coefficient, static_cast<double>(t[i].factors.size());
    for (const cases::ThetaFactor& x : t[i].factors) {
      f.row(row++) << static_cast<double>(x.parameter), x.scale, static_cast<double>(x.power);
    }
  }
  v.mat(name, m);
  v.mat(name + "_factors", f);
  require(m.cols() == 2 || m.size() == 0, "field '" + name + "' is not a theta table");
  require(f.cols() == 3 || f.size() == 0, "field '" + name + "_factors' is not a theta factor table");
  t.assign(static_cast<std::size_t>(m.rows()), {});
  Eigen::Index next = 0;
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    const double count = m(i, 1);
    require(count >= 0.0 && count <= 64.0 && count == std::floor(count) && next + static_cast<Eigen::Index>(count) <= f.rows(),
            "field '" + name + "' row " + std::to_string(i) + " has an invalid factor count");
    cases::ThetaMonomial& x = t[static_cast<std::size_t>(i)];
    x.coefficient = m(i, 0);
    for (int k = 0; k < static_cast<int>(count); ++k, ++next) {
      const double par = f(next, 0), power = f(next, 2);
      require(par >= 0.0 && par < 1000.0 && par == std::floor(par) && std::abs(power) <= 64.0 && power == std::floor(power),
              "field '" + name + "_factors' row " + std::to_string(next) + " is invalid");
      x.factors.push_back({static_cast<int>(par), f(next, 1), static_cast<int>(power)});
    }
  }
  require(next == f.rows() || f.size() == 0, "field '" + name + "_factors' has rows no monomial uses");
}
template <typename V>
void points(V& v, const std::string& name, std::vector<Eigen::Vector2d>& p) {
  Eigen::MatrixXd m(2, static_cast<Eigen::Index>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = p[i];
  v.mat(name, m);
  require(m.rows() == 2 || m.size() == 0, "field '" + name + "' is not a point list");
  p.resize(static_cast<std::size_t>(m.cols()));
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = m.col(static_cast<Eigen::Index>(i));
}

// A bool stored as an integer 0 / 1.
template <typename V>
void flag(V& v, const std::string& name, bool& b) {
  int i = b ? 1 : 0;
  v.integer(name, i);
  b = i != 0;
}

// Every field of the model, in the checksum's order (the format version is checked first,
// apart).
template <typename V>
void visit(V& v, rb::ReducedModel& m) {
  v.str("case_name", m.case_name);
  v.str("case_kind", m.case_kind);
  v.str("case_spec", m.case_spec);
  v.integer("level", m.level);
  int count = static_cast<int>(m.parameters.size());
  v.integer("parameter_count", count);
  require(count >= 0 && count <= 1000, "field 'parameter_count' is " + std::to_string(count));  // 0: check_model says so
  m.parameters.resize(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    cases::ParameterSpec& p = m.parameters[static_cast<std::size_t>(k)];
    const std::string pre = "parameter_" + std::to_string(k) + "_";
    v.str(pre + "name", p.name);
    v.str(pre + "units", p.units);
    std::string kind = cases::to_string(p.kind);
    v.str(pre + "kind", kind);
    p.kind = cases::parameter_kind_from_string(kind);
    v.num(pre + "min", p.min);
    v.num(pre + "max", p.max);
    v.num(pre + "reference", p.reference);
    v.integer(pre + "body", p.body);
    v.num(pre + "center_x", p.center.x());
    v.num(pre + "center_y", p.center.y());
  }
  thetas(v, "theta_a", m.thetas.a);
  thetas(v, "theta_f", m.thetas.f);
  thetas(v, "theta_lift", m.thetas.lift);
  v.str("inner_product", m.inner_product);
  v.str("dual_method", m.dual_method);
  v.num("eps_pod", m.eps_pod);
  flag(v, "eps_pod_relative", m.eps_pod_relative);
  v.num("eps_du", m.eps_du);
  flag(v, "eps_du_relative", m.eps_du_relative);
  v.num("eps_eim_k", m.eps_eim_k);
  flag(v, "eps_eim_k_relative", m.eps_eim_k_relative);
  v.num("eps_eim_g", m.eps_eim_g);
  flag(v, "eps_eim_g_relative", m.eps_eim_g_relative);
  int compression = m.compression ? 1 : 0;
  v.integer("compression", compression);
  m.compression = compression != 0;
  v.num("kacanov_alpha", m.kacanov_alpha);
  v.num("kacanov_tolerance", m.kacanov_tolerance);
  v.integer("kacanov_max_iterations", m.kacanov_max_iterations);
  v.integer("N_max", m.N_max);
  v.integer("N_supremizers", m.N_supremizers);
  v.integer("R_max", m.R_max);
  v.integer("Mk_max", m.Mk_max);
  v.integer("Mg_max", m.Mg_max);
  vec(v, "singular_values", m.singular_values);
  v.mat("training_mu", m.training_mu);
  v.mat("training_u_hat", m.training_u_hat);
  v.mat("training_lambda_hat", m.training_lambda_hat);
  mats(v, "A_hat", m.A_hat);
  vecs(v, "f_hat", m.f_hat);
  vecs(v, "A_lift_hat", m.A_lift_hat);
  dvec(v, "lift_AA", m.lift_AA);
  dvec(v, "lift_f", m.lift_f);
  v.ivec("kept_rows", m.kept_rows);
  v.mat("Xi", m.Xi);
  v.ivec("kappa_row", m.kappa_row);
  v.ivec("kappa_dof", m.kappa_dof);
  v.mat("B_kappa", m.B_kappa);
  mats(v, "C_kappa", m.C_kappa);
  dvec(v, "eim_kappa_errors", m.eim_kappa_errors);
  v.ivec("gamma_row", m.gamma_row);
  v.mat("B_gamma", m.B_gamma);
  v.mat("XiQ_gamma", m.XiQ_gamma);
  dvec(v, "eim_gamma_errors", m.eim_gamma_errors);
  rb::ContactSurface& s = m.surface;
  points(v, "surface_reference_nodes", s.reference_nodes);
  v.ivec("surface_body", s.body);
  v.ivec("surface_slave", s.slave);
  v.ivec("surface_master", s.master);
  int disc = static_cast<int>(s.discretization);
  v.integer("surface_discretization", disc);
  s.discretization = static_cast<contact::Discretization>(disc);
  v.integer("surface_num_constraints", s.num_constraints);
  v.mat("Theta_c", m.Theta_c);
  v.mat("lift_c", m.lift_c);
  // Format 3: the error estimate (rb/error_estimate_data.hpp).
  rb::EstimateData& e = m.estimate;
  vec(v, "estimate_theta_a_reference", e.theta_a_reference);
  v.mat("estimate_residual_T", e.residual_T);
  mats(v, "estimate_QTheta_kappa", e.QTheta_kappa);
  v.mat("estimate_Q_gamma", e.Q_gamma);
  vec(v, "estimate_eim_residual", e.eim_residual);
  v.mat("estimate_eim_slack", e.eim_slack);
}

void write_u64(hid_t file, const std::string& name, std::uint64_t value) {
  const hsize_t dims[1] = {1};
  write_raw(file, name, &value, 1, dims, H5T_STD_U64LE, H5T_NATIVE_UINT64);
}
std::uint64_t read_u64(hid_t file, const std::string& name) {
  std::uint64_t value = 0;
  read_raw(file, name, 1, H5T_NATIVE_UINT64, [&](std::size_t n, const std::vector<hsize_t>&) -> void* {
    if (n != 1) throw H5Failure{"dataset '" + name + "' is not a scalar"};
    return &value;
  });
  return value;
}

// The mark `name` (= 1) is written last: a missing one or any other value (0, a damaged one) is
// not a finished write.
bool is_complete(hid_t file, const std::string& name) {
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) return false;
  int complete = 0;
  read_raw(file, name, 1, H5T_NATIVE_INT, [&](std::size_t n, const std::vector<hsize_t>&) -> void* {
    if (n != 1) throw H5Failure{"dataset '" + name + "' is not a scalar"};
    return &complete;
  });
  return complete == 1;
}

}  // namespace

namespace {

constexpr const char* kReconstructionGroup = "reconstruction";

// The reconstruction's fields, in its checksum's order, names relative to the file root.
template <typename V>
void visit_reconstruction(V& v, rb::ReducedReconstruction& r) {
  const std::string g = std::string(kReconstructionGroup) + "/";
  v.integer(g + "num_dofs", r.num_dofs);
  v.ivec(g + "free_dofs", r.free_dofs);
  v.mat(g + "Theta", r.Theta);
  vecs(v, g + "lift", r.lift);
  thetas(v, g + "theta_a", r.thetas.a);
  thetas(v, g + "theta_f", r.thetas.f);
  thetas(v, g + "theta_lift", r.thetas.lift);
  v.ivec(g + "kept_rows", r.kept_rows);
  v.integer(g + "num_constraints", r.num_constraints);
  v.mat(g + "Xi", r.Xi);
}

void write_reconstruction_group(hid_t file, const rb::ReducedReconstruction& reconstruction) {
  Id group(H5Gcreate2(file, kReconstructionGroup, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
           "cannot create the group 'reconstruction'");
  Writer w(file);
  const std::string g = std::string(kReconstructionGroup) + "/";
  int version = kReconstructionFormatVersion;
  w.integer(g + "format_version", version);
  rb::ReducedReconstruction copy = reconstruction;  // the visitor takes references
  visit_reconstruction(w, copy);
  write_u64(file, g + "checksum", w.checksum().value());
  int complete = 1;
  const hsize_t dims[1] = {1};
  write_raw(file, g + "complete", &complete, 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT);
}

void write_model_file(const rb::ReducedModel& model, const rb::ReducedReconstruction* reconstruction,
                      const std::string& path) {
  QuietHdf5 quiet;
  check_output_target(path);
  remove_stale_temporaries(path);
  const std::string tmp = temporary_path(path).string();
  try {
    {
      Id file(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "cannot create the file");
      Writer w(file.get());
      std::string format = kReducedModelFormatName;
      w.str("format", format);
      int version = model.format_version;
      w.integer("format_version", version);
      rb::ReducedModel copy = model;  // the visitor takes references
      visit(w, copy);
      if (reconstruction != nullptr) write_reconstruction_group(file.get(), *reconstruction);
      write_u64(file.get(), "checksum", w.checksum().value());
      int complete = 1;
      const hsize_t dims[1] = {1};
      write_raw(file.get(), "complete", &complete, 1, dims, H5T_STD_I32LE, H5T_NATIVE_INT);
      file.close("cannot close (flush) the file");
    }
    commit_temporary(tmp, path);  // removes tmp itself when it fails
  } catch (const H5Failure& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error("reduced model file '" + path + "': " + e.what);
  } catch (const Error& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw Error("reduced model file '" + path + "': " + e.what());
  }
}

// The cheap checks before opening a file (as read_reduced_model_file).
void check_model_path(const std::string& path, const std::string& where) {
  require(std::filesystem::exists(path), where + "no such file");
  check_input_file(path, "reduced model file", InputKind::Hdf5);  // a regular file below the size limit
  require(H5Fis_hdf5(path.c_str()) > 0, where + "not an HDF5 file (or truncated before its superblock)");
}
Id open_model_file(const std::string& path) {
  return Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
            "cannot open the file (truncated or damaged)");
}

}  // namespace

void write_reduced_model_file(const rb::ReducedModel& model, const std::string& path) {
  write_model_file(model, nullptr, path);
}

void write_reduced_model_file(const rb::ReducedModel& model, const rb::ReducedReconstruction& reconstruction,
                              const std::string& path) {
  write_model_file(model, &reconstruction, path);
}

rb::ReducedModel read_reduced_model_file(const std::string& path) {
  QuietHdf5 quiet;
  const std::string where = "reduced model file '" + path + "': ";
  require(std::filesystem::exists(path), where + "no such file");
  check_input_file(path, "reduced model file", InputKind::Hdf5);  // a regular file below the size limit
  require(H5Fis_hdf5(path.c_str()) > 0, where + "not an HDF5 file (or truncated before its superblock)");
  try {
    Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
            "cannot open the file (truncated or damaged)");
    if (H5Lexists(file.get(), "format", H5P_DEFAULT) <= 0 && is_snapshot_file(path)) {
      throw H5Failure{"a contactrb snapshot file, not a reduced model (build a model from it with `contactrb offline "
                      "--snapshots`)"};
    }
    Reader r(file.get());
    std::string format;
    r.str("format", format);
    if (format != kReducedModelFormatName) throw H5Failure{"not a contactrb reduced model (format '" + format + "')"};
    rb::ReducedModel m;
    r.integer("format_version", m.format_version);
    if (m.format_version != rb::kReducedModelFormatVersion) {
      throw H5Failure{"format version " + std::to_string(m.format_version) + ", this build reads version " +
                      std::to_string(rb::kReducedModelFormatVersion) + " (rebuild the model with `contactrb offline`)"};
    }
    if (!is_complete(file.get(), "complete")) throw H5Failure{"incomplete file (the write was interrupted)"};
    visit(r, m);
    const std::uint64_t stored = read_u64(file.get(), "checksum");
    if (stored != r.checksum().value()) throw H5Failure{"checksum mismatch: the file was modified or damaged"};
    return m;
  } catch (const H5Failure& e) {
    throw Error(where + e.what);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
}

bool has_reconstruction(const std::string& path) {
  QuietHdf5 quiet;
  const std::string where = "reduced model file '" + path + "': ";
  check_model_path(path, where);
  try {
    Id file = open_model_file(path);
    return H5Lexists(file.get(), kReconstructionGroup, H5P_DEFAULT) > 0;
  } catch (const H5Failure& e) {
    throw Error(where + e.what);
  }
}

rb::ReducedReconstruction read_reconstruction(const std::string& path) {
  QuietHdf5 quiet;
  const std::string where = "reduced model file '" + path + "': ";
  check_model_path(path, where);
  try {
    Id file = open_model_file(path);
    if (H5Lexists(file.get(), kReconstructionGroup, H5P_DEFAULT) <= 0) {
      throw H5Failure{"no reconstruction data (a model written without them; rerun `contactrb offline` to get "
                      "them)"};
    }
    const std::string g = std::string(kReconstructionGroup) + "/";
    if (!is_complete(file.get(), g + "complete")) {
      throw H5Failure{"incomplete reconstruction data (the write was interrupted)"};
    }
    Reader r(file.get());
    int version = 0;
    r.integer(g + "format_version", version);
    if (version != kReconstructionFormatVersion) {
      throw H5Failure{"reconstruction format version " + std::to_string(version) + ", this build reads version " +
                      std::to_string(kReconstructionFormatVersion)};
    }
    rb::ReducedReconstruction rec;
    visit_reconstruction(r, rec);
    const std::uint64_t stored = read_u64(file.get(), g + "checksum");
    if (stored != r.checksum().value()) {
      throw H5Failure{"reconstruction checksum mismatch: the file was modified or damaged"};
    }
    // Sizes only (the model-dependent checks are rb::check_reconstruction's).
    require(rec.num_dofs > 0 && rec.Theta.rows() == static_cast<Eigen::Index>(rec.free_dofs.size()) &&
                rec.Xi.rows() == static_cast<Eigen::Index>(rec.kept_rows.size()) &&
                rec.lift.size() == rec.thetas.lift.size(),
            "reconstruction data with inconsistent array sizes");
    for (const Eigen::VectorXd& l : rec.lift) require(l.size() == rec.num_dofs, "reconstruction lift of the wrong size");
    return rec;
  } catch (const H5Failure& e) {
    throw Error(where + e.what);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
}

}  // namespace contactrb::io
