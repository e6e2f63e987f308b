#pragma once
// Offline-side data that map a reduced solution back to the HF mesh (HF size: never used by
// the online solver). Written by `contactrb offline` next to the reduced arrays in the model
// file (io/reduced_model_file.hpp, group "reconstruction"), read only for VTU output and
// error analysis (study/evaluation.hpp).
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/theta.hpp"
#include "contactrb/online/reduced_model.hpp"

namespace contactrb::rb {

struct ReducedReconstruction {
  int num_dofs = 0;
  std::vector<int> free_dofs;
  Eigen::MatrixXd Theta;              // n_free x N_max
  std::vector<Eigen::VectorXd> lift;  // J^D global lift vectors lift_k (num_dofs)
  cases::AffineThetas thetas;
  std::vector<int> kept_rows;
  int num_constraints = 0;
  Eigen::MatrixXd Xi;                 // R_kept x R_max
};

// u = u_D(mu) + Theta[:, :N] u_hat on the HF DOFs (num_dofs), N = u_hat.size().
Eigen::VectorXd reconstruct_displacement(const ReducedReconstruction& rec, const Eigen::VectorXd& mu, const Eigen::VectorXd& u_hat);
// lambda = Xi[:, :R] lambda_hat on the kept rows, 0 on the dropped ones (R_hf), R = lambda_hat.size().
Eigen::VectorXd reconstruct_multipliers(const ReducedReconstruction& rec, const Eigen::VectorXd& lambda_hat);

// Throws contactrb::Error naming the first disagreement between a reconstruction and the model
// it was built with (basis sizes, kept rows, constraint count, lift terms) or an inconsistent
// reconstruction (array sizes, indices out of range).
void check_reconstruction(const ReducedModel& model, const ReducedReconstruction& rec);

}  // namespace contactrb::rb
