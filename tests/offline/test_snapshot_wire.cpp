// offline/snapshot_wire.hpp: a packed result and task unpack to the same bits (signed zeros, NaN
// payloads, empty arrays), and damaged bytes are refused, never read past.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "contactrb/common/error.hpp"
#include "contactrb/io/snapshot_rows.hpp"
#include "contactrb/offline/snapshot_wire.hpp"
#include "support/snapshot_fixtures.hpp"

namespace offline = contactrb::offline;
namespace io = contactrb::io;
using contactrb::test::same_bits;

TEST(SnapshotWire, ResultRoundTripIsBitwise) {
  io::Snapshot s;
  s.mu = Eigen::Vector2d(0.3, -0.0);
  s.converged = true;
  s.status = "converged";
  s.message = std::string("with\0nul", 8);
  s.iterations = 17;
  s.time_s = 1.25;
  s.cpu_time_s = 0.5;
  s.u0 = Eigen::VectorXd::LinSpaced(7, -1.0, 1.0);
  s.u = Eigen::VectorXd::Random(9);
  s.u(3) = std::numeric_limits<double>::quiet_NaN();
  s.lambda = Eigen::VectorXd::Random(3);
  Eigen::MatrixXd K = Eigen::MatrixXd::Random(3, 4);
  K(1, 2) = 0.0;  // not stored
  s.K = io::rows_from_dense(K);
  ASSERT_EQ(s.K.nonZeros(), 11);
  s.g = Eigen::VectorXd::Random(3);
  s.weight = Eigen::VectorXd();  // empty
  s.gap_pointwise = Eigen::VectorXd::Random(2);
  offline::SnapshotLayout l;
  l.valid = true;
  l.num_dofs = 9;
  l.free_dofs = {0, 2, 5};
  l.contact_dofs = {4, 5, 6, 7};
  l.slave = {2};
  l.master = {3, 1, 3};
  l.constraint = "lac";

  const std::vector<char> bytes = offline::pack_solved(42, s, l);
  std::uint64_t index = 0;
  io::Snapshot t;
  offline::SnapshotLayout m;
  offline::unpack_solved(bytes, index, t, m);
  EXPECT_EQ(index, 42u);
  EXPECT_TRUE(same_bits(s.mu, t.mu));
  EXPECT_EQ(t.converged, true);
  EXPECT_EQ(t.status, s.status);
  EXPECT_EQ(t.message, s.message);
  EXPECT_EQ(t.iterations, 17);
  EXPECT_EQ(t.time_s, 1.25);
  EXPECT_EQ(t.cpu_time_s, 0.5);
  EXPECT_TRUE(same_bits(s.u0, t.u0));
  EXPECT_TRUE(same_bits(s.u, t.u));
  EXPECT_TRUE(same_bits(s.lambda, t.lambda));
  EXPECT_TRUE(same_bits(s.K, t.K));
  EXPECT_TRUE(same_bits(s.g, t.g));
  EXPECT_EQ(t.weight.size(), 0);
  EXPECT_TRUE(same_bits(s.gap_pointwise, t.gap_pointwise));
  EXPECT_TRUE(m.valid);
  EXPECT_TRUE(m == l);

  // Every truncation, and one byte too many, is refused.
  for (std::size_t n = 0; n < bytes.size(); n += 7) {
    const std::vector<char> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_THROW(offline::unpack_solved(cut, index, t, m), contactrb::Error) << n;
  }
  std::vector<char> longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(offline::unpack_solved(longer, index, t, m), contactrb::Error);
  // A huge array length is refused before anything is allocated.
  std::vector<char> huge = bytes;
  const std::uint64_t big = std::numeric_limits<std::uint64_t>::max() / 2;
  std::memcpy(huge.data() + 8, &big, sizeof big);  // the length of mu
  EXPECT_THROW(offline::unpack_solved(huge, index, t, m), contactrb::Error);
}

TEST(SnapshotWire, TaskRoundTrip) {
  io::Snapshot start;
  start.converged = true;
  start.u = Eigen::VectorXd::Random(5);
  start.lambda = Eigen::VectorXd::Random(2);
  std::uint64_t index = 0;
  bool has = false;
  io::Snapshot got;
  offline::unpack_task(offline::pack_task(7, &start), index, has, got);
  EXPECT_EQ(index, 7u);
  EXPECT_TRUE(has);
  EXPECT_TRUE(got.converged);
  EXPECT_TRUE(same_bits(start.u, got.u));
  EXPECT_TRUE(same_bits(start.lambda, got.lambda));
  offline::unpack_task(offline::pack_task(3, nullptr), index, has, got);
  EXPECT_EQ(index, 3u);
  EXPECT_FALSE(has);
  EXPECT_EQ(got.u.size(), 0);
}
