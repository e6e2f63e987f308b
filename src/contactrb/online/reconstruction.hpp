#pragma once
// A reduced solution mapped back to the HF mesh with the reconstruction data
// (model/reconstruction.hpp), and their check against the model they were built with.
#include <Eigen/Core>

#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::online {

// u = u_D(mu) + Theta[:, :N] u_hat on the HF DOFs (num_dofs), N = u_hat.size().
Eigen::VectorXd reconstruct_displacement(const contactrb::model::ReducedReconstruction& rec, const Eigen::VectorXd& mu,
                                         const Eigen::VectorXd& u_hat);
// lambda = Xi[:, :R] lambda_hat on the kept rows (Xi(mu) for a registered cone), 0 on the dropped
// ones (R_hf), R = lambda_hat.size().
Eigen::VectorXd reconstruct_multipliers(const contactrb::model::ReducedReconstruction& rec, const Eigen::VectorXd& mu,
                                        const Eigen::VectorXd& lambda_hat);

// Throws contactrb::Error naming the first disagreement between a reconstruction and the model
// it was built with (basis sizes, kept rows, constraint count, lift terms) or an inconsistent
// reconstruction (array sizes, indices out of range).
void check_reconstruction(const contactrb::model::ReducedModel& model,
                          const contactrb::model::ReducedReconstruction& rec);

}  // namespace contactrb::online
