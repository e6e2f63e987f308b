#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact/contact_fixtures.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/contact/contact_pair.hpp"

using namespace contactrb;
using namespace contactrb::contact;
using contact_test::flat_blocks;
using mesh::Mesh;

namespace {

// Message of the contactrb::Error thrown by f (empty if none).
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

// Arc length of each slave node along the chain.
Eigen::VectorXd abscissa(const Mesh& m, const ContactPair& pair) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(pair.slave.size()));
  for (std::size_t i = 1; i < pair.slave.size(); ++i) {
    s(static_cast<Eigen::Index>(i)) =
        s(static_cast<Eigen::Index>(i - 1)) +
        (m.nodes[static_cast<std::size_t>(pair.slave[i])] - m.nodes[static_cast<std::size_t>(pair.slave[i - 1])]).norm();
  }
  return s;
}

// Moves the slave nodes along x to x0 + L ((i / n)^2): a graded, non-uniform chain.
void grade_slave(Mesh& m, const ContactPair& pair, double x0, double L) {
  const double n = static_cast<double>(pair.slave.size() - 1);
  for (std::size_t i = 0; i < pair.slave.size(); ++i) {
    m.nodes[static_cast<std::size_t>(pair.slave[i])].x() = x0 + L * (static_cast<double>(i) / n) * (static_cast<double>(i) / n);
  }
}

}  // namespace

TEST(ContactPair, DiscretizationNamesRoundTrip) {
  for (Discretization d : {Discretization::Collocation, Discretization::LAC, Discretization::LACSimpson}) {
    EXPECT_EQ(discretization_from_string(to_string(d)), d);
  }
  EXPECT_EQ(discretization_from_string("lac"), Discretization::LAC);
  EXPECT_EQ(discretization_from_string("lac-simpson"), Discretization::LACSimpson);
  const std::string msg = error_message([] { discretization_from_string("mortar"); });
  EXPECT_NE(msg.find("mortar"), std::string::npos) << msg;
  EXPECT_NE(msg.find("collocation"), std::string::npos) << msg;
  EXPECT_NE(msg.find("lac"), std::string::npos) << msg;
  EXPECT_NE(msg.find("lac-simpson"), std::string::npos) << msg;
}

TEST(ContactPair, ChainsFollowEdgeOrientation) {
  const Mesh m = flat_blocks(0.0, 1.0, 0.25, 4, 0.0, 1.0, 3);
  ASSERT_NO_THROW(mesh::validate(m));
  const ContactPair pair = make_contact_pair(m);
  ASSERT_EQ(pair.slave.size(), 5u);
  ASSERT_EQ(pair.master.size(), 4u);
  // Slave bottom runs left to right, master top right to left (each body on its left).
  EXPECT_EQ(m.nodes[static_cast<std::size_t>(pair.slave.front())].x(), 0.0);
  EXPECT_EQ(m.nodes[static_cast<std::size_t>(pair.slave.back())].x(), 1.0);
  EXPECT_EQ(m.nodes[static_cast<std::size_t>(pair.master.front())].x(), 1.0);
  EXPECT_EQ(m.nodes[static_cast<std::size_t>(pair.master.back())].x(), 0.0);
}

TEST(ContactPair, ErrorsNameTheProblem) {
  Mesh m = flat_blocks(0.0, 1.0, 0.25, 4, 0.0, 1.0, 3);
  {
    Mesh no_master = m;
    mesh::rename_boundary(no_master, "master", "m_top");
    const std::string msg = error_message([&] { make_contact_pair(no_master); });
    EXPECT_NE(msg.find("'master'"), std::string::npos) << msg;
  }
  {
    // Groups swapped: the slave group lies on body 1.
    Mesh swapped = m;
    mesh::rename_boundary(swapped, "master", "tmp");
    mesh::rename_boundary(swapped, "slave", "master");
    mesh::rename_boundary(swapped, "tmp", "slave");
    const std::string msg = error_message([&] { make_contact_pair(swapped); });
    EXPECT_NE(msg.find("slave boundary"), std::string::npos) << msg;
    EXPECT_NE(msg.find("body 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("must lie on body 0"), std::string::npos) << msg;
  }
  {
    // Two disjoint pieces.
    Mesh split = m;
    auto& edges = split.boundaries["slave"];
    edges.erase(edges.begin() + 1);
    const std::string msg = error_message([&] { make_contact_pair(split); });
    EXPECT_NE(msg.find("not a single polyline"), std::string::npos) << msg;
  }
  {
    // Closed slave loop: the whole boundary of the slave block.
    Mesh closed = m;
    auto& edges = closed.boundaries["slave"];
    for (const char* g : {"s_right", "s_top", "s_left"}) {
      edges.insert(edges.end(), closed.boundaries[g].begin(), closed.boundaries[g].end());
    }
    const std::string msg = error_message([&] { make_contact_pair(closed); });
    EXPECT_NE(msg.find("closed loop"), std::string::npos) << msg;
  }
}

TEST(ContactPair, ClosedMasterRepeatsItsFirstNode) {
  Mesh m = flat_blocks(0.0, 1.0, 0.25, 4, 0.0, 1.0, 3);
  auto& edges = m.boundaries["master"];
  for (const char* g : {"m_left", "m_bottom", "m_right"}) {
    edges.insert(edges.end(), m.boundaries[g].begin(), m.boundaries[g].end());
  }
  const ContactPair pair = make_contact_pair(m);
  EXPECT_EQ(pair.master.size(), edges.size() + 1);
  EXPECT_EQ(pair.master.front(), pair.master.back());
}

TEST(Quadrature, CollocationIsDiagonalHalfEdges) {
  Mesh m = flat_blocks(0.0, 2.0, 0.25, 6, 0.0, 2.0, 3);
  const ContactPair pair = make_contact_pair(m);
  grade_slave(m, pair, 0.0, 2.0);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::Collocation);
  const Eigen::VectorXd s = abscissa(m, pair);
  const int S = static_cast<int>(pair.slave.size());
  ASSERT_EQ(q.W.rows(), S);
  ASSERT_EQ(q.W.cols(), S);
  EXPECT_EQ(q.W.nonZeros(), S);
  EXPECT_NEAR(q.weight.sum(), 2.0, 1e-14);
  for (int r = 0; r < S; ++r) {
    const double left = r > 0 ? s(r) - s(r - 1) : 0.0;
    const double right = r < S - 1 ? s(r + 1) - s(r) : 0.0;
    EXPECT_NEAR(q.W.coeff(r, r), 0.5 * (left + right), 1e-15);
    EXPECT_EQ(q.weight(r), q.W.coeff(r, r));
    EXPECT_EQ(q.center_node[static_cast<std::size_t>(r)], pair.slave[static_cast<std::size_t>(r)]);
  }
}

TEST(Quadrature, LacSimpsonIsExactForQuadratics) {
  // 8 uniform slave edges: 4 macro-segments, Simpson exact for a quadratic of the abscissa.
  const Mesh m = flat_blocks(0.0, 2.0, 0.25, 8, 0.0, 2.0, 3);
  const ContactPair pair = make_contact_pair(m);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::LACSimpson);
  ASSERT_EQ(q.W.rows(), 4);
  ASSERT_EQ(q.W.cols(), 9);
  EXPECT_NEAR(q.weight.sum(), 2.0, 1e-14);
  const Eigen::VectorXd s = abscissa(m, pair);
  const Eigen::VectorXd f = (3.0 * s.array().square() - 2.0 * s.array() + 1.0).matrix();
  const double exact = 8.0 - 4.0 + 2.0;  // int_0^2 (3 s^2 - 2 s + 1) ds
  EXPECT_NEAR((q.W * f).sum(), exact, 1e-13);
  // Each row integrates over its own macro-segment [s_2r, s_2r+2].
  for (int r = 0; r < 4; ++r) {
    const double a = s(2 * r), b = s(2 * r + 2);
    const double row_exact = (b * b * b - a * a * a) - (b * b - a * a) + (b - a);
    EXPECT_NEAR((q.W * f)(r), row_exact, 1e-13);
    EXPECT_NEAR(q.weight(r), b - a, 1e-15);
    EXPECT_NEAR(q.W.coeff(r, 2 * r + 1), 4.0 * (b - a) / 6.0, 1e-15);
    EXPECT_EQ(q.center_node[static_cast<std::size_t>(r)], pair.slave[static_cast<std::size_t>(2 * r + 1)]);
  }
}

TEST(Quadrature, LacOddEdgeCountEndsWithTrapezoid) {
  Mesh m = flat_blocks(0.0, 1.0, 0.25, 7, 0.0, 1.0, 3);
  const ContactPair pair = make_contact_pair(m);
  grade_slave(m, pair, 0.0, 1.0);
  const Eigen::VectorXd s = abscissa(m, pair);
  for (Discretization d : {Discretization::LAC, Discretization::LACSimpson}) {
    const ContactQuadrature q = make_quadrature(m, pair, d);
    ASSERT_EQ(q.W.rows(), 4);  // ceil(7 / 2)
    EXPECT_NEAR(q.weight.sum(), 1.0, 1e-14);
    const double e = s(7) - s(6);
    EXPECT_EQ(q.W.row(3).nonZeros(), 2);
    EXPECT_NEAR(q.W.coeff(3, 6), e / 2.0, 1e-15);
    EXPECT_NEAR(q.W.coeff(3, 7), e / 2.0, 1e-15);
    EXPECT_EQ(q.center_node[3], pair.slave[6]);
  }
  // On a uniform chain, linear functions are integrated exactly by both rules. (On a graded
  // chain the Simpson weights |I|/6, 4|I|/6, |I|/6 assume the middle node at the midpoint,
  // as in the paper, so they are not exact there; the LAC weights are, see below.)
  const Mesh u = flat_blocks(0.0, 1.0, 0.25, 7, 0.0, 1.0, 3);
  const ContactPair pu = make_contact_pair(u);
  const ContactQuadrature qu = make_quadrature(u, pu, Discretization::LACSimpson);
  const Eigen::VectorXd su = abscissa(u, pu);
  const Eigen::VectorXd f = (5.0 * su.array() - 1.0).matrix();
  EXPECT_NEAR((qu.W * f).sum(), 2.5 - 1.0, 1e-14);
}

TEST(Quadrature, LacWeightsAreExactForP1OnAGradedChain) {
  // LAC's W: int_{I_r} phi_s = h1/2, (h1 + h2)/2, h2/2, exact for P1 on the slave chain.
  Mesh m = flat_blocks(0.0, 2.0, 0.25, 8, 0.0, 2.0, 3);
  const ContactPair pair = make_contact_pair(m);
  grade_slave(m, pair, 0.0, 2.0);
  const ContactQuadrature q = make_quadrature(m, pair, Discretization::LAC);
  const Eigen::VectorXd s = abscissa(m, pair);
  ASSERT_EQ(q.W.rows(), 4);
  EXPECT_NEAR(q.weight.sum(), 2.0, 1e-14);
  const Eigen::VectorXd f = (5.0 * s.array() - 1.0).matrix();
  for (int r = 0; r < 4; ++r) {
    const double a = s(2 * r), mid = s(2 * r + 1), b = s(2 * r + 2);
    EXPECT_NEAR(q.W.coeff(r, 2 * r), 0.5 * (mid - a), 1e-15);
    EXPECT_NEAR(q.W.coeff(r, 2 * r + 1), 0.5 * (b - a), 1e-15);
    EXPECT_NEAR(q.W.coeff(r, 2 * r + 2), 0.5 * (b - mid), 1e-15);
    EXPECT_NEAR(q.weight(r), b - a, 1e-15);
    EXPECT_NEAR((q.W * f)(r), 2.5 * (b * b - a * a) - (b - a), 1e-14);
    EXPECT_EQ(q.center_node[static_cast<std::size_t>(r)], pair.slave[static_cast<std::size_t>(2 * r + 1)]);
  }
  // The Simpson rule on the same graded chain is not exact for linear functions.
  const ContactQuadrature simpson = make_quadrature(m, pair, Discretization::LACSimpson);
  EXPECT_GT(std::abs((simpson.W * f).sum() - (10.0 - 2.0)), 1e-3);
}

TEST(Quadrature, RejectsShortChains) {
  const Mesh m = flat_blocks(0.0, 1.0, 0.25, 2, 0.0, 1.0, 3);
  ContactPair pair = make_contact_pair(m);
  pair.slave.resize(1);
  EXPECT_THROW(make_quadrature(m, pair, Discretization::LAC), Error);
}
