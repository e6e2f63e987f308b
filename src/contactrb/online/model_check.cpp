#include "contactrb/online/model_check.hpp"

#include <cmath>
#include <string>

#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/online/error_estimator.hpp"

namespace contactrb::online {

using model::ContactSurface;
using model::ReducedModel;
using model::kReducedModelFormatVersion;

namespace {
std::string dims(Eigen::Index r, Eigen::Index c) { return std::to_string(r) + " x " + std::to_string(c); }
void expect_shape(const Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols, const std::string& name) {
  require(m.rows() == rows && m.cols() == cols,
          "reduced model: " + name + " is " + dims(m.rows(), m.cols()) + ", expected " + dims(rows, cols));
}
void expect_size(const Eigen::VectorXd& v, Eigen::Index n, const std::string& name) {
  require(v.size() == n, "reduced model: " + name + " has size " + std::to_string(v.size()) + ", expected " +
                             std::to_string(n));
}
void expect_indices(const std::vector<int>& idx, std::size_t count, int bound, const std::string& name) {
  require(idx.size() == count, "reduced model: " + name + " has " + std::to_string(idx.size()) +
                                   " entries, expected " + std::to_string(count));
  for (int i : idx) {
    require(i >= 0 && i < bound, "reduced model: " + name + " holds index " + std::to_string(i) +
                                     " outside [0, " + std::to_string(bound) + ")");
  }
}

// The registered cone (model/registration.hpp): its shapes, a uniform grid, generators >= 0,
// supports of positive width; the kept rows must be the identity cone it maps onto.
void check_registration(const ReducedModel& m) {
  const model::Registration& g = m.registration;
  const bool registered = m.dual_method == model::kRegisteredCone;
  require(registered != g.empty(), registered ? "reduced model: a registered cone without its registration arrays"
                                              : "reduced model: registration arrays for a " + m.dual_method + " cone");
  if (!registered) return;
  const Eigen::Index P = m.training_mu.cols(), p = m.num_parameters(), n_g = g.grid.size();
  require(m.Xi.isIdentity(0.0), "reduced model: a registered cone's Xi must be the identity on the kept rows");
  expect_size(g.row_coordinate, m.R_kept(), "registration row_coordinate");
  require(n_g >= 2, "reduced model: the registration grid has fewer than 2 points");
  expect_shape(g.generators, n_g, g.R(), "registration generators");
  require(g.R() <= m.R_max, "reduced model: more registered generators than kept rows");
  expect_size(g.point_offset, p, "registration point_offset");
  expect_size(g.point_scale, p, "registration point_scale");
  expect_shape(g.points, p, P, "registration points");
  expect_shape(g.support, 2, P, "registration support");
  require(g.row_coordinate.allFinite() && g.grid.allFinite() && g.generators.allFinite() && g.points.allFinite() &&
              g.support.allFinite() && g.point_offset.allFinite() && g.point_scale.allFinite(),
          "reduced model: a registration array is not finite");
  const double h = (g.grid(n_g - 1) - g.grid(0)) / static_cast<double>(n_g - 1);
  for (Eigen::Index i = 1; i < n_g; ++i) {
    require(std::abs(g.grid(i) - g.grid(i - 1) - h) <= 1e-9 * std::abs(h) && h > 0.0,
            "reduced model: the registration grid is not uniform and increasing");
  }
  require(g.generators.minCoeff() >= 0.0, "reduced model: a registered generator has a negative entry");
  for (Eigen::Index j = 0; j < P; ++j) {
    require(g.support(1, j) > g.support(0, j), "reduced model: registration support " + std::to_string(j) +
                                                   " has no positive width");
  }
}

}  // namespace

void check_model(const ReducedModel& m) {
  require(m.format_version == kReducedModelFormatVersion,
          "reduced model: format version " + std::to_string(m.format_version) + ", this build reads version " +
              std::to_string(kReducedModelFormatVersion));
  require(m.level >= 0 && m.level <= mesh::kMaxMeshLevel,
          "reduced model: level " + std::to_string(m.level) + " (expected 0 to " + std::to_string(mesh::kMaxMeshLevel) +
              ", the finest built-in level)");
  require(m.N_max >= 1 && m.R_max >= 0 && m.Mk_max >= 0 && m.Mg_max >= 0,
          "reduced model: invalid maxima N_max = " + std::to_string(m.N_max) + ", R_max = " + std::to_string(m.R_max) +
              ", Mk_max = " + std::to_string(m.Mk_max) + ", Mg_max = " + std::to_string(m.Mg_max));
  require(m.N_supremizers >= 0 && m.N_supremizers < m.N_max,
          "reduced model: " + std::to_string(m.N_supremizers) + " supremizers in a basis of " +
              std::to_string(m.N_max) + " (at least one POD mode comes first)");
  const std::size_t Ja = m.thetas.a.size(), Jf = m.thetas.f.size(), JD = m.thetas.lift.size();
  require(m.A_hat.size() == Ja && Ja >= 1, "reduced model: " + std::to_string(m.A_hat.size()) +
                                               " matrices A_hat for " + std::to_string(Ja) + " theta^a");
  require(m.f_hat.size() == Jf, "reduced model: " + std::to_string(m.f_hat.size()) + " vectors f_hat for " +
                                    std::to_string(Jf) + " theta^f");
  require(m.A_lift_hat.size() == Ja * JD, "reduced model: A_lift_hat count " + std::to_string(m.A_lift_hat.size()) +
                                              ", expected J^a J^D = " + std::to_string(Ja * JD));
  require(m.lift_AA.size() == Ja * JD * JD && m.lift_f.size() == Jf * JD, "reduced model: lift energy terms");
  for (std::size_t j = 0; j < Ja; ++j) expect_shape(m.A_hat[j], m.N_max, m.N_max, "A_hat[" + std::to_string(j) + "]");
  for (std::size_t j = 0; j < Jf; ++j) expect_size(m.f_hat[j], m.N_max, "f_hat[" + std::to_string(j) + "]");
  for (std::size_t j = 0; j < m.A_lift_hat.size(); ++j) {
    expect_size(m.A_lift_hat[j], m.N_max, "A_lift_hat[" + std::to_string(j) + "]");
  }
  cases::check_parameter_list(m.parameters, "reduced model");
  cases::check_thetas(m.thetas, m.num_parameters(), "reduced model");
  require(m.training_mu.rows() == m.num_parameters() || m.training_mu.size() == 0,
          "reduced model: training points of " + std::to_string(m.training_mu.rows()) + " values for " +
              std::to_string(m.num_parameters()) + " parameters");
  require(m.training_mu.allFinite(), "reduced model: a training value is not finite");
  expect_shape(m.training_u_hat, m.N_max, m.training_mu.cols(), "training_u_hat");
  expect_shape(m.training_lambda_hat, m.R_max, m.training_mu.cols(), "training_lambda_hat");
  if (m.training_jacobian.size() > 0) {
    expect_shape(m.training_jacobian, m.N_max, static_cast<Eigen::Index>(m.N_max) * m.training_mu.cols(),
                 "training_jacobian");
    require(m.training_jacobian.allFinite(), "reduced model: training_jacobian holds a value that is not finite");
  }
  if (m.training_u_sensitivity.size() > 0) {
    expect_shape(m.training_u_sensitivity, m.N_max, static_cast<Eigen::Index>(m.num_parameters()) * m.training_mu.cols(),
                 "training_u_sensitivity");
    require(m.training_u_sensitivity.allFinite(), "reduced model: training_u_sensitivity holds a value that is not finite");
  }
  require(m.training_u_hat.allFinite() && m.training_lambda_hat.allFinite(),
          "reduced model: the training coordinates are not finite");
  const ContactSurface& s = m.surface;
  const int n_nodes = static_cast<int>(s.reference_nodes.size());
  const int n_c = s.num_dofs();
  require(n_nodes >= 3 && static_cast<int>(s.body.size()) == n_nodes,
          "reduced model: contact surface with " + std::to_string(n_nodes) + " nodes and " +
              std::to_string(s.body.size()) + " body ids");
  expect_indices(s.slave, s.slave.size(), n_nodes, "slave chain");
  expect_indices(s.master, s.master.size(), n_nodes, "master chain");
  require(s.slave.size() >= 2 && s.master.size() >= 2, "reduced model: contact chains need two nodes each");
  const int R_kept = m.R_kept();
  expect_indices(m.kept_rows, m.kept_rows.size(), s.num_constraints, "kept_rows");
  expect_shape(m.Xi, R_kept, m.R_max, "Xi");
  // The dual cone's generators are pressures (>= 0: CPG and angle-greedy keep scaled snapshots,
  // NMF non-negative factors); a negative entry beyond round-off is not a model of this method.
  if (m.Xi.size() > 0) {
    require(m.Xi.minCoeff() >= -1e-10 * m.Xi.cwiseAbs().maxCoeff(),
            "reduced model: the pressure basis Xi has a negative entry (" + number_text(m.Xi.minCoeff()) +
                "): its generators are contact pressures, >= 0");
  }
  expect_indices(m.kappa_row, static_cast<std::size_t>(m.Mk_max), R_kept, "kappa_row");
  expect_indices(m.kappa_dof, static_cast<std::size_t>(m.Mk_max), n_c, "kappa_dof");
  expect_shape(m.B_kappa, m.Mk_max, m.Mk_max, "B_kappa");
  require(static_cast<int>(m.C_kappa.size()) == m.Mk_max, "reduced model: " + std::to_string(m.C_kappa.size()) +
                                                              " matrices C_kappa for Mk_max = " +
                                                              std::to_string(m.Mk_max));
  for (std::size_t j = 0; j < m.C_kappa.size(); ++j) {
    expect_shape(m.C_kappa[j], m.R_max, m.N_max, "C_kappa[" + std::to_string(j) + "]");
  }
  expect_indices(m.gamma_row, static_cast<std::size_t>(m.Mg_max), R_kept, "gamma_row");
  expect_shape(m.B_gamma, m.Mg_max, m.Mg_max, "B_gamma");
  expect_shape(m.XiQ_gamma, m.R_max, m.Mg_max, "XiQ_gamma");
  expect_shape(m.Theta_c, n_c, m.N_max, "Theta_c");
  expect_shape(m.lift_c, n_c, static_cast<Eigen::Index>(JD), "lift_c");
  check_estimate_data(m);
  check_registration(m);
}

}  // namespace contactrb::online
