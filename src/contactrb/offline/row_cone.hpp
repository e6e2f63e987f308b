#pragma once
// The row cone: one generator per kept constraint row, the unit vector of that row. Every
// non-negative pressure on the rows active in training lies in it, so the reduced pressure is
// the HF pressure on those rows and their HF constraints hold exactly in the reduced problem
// (with the exact contact rows online, OnlineSettings::exact_rows). R is the number of rows
// active in training: small where the contact zone covers few rows (coarse meshes).
#include <Eigen/Core>

#include "contactrb/offline/dual_cone.hpp"

namespace contactrb::offline {

// snapshots: R_kept x P multipliers (>= 0, finite), settings.weights the Lambda-norm weights.
// errors[k] = max_p |lambda_p restricted to rows >= k|_Lambda, the error of the cone of the first k
// generators (an orthant face: the projection drops the other rows); errors[R_kept] = 0.
// selected[k]: the first snapshot (column) in which row k is active (> 0), 0 for a row active in
// none: the snapshot whose contact rows give the row's supremizer, fixed as snapshots are
// appended (OfflineSettings::extend_basis).
DualConeResult build_row_cone(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings);

}  // namespace contactrb::offline
