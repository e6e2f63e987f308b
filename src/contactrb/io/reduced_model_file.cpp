#include "contactrb/io/reduced_model_file.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/common/file_seal.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/output_file.hpp"
#include "contactrb/common/version.hpp"
#include "contactrb/io/hdf5_visitor.hpp"
#include "contactrb/io/mesh_group.hpp"
#include "contactrb/io/snapshot_file.hpp"

namespace contactrb::io {

namespace {

using hdf5::check;
using hdf5::Description;
using hdf5::Handle;
using hdf5::Loc;
using H5Failure = hdf5::Failure;
using QuietHdf5 = hdf5::Quiet;

// A theta list (cases::ThetaMonomial, theta(mu) = coefficient prod (mu_k / s_k)^p_k) as two
// tables in group `name`: monomials J x 2 (coefficient, number of factors), factors F x 3
// (parameter index k, scale s_k, power p_k), the factors of the monomials one after the other.
template <typename V>
void thetas(V& v, const Loc& parent, const std::string& name, const std::string& meaning,
            std::vector<cases::ThetaMonomial>& t) {
  Handle g = v.group(parent, name, meaning);
  const Loc loc{g.get(), parent.field(name)};
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
  v.mat(loc, "monomials", m,
        {"J x 2: row j is theta_j = coefficient * prod of its factors; columns: coefficient, number of factors "
         "(its rows of `factors`, in order)",
         "1"});
  v.mat(loc, "factors", f,
        {"F x 3: one factor (mu_k / s)^p per row, the factors of monomial 0, then 1, ...; columns: parameter "
         "index k (0-based, /parameters/NNNNNN), scale s, power p",
         "column 0 index, column 1 the parameter's units, column 2 1"});
  if constexpr (V::kWriting) return;
  require(m.cols() == 2 || m.size() == 0, "field '" + loc.field("monomials") + "' is not a theta table");
  require(f.cols() == 3 || f.size() == 0, "field '" + loc.field("factors") + "' is not a theta factor table");
  t.assign(static_cast<std::size_t>(m.rows()), {});
  Eigen::Index next = 0;
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    const double count = m(i, 1);
    require(count >= 0.0 && count <= 64.0 && count == std::floor(count) &&
                next + static_cast<Eigen::Index>(count) <= f.rows(),
            "field '" + loc.field("monomials") + "' row " + std::to_string(i) + " has an invalid factor count");
    cases::ThetaMonomial& x = t[static_cast<std::size_t>(i)];
    x.coefficient = m(i, 0);
    for (int k = 0; k < static_cast<int>(count); ++k, ++next) {
      const double par = f(next, 0), power = f(next, 2);
      require(par >= 0.0 && par < 1000.0 && par == std::floor(par) && std::abs(power) <= 64.0 &&
                  power == std::floor(power),
              "field '" + loc.field("factors") + "' row " + std::to_string(next) + " is invalid");
      x.factors.push_back({static_cast<int>(par), f(next, 1), static_cast<int>(power)});
    }
  }
  require(next == f.rows() || f.size() == 0, "field '" + loc.field("factors") + "' has rows no monomial uses");
}

template <typename V>
void theta_group(V& v, const Loc& parent, cases::AffineThetas& t) {
  Handle g = v.group(parent, "theta", "the affine coefficient functions theta(mu) (docs/offline-online.md, (49))");
  const Loc loc{g.get(), parent.field("theta")};
  thetas(v, loc, "a", "theta^a_j: A(mu) = sum_j theta^a_j(mu) A_j (J^a terms)", t.a);
  thetas(v, loc, "f", "theta^f_j: f(mu) = sum_j theta^f_j(mu) f_j (J^f terms)", t.f);
  thetas(v, loc, "lift",
         "theta^lift_k: the Dirichlet lift u_D(mu) = sum_k theta^lift_k(mu) lift_k; row k is the coefficient of "
         "/reconstruction/lift row k and of /primal/lift_c column k (J^D terms)",
         t.lift);
}

// Every field of the model (layout: docs/file-formats.md).
// The registered cone (model/registration.hpp); every array empty for the other cones.
template <typename V>
void visit_registration(V& v, const Loc& root, contactrb::model::Registration& r) {
  Handle g = v.group(root, "registration",
                     "the registered dual cone: lambda = Xi(mu) lambda_hat on the kept rows, Xi(mu)_rk = G_k((s_r - "
                     "s_left(mu)) / (s_right(mu) - s_left(mu))); empty arrays for the other cones");
  const Loc re{g.get(), "/registration"};
  v.vec(re, "row_coordinate", r.row_coordinate,
        {"R_kept: s_r, the arc length along the slave chain of kept row r's centre node (reference)", "length"});
  v.vec(re, "grid", r.grid, {"n_g: the registered coordinates xi of the generators, uniform, increasing", "1"});
  v.mat(re, "generators", r.generators, {"n_g x R: column k is generator G_k on the grid, >= 0", "pressure"});
  v.vec(re, "point_offset", r.point_offset, {"p: x = (mu - point_offset) .* point_scale", "row k: parameter k"});
  v.vec(re, "point_scale", r.point_scale, {"p: x = (mu - point_offset) .* point_scale", "1 / parameter k"});
  v.mat(re, "points", r.points, {"p x P: the training points x, scaled to [0, 1]", "1"});
  v.mat(re, "support", r.support, {"2 x P: [s_left, s_right] of each training pressure", "length"});
}

template <typename V>
void visit(V& v, const Loc& root, contactrb::model::ReducedModel& m) {
  {
    Handle g = v.group(root, "meta", "provenance, the settings the model was built with, the maximal sizes");
    const Loc meta{g.get(), "/meta"};
    v.str(meta, "case_name", m.case_name);
    v.str(meta, "case_kind", m.case_kind);
    v.str(meta, "case_spec", m.case_spec);
    v.integer(meta, "level", m.level);
    v.str(meta, "inner_product", m.inner_product);
    v.str(meta, "dual_method", m.dual_method);
    v.num(meta, "eps_pod", m.eps_pod);
    v.flag(meta, "eps_pod_relative", m.eps_pod_relative);
    v.num(meta, "eps_du", m.eps_du);
    v.flag(meta, "eps_du_relative", m.eps_du_relative);
    v.num(meta, "eps_eim_k", m.eps_eim_k);
    v.flag(meta, "eps_eim_k_relative", m.eps_eim_k_relative);
    v.num(meta, "eps_eim_g", m.eps_eim_g);
    v.flag(meta, "eps_eim_g_relative", m.eps_eim_g_relative);
    v.flag(meta, "compression", m.compression);
    v.num(meta, "kacanov_alpha", m.kacanov_alpha);
    v.num(meta, "kacanov_tolerance", m.kacanov_tolerance);
    v.integer(meta, "kacanov_max_iterations", m.kacanov_max_iterations);
    v.integer(meta, "N_max", m.N_max);
    v.integer(meta, "N_supremizers", m.N_supremizers);
    v.integer(meta, "R_max", m.R_max);
    v.integer(meta, "Mk_max", m.Mk_max);
    v.integer(meta, "Mg_max", m.Mg_max);
  }
  {
    Handle g = v.group(root, "parameters",
                       "the parameters mu = (mu_0, ..., mu_{p-1}): one subgroup each (000000, ...), and the training "
                       "points");
    const Loc par{g.get(), "/parameters"};
    int count = static_cast<int>(m.parameters.size());
    v.integer(par, "count", count);
    require(count >= 0 && count <= 1000, "field '/parameters/count' is " + std::to_string(count));  // 0: check_model says so
    m.parameters.resize(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      cases::ParameterSpec& p = m.parameters[static_cast<std::size_t>(k)];
      const std::string name = hdf5::list_entry_name(static_cast<std::size_t>(k));
      Handle pg = v.group(par, name, "parameter mu_k: name, units, kind, domain [min, max], reference value, geometric map data");
      const Loc one{pg.get(), par.field(name)};
      v.str(one, "name", p.name);
      v.str(one, "units", p.units);
      std::string kind = cases::to_string(p.kind);
      v.str(one, "kind", kind);
      p.kind = cases::parameter_kind_from_string(kind);
      v.num(one, "min", p.min);
      v.num(one, "max", p.max);
      v.num(one, "reference", p.reference);
      v.integer(one, "body", p.body);
      v.num(one, "center_x", p.center.x());
      v.num(one, "center_y", p.center.y());
    }
    v.mat(par, "training_mu", m.training_mu,
          {"p x P: column i is training point mu^(i) (the snapshot set's order)", "row k: the units of parameter k"});
  }
  theta_group(v, root, m.thetas);
  {
    Handle g = v.group(root, "primal", "the reduced primal problem (49): u = u_D(mu) + Theta u_hat");
    const Loc pr{g.get(), "/primal"};
    v.vec(pr, "singular_values", m.singular_values, {"P: the POD singular values, decreasing", "displacement (M-norm)"});
    v.stack(pr, "A_hat", m.A_hat, {"J^a x N_max x N_max: A_hat[j] = Theta' A_j,00 Theta", "energy (stiffness x length^2)"});
    v.rows(pr, "f_hat", m.f_hat, {"J^f x N_max: row j is Theta' f_j,0", "force x length"});
    v.rows(pr, "A_lift_hat", m.A_lift_hat,
           {"(J^a J^D) x N_max: row j J^D + k is Theta' (A_j lift_k)_0", "force x length"});
    v.dvec(pr, "lift_AA", m.lift_AA, {"J^a J^D J^D: entry (j J^D + k) J^D + l is lift_k' A_j lift_l", "energy"});
    v.dvec(pr, "lift_f", m.lift_f, {"J^f J^D: entry j J^D + k is f_j' lift_k", "energy"});
    v.mat(pr, "Theta_c", m.Theta_c,
          {"n_c x N_max: the basis on the contact-surface DOFs (/surface), 0 where constrained", "length"});
    v.mat(pr, "lift_c", m.lift_c, {"n_c x J^D: column k is lift_k on the contact-surface DOFs", "length"});
    v.mat(pr, "training_u_hat", m.training_u_hat,
          {"N_max x P: column i is the online initial guess u_hat at training point i", "1 (basis coordinates)"});
    v.mat(pr, "training_jacobian", m.training_jacobian,
          {"N_max x (N_max P), or empty: block i is the Jacobian of the reduced Kacanov map at training point i "
           "(the online preconditioner)",
           "1"});
    v.mat(pr, "training_u_sensitivity", m.training_u_sensitivity,
          {"N_max x (p P), or empty: block i is the derivative of u_hat with respect to mu at training point i "
           "(the online start u_hat_i + S_i (mu - mu_i))",
           "1 / (units of mu)"});
  }
  {
    Handle g = v.group(root, "dual", "the reduced dual cone (Remark 7): lambda = Xi lambda_hat on the kept rows");
    const Loc du{g.get(), "/dual"};
    v.ints(du, "kept_rows", m.kept_rows,
           {"R_kept: the constraint rows (0 .. R_hf - 1) kept by the compression, increasing", "index (0-based)"});
    v.mat(du, "Xi", m.Xi, {"R_kept x R_max: column r is dual basis vector r on the kept rows, >= 0", "pressure"});
    v.mat(du, "training_lambda_hat", m.training_lambda_hat,
          {"R_max x P: column i is the online initial guess lambda_hat at training point i", "1 (basis coordinates)"});
  }
  {
    Handle eim = v.group(root, "eim", "the empirical interpolation of the contact map kappa and the gap gamma");
    const Loc e{eim.get(), "/eim"};
    {
      Handle g = v.group(e, "kappa", "EIM of kappa (50)-(52), (55)");
      const Loc k{g.get(), "/eim/kappa"};
      v.ints(k, "row", m.kappa_row, {"Mk_max: magic row i, an index into /dual/kept_rows", "index (0-based)"});
      v.ints(k, "dof", m.kappa_dof, {"Mk_max: magic contact-surface DOF i (/surface)", "index (0-based)"});
      v.mat(k, "B", m.B_kappa, {"Mk_max x Mk_max: the EIM matrix, lower triangular, unit diagonal", "1"});
      v.stack(k, "C", m.C_kappa, {"Mk_max x R_max x N_max: C[i] = Xi' Q_i Theta_c (55)", "pressure x length"});
      v.dvec(k, "errors", m.eim_kappa_errors, {"the greedy's interpolation error at each M", "1"});
    }
    {
      Handle g = v.group(e, "gamma", "EIM of gamma = g - K u_D(mu) (54)");
      const Loc k{g.get(), "/eim/gamma"};
      v.ints(k, "row", m.gamma_row, {"Mg_max: magic row i, an index into /dual/kept_rows", "index (0-based)"});
      v.mat(k, "B", m.B_gamma, {"Mg_max x Mg_max: the EIM matrix", "1"});
      v.mat(k, "XiQ", m.XiQ_gamma, {"R_max x Mg_max: Xi' Q^gamma (D^gamma = XiQ B^-1)", "pressure x length"});
      v.dvec(k, "errors", m.eim_gamma_errors, {"the greedy's interpolation error at each M", "length"});
    }
  }
  {
    contactrb::model::ContactSurface& s = m.surface;
    Handle g = v.group(root, "surface",
                       "the contact surface in the reference configuration: the contact nodes (slave and master chain "
                       "nodes in ascending global index); contact-surface DOF 2 i + c is component c of node i");
    const Loc su{g.get(), "/surface"};
    Eigen::MatrixXd nodes(static_cast<Eigen::Index>(s.reference_nodes.size()), 2);
    for (std::size_t i = 0; i < s.reference_nodes.size(); ++i) {
      nodes.row(static_cast<Eigen::Index>(i)) = s.reference_nodes[i].transpose();
    }
    v.mat(su, "reference_nodes", nodes, {"n_c / 2 x 2: row i is (x, y) of contact node i", "length"});
    if constexpr (!V::kWriting) {
      require(nodes.cols() == 2 || nodes.size() == 0, "field '/surface/reference_nodes' is not a point list");
      s.reference_nodes.resize(static_cast<std::size_t>(nodes.rows()));
      for (std::size_t i = 0; i < s.reference_nodes.size(); ++i) {
        s.reference_nodes[i] = nodes.row(static_cast<Eigen::Index>(i)).transpose();
      }
    }
    v.ints(su, "body", s.body, {"n_c / 2: body of contact node i, 0 slave, 1 master", "index (0-based)"});
    v.ints(su, "slave", s.slave, {"the slave chain, contact node indices in order", "index (0-based)"});
    v.ints(su, "master", s.master,
           {"the master chain, contact node indices in order (closed: the first repeated at the end)", "index (0-based)"});
    std::string disc = contact::to_string(s.discretization);
    v.str(su, "discretization", disc);
    s.discretization = contact::discretization_from_string(disc);
    v.integer(su, "num_constraints", s.num_constraints);
  }
  {
    contactrb::model::EstimateData& e = m.estimate;
    Handle g = v.group(root, "estimate", "the a posteriori error estimate's arrays (rb/error_estimate_data.hpp)");
    const Loc es{g.get(), "/estimate"};
    v.vec(es, "theta_a_reference", e.theta_a_reference, {"J^a: theta^a_j at the reference parameter value", "1"});
    v.mat(es, "residual_T", e.residual_T,
          {"rho x d_max: ||r||_X' = |residual_T y| for the coefficient vector y (columns: f_j | (A_j lift_k)_0 | "
           "A_j,00 Theta_n | E_c' Q_i' Xi_r)",
           "force x length / energy norm"});
    v.stack(es, "QTheta_kappa", e.QTheta_kappa, {"Mk_max x R_kept x N_max: EIM reconstruction of K Theta_c", "1"});
    v.mat(es, "Q_gamma", e.Q_gamma, {"R_kept x Mg_max: EIM basis of gamma on the kept rows", "length"});
    v.vec(es, "eim_residual", e.eim_residual, {"Mk_max + 1: the EIM residual bound at each M", "1"});
    v.mat(es, "eim_slack", e.eim_slack, {"(Mk_max + 1) x (Mg_max + 1): the EIM slack at each (M, M')", "length"});
    v.mat(es, "residual_exact", e.residual_exact,
          {"rho' x d_exact: ||r||_X' = |residual_exact y| with the exact contact rows (columns: f_j | "
           "(A_j lift_k)_0 | A_j,00 Theta_n | E_c' e_a for a in exact_dofs)",
           "force x length / energy norm"});
    v.ints(es, "exact_dofs", e.exact_dofs,
           {"the contact-surface DOFs (indices into the n_c contact DOFs) of the exact load columns", "index (0-based)"});
    v.num(es, "geometric_ratio", e.geometric_ratio);
  }
  visit_registration(v, root, m.registration);
}

constexpr const char* kReconstructionGroup = "reconstruction";

// The reconstruction and the mesh (one checksum: root attribute of /reconstruction).
template <typename V>
void visit_reconstruction(V& v, const Loc& root, contactrb::model::ReducedReconstruction& r, bool with_mesh) {
  {
    Handle g = v.group(root, kReconstructionGroup,
                       "HF-size data mapping a reduced solution back to the mesh: u = u_D(mu) + P Theta u_hat, "
                       "u_D(mu) = sum_k theta^lift_k(mu) lift_k, P the scatter to free_dofs");
    const Loc rec{g.get(), "/reconstruction"};
    v.integer(rec, "num_dofs", r.num_dofs);
    v.integer(rec, "num_constraints", r.num_constraints);
    v.ints(rec, "free_dofs", r.free_dofs,
           {"n_free: the global DOF (2 node + component) of each row of Theta", "index (0-based)"});
    v.mat(rec, "Theta", r.Theta,
          {"n_free x N_max: column j is basis vector j on the free DOFs", "length per unit of u_hat"});
    v.rows(rec, "lift", r.lift, {"J^D x num_dofs: row k is lift vector lift_k on every DOF", "length"});
    v.ints(rec, "kept_rows", r.kept_rows,
           {"R_kept: the constraint rows kept (as /dual/kept_rows)", "index (0-based)"});
    v.mat(rec, "Xi", r.Xi,
          {"R_kept x R_max: lambda = Xi lambda_hat on the kept rows, 0 on the others", "pressure"});
    theta_group(v, rec, r.thetas);
  }
  if (with_mesh) hdf5::visit_mesh(v, root, r.mesh);
}

void write_reconstruction(hid_t file, const contactrb::model::ReducedReconstruction& reconstruction) {
  FieldChecksum sum;
  hdf5::FieldWriter w(sum);
  const Loc root{file, ""};
  contactrb::model::ReducedReconstruction copy = reconstruction;  // the visitor takes references
  visit_reconstruction(w, root, copy, !copy.mesh.nodes.empty());
  Handle g = hdf5::open_group(file, kReconstructionGroup);
  hdf5::write_number_attribute(g.get(), "format_version", kReconstructionFormatVersion, H5T_STD_I32LE, H5T_NATIVE_INT);
  hdf5::write_number_attribute(g.get(), "has_mesh", copy.mesh.nodes.empty() ? 0 : 1, H5T_STD_I32LE, H5T_NATIVE_INT);
  hdf5::write_number_attribute(g.get(), "checksum", sum.value(), H5T_STD_U64LE, H5T_NATIVE_UINT64);
  hdf5::write_number_attribute(g.get(), "complete", 1, H5T_STD_I32LE, H5T_NATIVE_INT);
}

void write_model_file(const contactrb::model::ReducedModel& model,
                      const contactrb::model::ReducedReconstruction* reconstruction, const std::string& path) {
  QuietHdf5 quiet;
  check_output_target(path);
  remove_stale_temporaries(path);
  const std::string tmp = temporary_path(path).string();
  try {
    {
      const Handle fcpl = hdf5::sealed_file_properties();
      Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_EXCL, fcpl.get(), H5P_DEFAULT), H5Fclose, "cannot create the file");
      const hid_t f = file.get();
      hdf5::write_string_attribute(f, "format", kReducedModelFormatName);
      hdf5::write_number_attribute(f, "format_version", model.format_version, H5T_STD_I32LE, H5T_NATIVE_INT);
      hdf5::write_string_attribute(f, "contactrb_version", kVersion);
      hdf5::write_string_attribute(f, "description",
                                   "contactrb reduced model (paper Algorithm 1); layout: docs/file-formats.md");
      FieldChecksum sum;
      hdf5::FieldWriter w(sum);
      contactrb::model::ReducedModel copy = model;  // the visitor takes references
      visit(w, Loc{f, ""}, copy);
      if (reconstruction != nullptr) write_reconstruction(f, *reconstruction);
      hdf5::write_number_attribute(f, "checksum", sum.value(), H5T_STD_U64LE, H5T_NATIVE_UINT64);
      hdf5::write_number_attribute(f, "complete", 1, H5T_STD_I32LE, H5T_NATIVE_INT);  // last
      file.close("cannot close (flush) the file");
    }
    seal_file(tmp);  // the hash of every byte, checked before HDF5 parses the file
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

// The cheap checks before opening a file; true when the file's seal is valid (a file without
// one: an older version or another program's). A sealed file whose bytes changed is refused
// here, before HDF5 parses it (common/file_seal.hpp).
bool check_model_path(const std::string& path, const std::string& where) {
  require(std::filesystem::exists(path), where + "no such file");
  check_input_file(path, "reduced model file", InputKind::Hdf5);  // a regular file below the size limit
  require(H5Fis_hdf5(path.c_str()) > 0, where + "not an HDF5 file (or truncated before its superblock)");
  const SealState seal = check_seal(path);
  require(seal != SealState::Mismatch,
          where + "checksum mismatch: the file was modified or damaged after it was written (its bytes' hash)");
  return seal == SealState::Valid;
}
Handle open_model_file(const std::string& path) {
  return Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                "cannot open the file (truncated or damaged)");
}

// The version of a file of the format before 5 (every field a dataset of the root, the
// version a one-element int dataset), or -1.
int old_layout_version(hid_t file) {
  try {
    hsize_t dims[1] = {0};
    Handle set = hdf5::open_dataset(file, "format_version", 1, H5T_INTEGER, dims, sizeof(int));
    if (dims[0] != 1) return -1;
    int version = -1;
    check(H5Dread(set.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, &version), "format_version");
    return version;
  } catch (const H5Failure&) {
    return -1;
  }
}

std::string rebuild_message(int version) {
  const int current = contactrb::model::kReducedModelFormatVersion;
  const std::string state = version > current ? " is newer than this build reads" : " is no longer read";
  return "model format " + std::to_string(version) + state + " (this build reads format " + std::to_string(current) +
         "): rebuild it with `contactrb offline`";
}

constexpr const char* kSnapshotNotModel =
    "a contactrb snapshot file, not a reduced model (build a model from it with `contactrb offline --snapshots`)";

// A file whose `format` is a variable-length string (model format 5, snapshot format 4),
// told from the attribute's type alone: its strings are never read (hdf5_fields.hpp,
// fixed_string_type). The integer `format_version` names the version.
[[noreturn]] void refuse_variable_length_file(hid_t file) {
  if (H5Lexists(file, "snapshots", H5P_DEFAULT) > 0 && H5Lexists(file, "meta", H5P_DEFAULT) <= 0) {
    throw H5Failure{kSnapshotNotModel};
  }
  const int version = hdf5::read_number_attribute<int>(file, "format_version", H5T_NATIVE_INT, H5T_INTEGER);
  if (version == contactrb::model::kReducedModelFormatVersion) {
    throw H5Failure{"damaged: its 'format' is a variable-length string, which format " + std::to_string(version) +
                    " never stores (not read)"};
  }
  throw H5Failure{rebuild_message(version)};
}

// Format, version and completeness of an open model file; throws H5Failure with the reason.
void check_header(hid_t file, const std::string& path, bool sealed) {
  if (H5Aexists(file, "format") <= 0) {
    if (is_snapshot_file(path)) throw H5Failure{kSnapshotNotModel};
    const int old = old_layout_version(file);
    if (old >= 0) throw H5Failure{rebuild_message(old)};
    throw H5Failure{"not a contactrb reduced model (no 'format' attribute)"};
  }
  if (hdf5::is_vlen_string_attribute(file, "format")) refuse_variable_length_file(file);
  std::string format;
  try {
    format = hdf5::read_string_attribute(file, "format");
  } catch (const H5Failure& e) {
    if (!sealed) throw H5Failure{"damaged or not written by contactrb (" + e.what + ")"};
    format = "(unreadable)";
  }
  if (format == kSnapshotFormatName) throw H5Failure{kSnapshotNotModel};
  if (format != kReducedModelFormatName) throw H5Failure{"not a contactrb reduced model (format '" + format + "')"};
  const int version = hdf5::read_number_attribute<int>(file, "format_version", H5T_NATIVE_INT, H5T_INTEGER);
  if (version != contactrb::model::kReducedModelFormatVersion) throw H5Failure{rebuild_message(version)};
  // Every file of this version is sealed by its writer: no seal, its first bytes were damaged.
  if (!sealed) throw H5Failure{"damaged: its seal (the first bytes of the file) is missing"};
  // `complete` = 1 is written last: a missing one or any other value is not a finished write.
  if (H5Aexists(file, "complete") <= 0 ||
      hdf5::read_number_attribute<int>(file, "complete", H5T_NATIVE_INT, H5T_INTEGER) != 1) {
    throw H5Failure{"incomplete file (the write was interrupted)"};
  }
}

}  // namespace

void write_reduced_model_file(const contactrb::model::ReducedModel& model, const std::string& path) {
  write_model_file(model, nullptr, path);
}

void write_reduced_model_file(const contactrb::model::ReducedModel& model,
                              const contactrb::model::ReducedReconstruction& reconstruction, const std::string& path) {
  write_model_file(model, &reconstruction, path);
}

contactrb::model::ReducedModel read_reduced_model_file(const std::string& path) {
  QuietHdf5 quiet;
  const std::string where = "reduced model file '" + path + "': ";
  const bool sealed = check_model_path(path, where);
  try {
    Handle file = open_model_file(path);
    check_header(file.get(), path, sealed);
    contactrb::model::ReducedModel m;
    m.format_version = contactrb::model::kReducedModelFormatVersion;
    FieldChecksum sum;
    hdf5::FieldReader r(sum);
    visit(r, Loc{file.get(), ""}, m);
    const auto stored =
        hdf5::read_number_attribute<std::uint64_t>(file.get(), "checksum", H5T_NATIVE_UINT64, H5T_INTEGER);
    if (stored != sum.value()) throw H5Failure{"checksum mismatch: the file was modified or damaged"};
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
  (void)check_model_path(path, where);
  try {
    Handle file = open_model_file(path);
    return H5Lexists(file.get(), kReconstructionGroup, H5P_DEFAULT) > 0;
  } catch (const H5Failure& e) {
    throw Error(where + e.what);
  }
}

contactrb::model::ReducedReconstruction read_reconstruction(const std::string& path) {
  QuietHdf5 quiet;
  const std::string where = "reduced model file '" + path + "': ";
  const bool sealed = check_model_path(path, where);
  try {
    Handle file = open_model_file(path);
    check_header(file.get(), path, sealed);
    if (H5Lexists(file.get(), kReconstructionGroup, H5P_DEFAULT) <= 0) {
      throw H5Failure{"no reconstruction data (a model written without them; rerun `contactrb offline` to get "
                      "them)"};
    }
    Handle g = hdf5::open_group(file.get(), kReconstructionGroup);
    const auto attribute = [&](const char* name) {
      return hdf5::read_number_attribute<int>(g.get(), name, H5T_NATIVE_INT, H5T_INTEGER);
    };
    if (H5Aexists(g.get(), "complete") <= 0 || attribute("complete") != 1) {
      throw H5Failure{"incomplete reconstruction data (the write was interrupted)"};
    }
    const int version = attribute("format_version");
    if (version != kReconstructionFormatVersion) {
      throw H5Failure{"reconstruction format version " + std::to_string(version) + ", this build reads version " +
                      std::to_string(kReconstructionFormatVersion)};
    }
    const int has_mesh = attribute("has_mesh");
    if (has_mesh != 0 && has_mesh != 1) throw H5Failure{"/reconstruction has_mesh is neither 0 nor 1"};
    contactrb::model::ReducedReconstruction rec;
    FieldChecksum sum;
    hdf5::FieldReader r(sum);
    visit_reconstruction(r, Loc{file.get(), ""}, rec, has_mesh == 1);
    const auto stored = hdf5::read_number_attribute<std::uint64_t>(g.get(), "checksum", H5T_NATIVE_UINT64, H5T_INTEGER);
    if (stored != sum.value()) throw H5Failure{"reconstruction checksum mismatch: the file was modified or damaged"};
    {  // the model's registration (covered by the model's checksum, checked with the model)
      FieldChecksum unused;
      hdf5::FieldReader model_reader(unused);
      visit_registration(model_reader, Loc{file.get(), ""}, rec.registration);
    }
    // Sizes only (the model-dependent checks are online::check_reconstruction's).
    require(rec.num_dofs > 0 && rec.Theta.rows() == static_cast<Eigen::Index>(rec.free_dofs.size()) &&
                rec.Xi.rows() == static_cast<Eigen::Index>(rec.kept_rows.size()) &&
                rec.lift.size() == rec.thetas.lift.size(),
            "reconstruction data with inconsistent array sizes");
    for (const Eigen::VectorXd& l : rec.lift) require(l.size() == rec.num_dofs, "reconstruction lift of the wrong size");
    if (has_mesh == 1) {
      mesh::validate(rec.mesh);  // indices, orientation, bodies, boundary edges: before any use
      require(rec.mesh.num_dofs() == rec.num_dofs, "the stored mesh has " + std::to_string(rec.mesh.num_dofs()) +
                                                       " DOFs, the reconstruction data " + std::to_string(rec.num_dofs));
    }
    return rec;
  } catch (const H5Failure& e) {
    throw Error(where + e.what);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
}

}  // namespace contactrb::io
