#pragma once
// The bodies whose rigid motions the Dirichlet conditions leave free: without contact their
// stiffness is singular, whatever a sparse factorization of A_00 reports at round-off. A rigid
// motion of body b (2D: two translations and the rotation about its centroid; 3D: three and
// three) is held when it moves some constrained DOF of b; b floats when a combination of them
// moves none: the matrix of the motions' values at b's constrained DOFs has a null space.
#include <vector>

#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/mesh/mesh.hpp"

namespace contactrb::fem {

// The ids of the floating bodies, increasing (empty: every body held).
template <int Dim>
std::vector<int> floating_bodies(const mesh::SimplexMesh<Dim>& mesh, const DofMap& dofs);

extern template std::vector<int> floating_bodies(const mesh::SimplexMesh<2>&, const DofMap&);
extern template std::vector<int> floating_bodies(const mesh::SimplexMesh<3>&, const DofMap&);

}  // namespace contactrb::fem
