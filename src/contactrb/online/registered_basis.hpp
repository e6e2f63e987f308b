#pragma once
// The registered dual cone online (model/registration.hpp): the support predicted at mu and the
// dual basis Xi(mu) on the kept rows.
#include <Eigen/Core>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/model/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/model/registration.hpp"

namespace contactrb::online {

// s of every constraint row (R_hf): the arc length along the slave chain, in the reference
// configuration, of the row's centre node (ContactQuadrature::center_node).
Eigen::VectorXd row_coordinates(const contactrb::model::ContactSurface& surface);

// [s_left, s_right](mu). One parameter: linear interpolation between the training values (the
// end values outside them). More: a linear least-squares fit over the nearest 2 (p + 1) training
// points (scaled coordinates), weighted by the inverse squared distance, so that a training point
// gets its own support back.
Eigen::Vector2d predicted_support(const contactrb::model::Registration& reg, const cases::Mu& mu);

// Xi (R_kept x R): Xi_rk = G_k((s_r - s_left) / (s_right - s_left)), the first R generators.
void registered_basis(const contactrb::model::Registration& reg, const Eigen::Vector2d& support, int R,
                      Eigen::MatrixXd& Xi);

// The dual basis of a reconstruction at mu: the first R columns of Xi, or of Xi(mu) when the
// model's cone is registered.
Eigen::MatrixXd dual_basis(const contactrb::model::ReducedReconstruction& rec, const cases::Mu& mu, int R);

}  // namespace contactrb::online
