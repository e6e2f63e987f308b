#include <gtest/gtest.h>

#include "contactrb/common/error.hpp"
#include "contactrb/offline/compression.hpp"

using namespace contactrb::offline;
using Eigen::MatrixXd;
using Eigen::VectorXd;

TEST(Compression, NeverActiveConstraintsAreDropped) {
  MatrixXd L = MatrixXd::Zero(6, 4);
  L(0, 0) = 1.0;
  L(2, 1) = 0.5;
  L(3, 3) = 2.0;
  L(5, 2) = 1e-3;
  const Compression c = compress_constraints(L);
  EXPECT_EQ(c.total, 6);
  EXPECT_EQ(c.active, 4);
  EXPECT_EQ(c.kept, (std::vector<int>{0, 2, 3, 5}));
  // A threshold drops the barely active one.
  EXPECT_EQ(compress_constraints(L, {.enabled = true, .threshold = 1e-2}).kept, (std::vector<int>{0, 2, 3}));
  // Switched off: everything kept, the active count still reported.
  const Compression off = compress_constraints(L, {.enabled = false, .threshold = 0.0});
  EXPECT_EQ(off.kept, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(off.active, 4);
  // Restricting rows of K (R x N) and g (R).
  MatrixXd K(6, 2);
  for (int r = 0; r < 6; ++r) K.row(r) << r, 10 * r;
  const MatrixXd Kc = restrict_rows(K, c.kept);
  ASSERT_EQ(Kc.rows(), 4);
  EXPECT_EQ(Kc(3, 1), 50.0);
  const VectorXd g = VectorXd::LinSpaced(6, 0.0, 5.0);
  EXPECT_EQ(restrict_rows(g, c.kept), (VectorXd(4) << 0, 2, 3, 5).finished());
  EXPECT_THROW(restrict_rows(g, {6}), contactrb::Error);
  EXPECT_THROW(active_constraints(L, -1.0), contactrb::Error);
}
