// S = (A^-1)[c, c] from elimination-tree forward solves against a dense inverse.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "contactrb/fem/dirichlet.hpp"
#include "contactrb/fem/elasticity.hpp"
#include "contactrb/hf/contact_condensation.hpp"
#include "hf_test_meshes.hpp"

using namespace contactrb;

TEST(ContactCondensation, EqualsTheDenseInverseBlockAndSolves) {
  mesh::Mesh m = test_meshes::two_blocks(1.0, 0.5, 0.7, 6, 3, 7, 4);
  mesh::perturb_interior(m, 0.2, 3);
  const fem::DofMap dofs(m, {{"top", 0.0, -0.1}, {"bottom", 0.0, 0.0}});
  const Eigen::SparseMatrix<double> A00 = dofs.restrict_matrix(fem::stiffness(m, {{3.0, 0.3}, {1.0, 0.25}}));
  const Eigen::MatrixXd Ainv = Eigen::MatrixXd(A00).inverse();
  const std::vector<int> contact{0, 5, 17, 3, 40, static_cast<int>(A00.rows()) - 1};
  const hf::ContactCondensation cc(A00, contact);
  for (std::size_t i = 0; i < contact.size(); ++i) {
    for (std::size_t j = 0; j < contact.size(); ++j) {
      EXPECT_NEAR(cc.contact_inverse()(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)),
                  Ainv(contact[i], contact[j]), 1e-12 * Ainv.cwiseAbs().maxCoeff());
    }
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A00.rows(), -1.0, 2.0);
  EXPECT_LT((A00 * cc.solve(b) - b).norm(), 1e-12 * b.norm());
}
