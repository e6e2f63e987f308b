// fem/floating_bodies.hpp: a body is floating exactly when its stiffness restricted to the free
// DOFs is singular. The independent truth: the smallest eigenvalue of that body's A_00 (dense,
// from the assembled stiffness), at round-off for a floating body and O(1) for a held one.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <vector>

#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/fem/floating_bodies.hpp"
#include "contactrb/mesh/structured.hpp"

using namespace contactrb;
using namespace contactrb::fem;

namespace {
// Two bodies, side by side and not touching: the lower one (body 1) under the upper (body 0).
mesh::Mesh two_rectangles() {
  mesh::Mesh upper = mesh::rectangle(0.0, 1.1, 2.0, 2.1, 4, 2, mesh::kSlaveBody);
  mesh::Mesh lower = mesh::rectangle(0.0, 0.0, 2.0, 1.0, 3, 2, mesh::kMasterBody);
  for (const char* g : {"bottom", "right", "top", "left"}) mesh::rename_boundary(lower, g, std::string("lower_") + g);
  return mesh::merge(upper, lower);
}

// The smallest eigenvalue of A_00 relative to its largest: about 1e-16 when a body floats.
template <int Dim>
double relative_smallest_eigenvalue(const mesh::SimplexMesh<Dim>& m, const DofMap& dofs) {
  const Eigen::MatrixXd A00 = Eigen::MatrixXd(dofs.restrict_matrix(stiffness(m, std::vector<Material>{{15.0, 0.35}, {15.0, 0.35}})));
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A00, Eigen::EigenvaluesOnly).eigenvalues();
  return ev(0) / ev(ev.size() - 1);
}
}  // namespace

TEST(FloatingBodies, TwoDimensionsAgreeWithTheStiffnessSpectrum) {
  const mesh::Mesh m = two_rectangles();
  struct Case {
    std::vector<DirichletCondition> conditions;
    std::vector<int> floating;
  };
  const std::vector<Case> cases{
      {{{"top", 0.0, 0.0}, {"lower_bottom", 0.0, 0.0}}, {}},
      // The upper body held in y only along its top edge: free to translate along x.
      {{{"top", std::nullopt, -0.1}, {"lower_bottom", 0.0, 0.1}}, {0}},
      // Held in x on one edge and in y on another: every motion held.
      {{{"top", std::nullopt, -0.1}, {"left", 0.0, std::nullopt}, {"lower_bottom", 0.0, 0.0}}, {}},
      // x fixed on a vertical edge only: y translation free (the rotation is held).
      {{{"left", 0.0, std::nullopt}, {"lower_bottom", 0.0, 0.0}}, {0}},
      // Nothing on the lower body.
      {{{"top", 0.0, 0.0}}, {1}},
  };
  for (const Case& c : cases) {
    const DofMap dofs(m, c.conditions);
    EXPECT_EQ(floating_bodies(m, dofs), c.floating);
    const double lmin = relative_smallest_eigenvalue(m, dofs);
    if (c.floating.empty()) {
      EXPECT_GT(lmin, 1e-6);
    } else {
      EXPECT_LT(lmin, 1e-12);
    }
  }
}

TEST(FloatingBodies, ThreeDimensionsAgreeWithTheStiffnessSpectrum) {
  const mesh::Mesh3 m = mesh::box({0, 0, 0}, {1.0, 0.8, 0.6}, 2, 2, 2);
  const auto check = [&](const std::vector<DirichletCondition>& conditions, bool floats) {
    const DofMap dofs(m, conditions);
    EXPECT_EQ(floating_bodies(m, dofs).size(), floats ? 1u : 0u);
    const Eigen::MatrixXd A00 = Eigen::MatrixXd(dofs.restrict_matrix(stiffness(m, std::vector<Material>{{15.0, 0.35}})));
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A00, Eigen::EigenvaluesOnly).eigenvalues();
    if (floats) {
      EXPECT_LT(ev(0) / ev(ev.size() - 1), 1e-12);
    } else {
      EXPECT_GT(ev(0) / ev(ev.size() - 1), 1e-6);
    }
  };
  check({{"bottom", 0.0, 0.0, 0.0}}, false);
  check({{"bottom", std::nullopt, std::nullopt, 0.0}}, true);  // in-plane translations and rotation free
  check({{"bottom", std::nullopt, std::nullopt, 0.0}, {"left", 0.0, std::nullopt, std::nullopt},
         {"front", std::nullopt, 0.0, std::nullopt}},
        false);
}
