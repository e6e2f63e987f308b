#pragma once
// The registered dual cone (docs/offline-online.md, "The registered cone"): the contact pressure
// written in a registered coordinate xi = (s - s_left(mu)) / (s_right(mu) - s_left(mu)), s the
// arc length along the slave chain, so that a support that moves with mu stops moving. The
// generators are non-negative registered pressure profiles on a uniform xi grid; online, the
// support ends are predicted from the training points and each kept row r gets
// Xi(mu)_rk = G_k(xi_r(mu)) (linear interpolation on the grid, 0 outside it).
// Built by offline/registration.hpp, evaluated by online/registered_basis.hpp.
#include <Eigen/Core>

namespace contactrb::model {

struct Registration {
  Eigen::VectorXd row_coordinate;  // R_kept: s of each kept row's centre node, reference configuration
  Eigen::VectorXd grid;            // n_g: uniform registered coordinates, increasing
  Eigen::MatrixXd generators;      // n_g x R: column k is generator G_k on the grid, >= 0
  // The training points scaled to [0, 1] per parameter, x = (mu - offset) .* scale, and the
  // support [s_left, s_right] of each training pressure (its ends: half-way to the first
  // inactive row on either side).
  Eigen::VectorXd point_offset, point_scale;  // p
  Eigen::MatrixXd points;                     // p x P
  Eigen::MatrixXd support;                    // 2 x P

  bool empty() const { return generators.cols() == 0; }
  int R() const { return static_cast<int>(generators.cols()); }
};

}  // namespace contactrb::model
