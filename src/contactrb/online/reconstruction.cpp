#include "contactrb/online/reconstruction.hpp"

#include <bit>
#include <cstdint>
#include <set>
#include <string>
#include <utility>

#include "contactrb/common/error.hpp"
#include "contactrb/common/index_cast.hpp"
#include "contactrb/online/registered_basis.hpp"

namespace contactrb::online {

using model::ReducedModel;
using model::ReducedReconstruction;

namespace {
std::string str(long long v) { return std::to_string(v); }
}  // namespace

Eigen::VectorXd reconstruct_displacement(const ReducedReconstruction& rec, const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat) {
  require(u_hat.size() <= rec.Theta.cols(), "reconstruct_displacement: u_hat has size " +
                                                 std::to_string(u_hat.size()) + ", the basis " +
                                                 std::to_string(rec.Theta.cols()) + " modes");
  Eigen::VectorXd u = Eigen::VectorXd::Zero(rec.num_dofs);
  const Eigen::VectorXd th = cases::evaluate(rec.thetas.lift, mu);
  for (std::size_t k = 0; k < rec.lift.size(); ++k) u += th(ix(k)) * rec.lift[k];
  const Eigen::VectorXd u0 = rec.Theta.leftCols(u_hat.size()) * u_hat;
  for (std::size_t i = 0; i < rec.free_dofs.size(); ++i) u(rec.free_dofs[i]) += u0(ix(i));
  return u;
}

Eigen::VectorXd reconstruct_multipliers(const ReducedReconstruction& rec, const Eigen::VectorXd& mu,
                                        const Eigen::VectorXd& lambda_hat) {
  const Eigen::Index R_max = rec.registration.empty() ? rec.Xi.cols() : rec.registration.R();
  require(lambda_hat.size() <= R_max, "reconstruct_multipliers: lambda_hat has size " +
                                          std::to_string(lambda_hat.size()) + ", the dual basis " +
                                          std::to_string(R_max) + " vectors");
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(rec.num_constraints);
  const Eigen::VectorXd lk = dual_basis(rec, mu, static_cast<int>(lambda_hat.size())) * lambda_hat;
  for (std::size_t i = 0; i < rec.kept_rows.size(); ++i) lambda(rec.kept_rows[i]) = lk(ix(i));
  return lambda;
}

namespace {

// The stored mesh is the one the model was built on: its size is num_dofs / 2 and every
// contact-surface node of the model is one of its nodes, bit for bit (the surface was copied
// from it). A mesh scaled, moved or from another level would give fields on the wrong mesh.
void check_stored_mesh(const ReducedModel& model, const ReducedReconstruction& rec, const std::string& where) {
  if (rec.mesh.nodes.empty()) return;  // no stored mesh: the case's is regenerated and checked
  require(2 * static_cast<long long>(rec.mesh.nodes.size()) == rec.num_dofs,
          where + "the stored mesh has " + str(ix(rec.mesh.nodes.size())) + " nodes for " + str(rec.num_dofs) +
              " DOFs");
  const auto key = [](const Eigen::Vector2d& x) {
    return std::make_pair(std::bit_cast<std::uint64_t>(x.x()), std::bit_cast<std::uint64_t>(x.y()));
  };
  std::set<std::pair<std::uint64_t, std::uint64_t>> nodes;
  for (const Eigen::Vector2d& x : rec.mesh.nodes) nodes.insert(key(x));
  for (std::size_t i = 0; i < model.surface.reference_nodes.size(); ++i) {
    require(nodes.count(key(model.surface.reference_nodes[i])) == 1,
            where + "contact node " + str(ix(i)) + " of the model is not a node of the stored mesh (a mesh of another "
                    "size, position or level)");
  }
}

}  // namespace

void check_reconstruction(const ReducedModel& model, const ReducedReconstruction& rec) {
  const std::string where = "reconstruction data: ";
  require(rec.num_dofs > 0, where + "no DOF");
  for (int d : rec.free_dofs) require(d >= 0 && d < rec.num_dofs, where + "free DOF " + str(d) + " out of range");
  require(rec.Theta.rows() == ix(rec.free_dofs.size()),
          where + "the basis has " + str(rec.Theta.rows()) + " rows for " + str(ix(rec.free_dofs.size())) + " free DOFs");
  for (std::size_t k = 0; k < rec.lift.size(); ++k) {
    require(rec.lift[k].size() == rec.num_dofs, where + "lift " + str(ix(k)) + " has the wrong size");
  }
  require(rec.lift.size() == rec.thetas.lift.size(), where + "lift terms and their theta functions differ in number");
  require(rec.Xi.rows() == ix(rec.kept_rows.size()), where + "Xi has " + str(rec.Xi.rows()) + " rows for " +
                                                          str(ix(rec.kept_rows.size())) + " kept constraints");
  for (int r : rec.kept_rows) {
    require(r >= 0 && r < rec.num_constraints, where + "kept row " + str(r) + " out of range");
  }
  const auto differs = [&](const std::string& what, long long a, long long b) {
    require(a == b, where + what + " " + str(a) + " does not match the model's " + str(b) +
                        " (reconstruction data of another model?)");
  };
  differs("basis size N", rec.Theta.cols(), model.N_max);
  differs("dual basis size R", rec.Xi.cols(), model.R_max);
  differs("constraint count", rec.num_constraints, model.surface.num_constraints);
  differs("lift term count", ix(rec.lift.size()), model.J_lift());
  require(rec.kept_rows == model.kept_rows, where + "the kept constraint rows do not match the model's");
  check_stored_mesh(model, rec, where);
}

}  // namespace contactrb::online
