#pragma once
// Offline-side data that map a reduced solution back to the HF mesh (HF size: never used by
// the online solver). Written by `contactrb offline` next to the reduced arrays in the model
// file (io/reduced_model_file.hpp, group "reconstruction"), read only for VTU output and
// error analysis (study/evaluation.hpp). The maps themselves: online/reconstruction.hpp.
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/theta.hpp"
#include "contactrb/mesh/mesh.hpp"
#include "contactrb/model/registration.hpp"

namespace contactrb::model {

struct ReducedReconstruction {
  int num_dofs = 0;
  std::vector<int> free_dofs;
  Eigen::MatrixXd Theta;              // n_free x N_max
  std::vector<Eigen::VectorXd> lift;  // J^D global lift vectors lift_k (num_dofs)
  cases::AffineThetas thetas;
  std::vector<int> kept_rows;
  int num_constraints = 0;
  Eigen::MatrixXd Xi;                 // R_kept x R_max
  Registration registration;          // the model's (read from /registration): lambda = Xi(mu) lambda_hat
  // The reference mesh the HF DOFs live on (the snapshot set's), stored in the model file so
  // that no .msh file is needed online; empty when unknown (the case's mesh is regenerated).
  mesh::Mesh mesh;
};

}  // namespace contactrb::model
