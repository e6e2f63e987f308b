#pragma once
// The geometric maps h_i(mu) of paper (32): affine per body, x -> M_i(mu) x + b_i(mu).
// FE-free (no mesh), so the online stage can map the few nodes it needs (e.g. the EIM
// magic points of the gap) without the mesh.
#include <Eigen/Core>
#include <Eigen/LU>  // determinant
#include <array>
#include <vector>

#include "contactrb/cases/parameter.hpp"

namespace contactrb::cases {

struct AffineMap {
  Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d& x) const { return M * x + b; }
  double jacobian() const { return M.determinant(); }  // det M_i(mu), paper (47)
  bool is_identity() const { return M == Eigen::Matrix2d::Identity() && b.isZero(0.0); }
};

// h_0(mu), h_1(mu) (body 0 slave, body 1 master). A body with a BodyScaling parameter k gets
// M = s I, b = (1 - s) c with s = mu_k / reference (x -> s (x - c) + c); a body without, the
// identity. Exactly the identity at mu_k = reference. `mu` has one value per parameter.
std::array<AffineMap, 2> geometric_maps(const std::vector<ParameterSpec>& parameters, const Mu& mu);
// True when some parameter moves a body (the gap and the contact map depend on mu: EIM).
bool is_geometric(const std::vector<ParameterSpec>& parameters);

}  // namespace contactrb::cases
