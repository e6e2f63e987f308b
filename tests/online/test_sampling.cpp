// online/sampling.hpp: statistics of known data (1..100: mean, sd, quantiles, histogram), the
// points' independence of the order they are drawn in, and the distributions' parsing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/online/sampling.hpp"

namespace online = contactrb::online;
namespace cases = contactrb::cases;

namespace {
// Named as their case names them (a string literal assigned here trips GCC 12's -Wrestrict).
std::vector<cases::ParameterSpec> two_parameters() {
  std::vector<cases::ParameterSpec> p(2);
  p[0].name = std::string(1, 'a');
  p[0].min = 0.0;
  p[0].max = 2.0;
  p[1].name = std::string(1, 'b');
  p[1].min = -1.0;
  p[1].max = -0.5;
  return p;
}
}  // namespace

TEST(Sampling, StatisticsOfOneToHundred) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);  // any order
  v.push_back(std::numeric_limits<double>::quiet_NaN());  // no answer: left out
  const online::OutputStats s = online::output_stats("x", v, 4);
  EXPECT_EQ(s.count, 100u);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
  EXPECT_NEAR(s.sd, std::sqrt(100.0 * 101.0 / 12.0), 1e-12);  // sample sd of 1..n: sqrt(n(n+1)/12)
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 100.0);
  EXPECT_DOUBLE_EQ(s.q05, 1.0 + 0.05 * 99.0);
  EXPECT_DOUBLE_EQ(s.q50, 50.5);
  EXPECT_DOUBLE_EQ(s.q95, 1.0 + 0.95 * 99.0);
  // Bins of width 24.75 over [1, 100]: 1..25, 26..50, 51..75, 76..100.
  EXPECT_EQ(s.histogram, (std::vector<std::size_t>{25, 25, 25, 25}));
  const online::OutputStats same = online::output_stats("x", {3.0, 3.0}, 10);
  EXPECT_EQ(same.histogram, std::vector<std::size_t>{2});
  EXPECT_EQ(online::output_stats("x", {}, 3).count, 0u);
  EXPECT_THROW(online::output_stats("x", v, 0), contactrb::Error);
}

TEST(Sampling, PointsDependOnSeedAndIndexOnly) {
  const auto p = two_parameters();
  const online::SampleDistribution u = online::parse_distribution("uniform", p);
  const online::SampleDistribution n = online::parse_distribution("normal:1.5:0.3,-0.8:0.05", p);
  for (const online::SampleDistribution* d : {&u, &n}) {
    double mean_a = 0.0;
    for (std::uint64_t i = 0; i < 4000; ++i) {
      const cases::Mu x = online::sample_point(*d, p, 7, i);
      ASSERT_EQ(x.size(), 2);
      EXPECT_GE(x(0), 0.0);
      EXPECT_LE(x(0), 2.0);
      EXPECT_GE(x(1), -1.0);
      EXPECT_LE(x(1), -0.5);
      mean_a += x(0) / 4000.0;
    }
    // Uniform on [0, 2]: 1 (standard error 0.009); normal(1.5, 0.3) truncated at 2 (1.67 sd):
    // 1.5 - 0.3 phi(1.667) / Phi(1.667) = 1.4686 (standard error 0.005).
    EXPECT_NEAR(mean_a, d == &u ? 1.0 : 1.4686, 0.03);
  }
  // Drawn backwards or forwards, the same point.
  EXPECT_EQ(online::sample_point(u, p, 7, 123), online::sample_point(u, p, 7, 123));
  EXPECT_NE(online::sample_point(u, p, 7, 123), online::sample_point(u, p, 8, 123));
  EXPECT_NE(online::sample_point(u, p, 7, 123), online::sample_point(u, p, 7, 124));
}

TEST(Sampling, DistributionErrors) {
  const auto p = two_parameters();
  const online::SampleDistribution d = online::parse_distribution("normal", p);
  EXPECT_DOUBLE_EQ(d.mean[0], 1.0);
  EXPECT_DOUBLE_EQ(d.sd[0], 2.0 / 6.0);
  for (const char* bad : {"gauss", "normal:1", "normal:1:0.1", "normal:1:0.1,x:0.1", "normal:3:0.1,-0.8:0.1",
                          "normal:1:-1,-0.8:0.1", "normal:1:0.1,-0.8:nan", "normal:1:0.1,-0.8:0.1,"}) {
    EXPECT_THROW(online::parse_distribution(bad, p), contactrb::Error) << bad;
  }
}
