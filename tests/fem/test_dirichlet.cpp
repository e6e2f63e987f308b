#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "contactrb/common/error.hpp"
#include "contactrb/fem/dirichlet.hpp"
#include "fem_fixtures.hpp"

using namespace contactrb;
using namespace contactrb::fem;

namespace {
bool message_contains(const std::function<void()>& f, const std::string& text) {
  try {
    f();
  } catch (const Error& e) {
    return std::string(e.what()).find(text) != std::string::npos;
  }
  return false;
}
}  // namespace

TEST(DofMap, NumberingLiftAndRoundTrip) {
  const mesh::Mesh m = mesh::rectangle(0, 0, 2, 1, 4, 2);  // 15 nodes
  const DofMap dofs(m, {{"left", 0.0, 0.0}, {"right", 0.25, std::nullopt}});
  EXPECT_EQ(dofs.num_dofs(), 30);
  // left: 3 nodes x 2 DOFs, right: 3 nodes x 1 DOF.
  EXPECT_EQ(static_cast<int>(dofs.constrained_dofs().size()), 9);
  EXPECT_EQ(dofs.num_free(), 21);
  EXPECT_TRUE(std::is_sorted(dofs.constrained_dofs().begin(), dofs.constrained_dofs().end()));
  EXPECT_TRUE(std::is_sorted(dofs.free_dofs().begin(), dofs.free_dofs().end()));
  for (int node : mesh::boundary_nodes(m, "right")) {
    EXPECT_EQ(dofs.lift()(2 * node), 0.25);
    EXPECT_TRUE(std::find(dofs.free_dofs().begin(), dofs.free_dofs().end(), 2 * node + 1) != dofs.free_dofs().end());
  }
  EXPECT_EQ(dofs.lift().sum(), 0.75);
  const Eigen::VectorXd free = Eigen::VectorXd::LinSpaced(dofs.num_free(), 1.0, 21.0);
  const Eigen::VectorXd global = dofs.extend(free);
  EXPECT_EQ(dofs.restrict(global), free);
  for (int d : dofs.constrained_dofs()) EXPECT_EQ(global(d), 0.0);
  // extend(restrict(g)) + lift() == g for a g that carries the prescribed values.
  Eigen::VectorXd g = Eigen::VectorXd::Random(30);
  for (int d : dofs.constrained_dofs()) g(d) = dofs.lift()(d);
  EXPECT_EQ(dofs.extend(dofs.restrict(g)) + dofs.lift(), g);
  EXPECT_THROW(dofs.restrict(Eigen::VectorXd(29)), Error);
  EXPECT_THROW(dofs.extend(Eigen::VectorXd(30)), Error);
}

TEST(DofMap, MatrixRestrictionsMatchDenseSelection) {
  const mesh::Mesh m = mesh::rectangle(0, 0, 1, 1, 3, 3);
  const SparseMatrix K = stiffness(m, {Material{}});
  const DofMap dofs(m, {{"bottom", 0.0, 0.0}, {"top", std::nullopt, -0.1}});
  const Eigen::MatrixXd Kd(K);
  const SparseMatrix K00 = dofs.restrict_matrix(K);
  ASSERT_EQ(K00.rows(), dofs.num_free());
  for (int i = 0; i < dofs.num_free(); ++i)
    for (int j = 0; j < dofs.num_free(); ++j)
      EXPECT_EQ(K00.coeff(i, j), Kd(dofs.free_dofs()[static_cast<std::size_t>(i)], dofs.free_dofs()[static_cast<std::size_t>(j)]));
  const Eigen::VectorXd f = Eigen::VectorXd::Random(m.num_dofs());
  EXPECT_LT((dofs.restrict_rhs(K, f) - dofs.restrict(f - Kd * dofs.lift())).norm(), 1e-14);
  Eigen::SparseMatrix<double, Eigen::RowMajor> C(2, m.num_dofs());
  C.insert(0, 1) = 2.0;
  C.insert(0, 9) = -1.0;
  C.insert(1, dofs.constrained_dofs()[0]) = 5.0;
  const auto C0 = dofs.restrict_columns(C);
  EXPECT_EQ(C0.cols(), dofs.num_free());
  for (int k = 0; k < dofs.num_free(); ++k)
    for (int r = 0; r < 2; ++r) EXPECT_EQ(C0.coeff(r, k), C.coeff(r, dofs.free_dofs()[static_cast<std::size_t>(k)]));
  EXPECT_THROW(dofs.restrict_matrix(SparseMatrix(3, 3)), Error);
}

TEST(DofMap, ErrorsNameTheGroupOrTheDof) {
  const mesh::Mesh m = mesh::rectangle(0, 0, 1, 1, 2, 2);
  EXPECT_TRUE(message_contains([&] { DofMap(m, {{"clamp", 0.0, 0.0}}); }, "'clamp'"));
  EXPECT_TRUE(message_contains([&] { DofMap(m, {{"clamp", 0.0, 0.0}}); }, "bottom"));  // lists the groups
  // The corner node 0 is in "bottom" and "left": equal values are fine, different ones not.
  EXPECT_NO_THROW(DofMap(m, {{"bottom", 0.0, 0.0}, {"left", 0.0, std::nullopt}}));
  EXPECT_TRUE(message_contains([&] { DofMap(m, {{"bottom", 0.0, 0.0}, {"left", 0.1, std::nullopt}}); },
                               "DOF 0 (node 0, x)"));
  const DofMap none(m, {});
  EXPECT_EQ(none.num_free(), m.num_dofs());
  EXPECT_EQ(none.lift().norm(), 0.0);
}
