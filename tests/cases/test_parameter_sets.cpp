// Parameter sets in p dimensions: the box checks, uniform axes and tensor grids (size, order,
// exact bounds), the seeded Latin hypercube and random sets (strata, determinism, golden
// values, statistics), CSV files of points (round trip, header forms, every error), the
// point checks and the scaled nearest point.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

#include "contactrb/cases/parameter_sets.hpp"
#include "contactrb/common/error.hpp"

using namespace contactrb;
using cases::ParameterBox;
using Eigen::VectorXd;
namespace fs = std::filesystem;

namespace {

VectorXd vec(std::initializer_list<double> v) {
  VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const double d : v) x[i++] = d;
  return x;
}

// Three parameters: a in [0, 1], b in [10, 20], c frozen at 3.
ParameterBox box3() { return {{"a", "b", "c"}, vec({0.0, 10.0, 3.0}), vec({1.0, 20.0, 3.0})}; }
ParameterBox box2() { return {{"a", "b"}, vec({0.0, 1.0}), vec({1.0, 2.0})}; }

void expect_mentions(const std::string& message, std::initializer_list<const char*> words) {
  for (const char* w : words) EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' not in: " << message;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A scratch directory per process, removed at the end of each test that uses it.
class CsvFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("contactrb_param_sets_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string read_error(const std::string& text, const ParameterBox& box) const {
    const std::string path = write("p.csv", text);
    return error_of([&] { cases::read_points_csv(path, box); });
  }
  fs::path dir_;
};

}  // namespace

TEST(ParameterBox, ChecksEveryField) {
  EXPECT_NO_THROW(cases::check_parameter_box(box3(), "here"));  // a frozen parameter is fine
  ParameterBox b = box2();
  b.names.clear();
  expect_mentions(error_of([&] { cases::check_parameter_box(b, "here"); }), {"here", "no parameter"});
  b = box2();
  b.max = vec({1.0});
  expect_mentions(error_of([&] { cases::check_parameter_box(b, "here"); }), {"2 names", "2 min", "1 max"});
  b = box2();
  b.names[1] = "";
  expect_mentions(error_of([&] { cases::check_parameter_box(b, "here"); }), {"parameter 2", "empty name"});
  b = box2();
  b.names[1] = "a";
  expect_mentions(error_of([&] { cases::check_parameter_box(b, "here"); }), {"'a'", "twice"});
  b = box2();
  b.max[0] = INFINITY;
  expect_mentions(error_of([&] { cases::check_parameter_box(b, "here"); }), {"'a'", "non-finite", "inf"});
  b = box2();
  b.min[1] = 3.0;
  expect_mentions(error_of([&] { cases::check_parameter_box(b, "here"); }), {"'b'", "inverted", "[3, 2]"});
}

TEST(UniformAxis, EndsExactlyAtTheBounds) {
  EXPECT_EQ(cases::uniform_axis(1.0, 3.0, 1), std::vector<double>{2.0});
  EXPECT_EQ(cases::uniform_axis(0.0, 1.0, 5), (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  // 0.1 + 0.6 * 6 / 6 is not 0.7 in floating point; the last value is set to max.
  const std::vector<double> v = cases::uniform_axis(0.1, 0.7, 7);
  ASSERT_EQ(v.size(), 7u);
  EXPECT_EQ(v.front(), 0.1);
  EXPECT_EQ(v.back(), 0.7);
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_NEAR(v[i], 0.1 + 0.1 * static_cast<double>(i), 1e-15);
    EXPECT_LE(v[i], 0.7);
  }
  EXPECT_EQ(cases::uniform_axis(2.0, 2.0, 1), std::vector<double>{2.0});
  expect_mentions(error_of([] { cases::uniform_axis(0, 1, 0); }), {"count", ">= 1", "0"});
  expect_mentions(error_of([] { cases::uniform_axis(1, 0, 3); }), {"min <= max", "[1, 0]"});
  expect_mentions(error_of([] { cases::uniform_axis(0, NAN, 3); }), {"finite"});
}

TEST(TensorGrid, FirstParameterVariesFastest) {
  const std::vector<VectorXd> g = cases::tensor_grid({{1, 2, 3}, {10, 20}, {-1}});
  ASSERT_EQ(g.size(), 6u);
  const double expected[6][3] = {{1, 10, -1}, {2, 10, -1}, {3, 10, -1}, {1, 20, -1}, {2, 20, -1}, {3, 20, -1}};
  for (std::size_t i = 0; i < 6; ++i) {
    ASSERT_EQ(g[i].size(), 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(g[i][k], expected[i][k]) << "point " << i << " parameter " << k;
  }
  // Grid of uniform axes: size is the product and the corners are the box's corners exactly.
  const std::vector<VectorXd> u =
      cases::tensor_grid({cases::uniform_axis(0.1, 0.7, 7), cases::uniform_axis(1.0, 2.0, 4)});
  ASSERT_EQ(u.size(), 28u);
  EXPECT_EQ(u.front(), vec({0.1, 1.0}));
  EXPECT_EQ(u[6], vec({0.7, 1.0}));
  EXPECT_EQ(u.back(), vec({0.7, 2.0}));
  EXPECT_NO_THROW(cases::check_points(u, {{"x", "y"}, vec({0.1, 1.0}), vec({0.7, 2.0})}, "grid"));
}

TEST(TensorGrid, RefusesEmptyAndHugeGrids) {
  expect_mentions(error_of([] { cases::tensor_grid({}); }), {"no axis"});
  expect_mentions(error_of([] { cases::tensor_grid({{1.0}, {}}); }), {"axis 2", "empty"});
  const std::vector<double> big(4000, 0.0);  // 4000^2 = 1.6e7 > 1e7: refused before allocating
  expect_mentions(error_of([&] { cases::tensor_grid({big, big}); }), {"more than 10000000"});
}

TEST(LatinHypercube, EachStratumOfEachParameterHoldsOnePoint) {
  const ParameterBox box = box3();
  for (const int n : {1, 7, 100}) {
    const std::vector<VectorXd> pts = cases::latin_hypercube(box, n, 42);
    ASSERT_EQ(pts.size(), static_cast<std::size_t>(n));
    for (int k = 0; k < 2; ++k) {
      std::vector<int> hits(static_cast<std::size_t>(n), 0);
      for (const VectorXd& mu : pts) {
        const double t = (mu[k] - box.min[k]) / (box.max[k] - box.min[k]);
        ASSERT_GE(t, 0.0);
        ASSERT_LE(t, 1.0);
        ++hits[static_cast<std::size_t>(std::min(n - 1, static_cast<int>(std::floor(t * n))))];
      }
      for (int j = 0; j < n; ++j) EXPECT_EQ(hits[static_cast<std::size_t>(j)], 1) << "n " << n << " stratum " << j;
    }
    for (const VectorXd& mu : pts) EXPECT_EQ(mu[2], 3.0);  // the frozen parameter
  }
}

TEST(LatinHypercube, SameSeedSamePointsOtherSeedOtherPoints) {
  const std::vector<VectorXd> a = cases::latin_hypercube(box3(), 50, 9);
  const std::vector<VectorXd> b = cases::latin_hypercube(box3(), 50, 9);
  const std::vector<VectorXd> c = cases::latin_hypercube(box3(), 50, 10);
  EXPECT_EQ(a, b);
  int same = 0;
  for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == c[i] ? 1 : 0;
  EXPECT_EQ(same, 0);
  // Freezing a parameter leaves the other coordinates unchanged (its draws are still made).
  ParameterBox frozen = box3();
  frozen.max[0] = frozen.min[0];
  const std::vector<VectorXd> f = cases::latin_hypercube(frozen, 50, 9);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(f[i][0], 0.0);
    EXPECT_EQ(f[i][1], a[i][1]);
  }
}

// The engine is the standard's: its 10000th output from the default seed is fixed by
// [rand.predef]. The golden points below then catch any change of our conversions or draw
// order, on this or another platform.
TEST(RandomSets, GoldenValues) {
  std::mt19937_64 engine;
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ull);

  const ParameterBox box = box2();
  const VectorXd lhs = cases::latin_hypercube(box, 10, 1).front();
  EXPECT_EQ(lhs[0], 0x1.4ee535e33e9d3p-3) << std::hexfloat << lhs[0];
  EXPECT_EQ(lhs[1], 0x1.de95fc31a4872p+0) << std::hexfloat << lhs[1];
  const VectorXd rnd = cases::uniform_random(box, 10, 1).front();
  EXPECT_EQ(rnd[0], 0x1.122deafddb434p-3) << std::hexfloat << rnd[0];
  EXPECT_EQ(rnd[1], 0x1.22eb92502319p+0) << std::hexfloat << rnd[1];
  // The documented conversion, from the engine directly: (x >> 11) 2^-53 scaled to the domain.
  std::mt19937_64 e1(1);
  const double u0 = static_cast<double>(e1() >> 11) * 0x1.0p-53;
  const double u1 = static_cast<double>(e1() >> 11) * 0x1.0p-53;
  EXPECT_EQ(rnd[0], u0);
  EXPECT_EQ(rnd[1], 1.0 + u1);
}

TEST(RandomSets, UniformPointsAreInsideTheBoxWithTheRightMean) {
  const ParameterBox box = box3();
  const int n = 20000;
  const std::vector<VectorXd> pts = cases::uniform_random(box, n, 7);
  ASSERT_EQ(pts.size(), static_cast<std::size_t>(n));
  VectorXd mean = VectorXd::Zero(3);
  for (const VectorXd& mu : pts) {
    ASSERT_EQ(mu.size(), 3);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(mu[k], box.min[k]);
      EXPECT_LE(mu[k], box.max[k]);
    }
    mean += mu;  // summed, then divided: the frozen coordinate stays exact
  }
  mean /= n;
  // The sample mean of n uniforms on [a, b] has standard deviation (b - a) / sqrt(12 n):
  // 5 of them is passed by chance with probability 6e-7, and a fixed seed makes it repeatable.
  for (int k = 0; k < 2; ++k) {
    const double sd = (box.max[k] - box.min[k]) / std::sqrt(12.0 * n);
    EXPECT_NEAR(mean[k], 0.5 * (box.min[k] + box.max[k]), 5 * sd) << "parameter " << k;
  }
  EXPECT_EQ(mean[2], 3.0);
  EXPECT_NE(cases::uniform_random(box, 5, 7)[0], cases::uniform_random(box, 5, 8)[0]);
  EXPECT_EQ(cases::uniform_random(box, 5, 7)[4], pts[4]);  // the first points do not depend on n
}

TEST(RandomSets, RefuseBadSizes) {
  expect_mentions(error_of([] { cases::latin_hypercube(box2(), 0, 1); }), {"latin_hypercube", "[1, 10000000]", "0"});
  expect_mentions(error_of([] { cases::uniform_random(box2(), -3, 1); }), {"uniform_random", "-3"});
  ParameterBox bad = box2();
  bad.min[0] = 2.0;
  expect_mentions(error_of([&] { cases::uniform_random(bad, 3, 1); }), {"inverted"});
}

TEST(CheckPoints, NamesThePointAndTheParameter) {
  const ParameterBox box = box2();
  EXPECT_NO_THROW(cases::check_points({vec({0, 1}), vec({1, 2})}, box, "set"));
  expect_mentions(error_of([&] { cases::check_points({}, box, "set 'x'"); }), {"set 'x'", "empty"});
  expect_mentions(error_of([&] { cases::check_points({vec({0, 1}), vec({0.5})}, box, "set"); }),
                  {"point 2", "1 values, expected 2"});
  expect_mentions(error_of([&] { cases::check_points({vec({0, NAN})}, box, "set"); }),
                  {"point 1", "'b'", "nan", "not a finite"});
  expect_mentions(error_of([&] { cases::check_points({vec({0, 1}), vec({0, 2.5})}, box, "set"); }),
                  {"point 2", "'b' = 2.5", "outside", "[1, 2]"});
  const std::vector<VectorXd> rep = {vec({0, 1}), vec({0.5, 1}), vec({0.2, 1}), vec({0.5, 1}), vec({0, 1})};
  // Points 4 (= 2) and 5 (= 1) both repeat; the earliest repeat is named.
  expect_mentions(error_of([&] { cases::check_points(rep, box, "set"); }), {"point 4 repeats point 2"});
}

TEST(Scaled, DistanceAndNearestPoint) {
  const ParameterBox box = box3();  // widths 1, 10, and c frozen
  EXPECT_EQ(cases::scaled(vec({0.25, 15.0, 3.0}), box), vec({0.25, 0.5, 0.0}));
  EXPECT_EQ(cases::scaled(std::vector<VectorXd>{vec({1, 10, 3})}, box).front(), vec({1.0, 0.0, 0.0}));
  // (0.3, 4 / 10) -> 0.5; the frozen coordinate counts 0 even when mu is off it.
  EXPECT_DOUBLE_EQ(cases::scaled_distance(vec({0.1, 11, 3}), vec({0.4, 15, 7}), box), 0.5);

  const std::vector<VectorXd> pts = {vec({0.0, 10, 3}), vec({1.0, 10, 3}), vec({0.5, 20, 3}), vec({0.5, 12, 3})};
  // Scaled squared distances from (0.9, 12): 0.85, 0.05, 0.8, 0.16. In raw units point 3
  // (0.4 away in a) would beat point 1 (2 away in b).
  EXPECT_EQ(cases::nearest_point(pts, vec({0.9, 12, 3}), box), 1);
  EXPECT_EQ(cases::nearest_point(pts, vec({0.9, 18, 3}), box), 2);
  EXPECT_EQ(cases::nearest_point(pts, vec({0.6, 12.5, 3}), box), 3);
  // Equidistant from points 0 and 1 (0.61, point 3 at 0.64): the smaller index, in either order.
  EXPECT_EQ(cases::nearest_point(pts, vec({0.5, 4, 3}), box), 0);
  EXPECT_EQ(cases::nearest_point({pts[1], pts[0], pts[3]}, vec({0.5, 4, 3}), box), 0);
  EXPECT_EQ(cases::nearest_point(pts, vec({-5, 10, 3}), box), 0);  // outside the box is fine
  expect_mentions(error_of([&] { cases::nearest_point({}, vec({0, 10, 3}), box); }), {"no point"});
  expect_mentions(error_of([&] { cases::nearest_point(pts, vec({0, 10}), box); }), {"2 values, expected 3"});
  expect_mentions(error_of([&] { cases::nearest_point(pts, vec({NAN, 10, 3}), box); }), {"non-finite"});
  expect_mentions(error_of([&] { cases::scaled_distance(vec({0}), vec({0, 10, 3}), box); }), {"1 values"});
}

TEST_F(CsvFiles, RoundTripWithAwkwardNames) {
  const ParameterBox box{{"load, scaled", "say \"E\"", "#1"}, vec({0, 1, -1}), vec({1, 2, 1})};
  const std::vector<VectorXd> pts = cases::latin_hypercube(box, 20, 3);
  const std::string text = cases::points_csv_text(pts, box);
  EXPECT_EQ(text.substr(0, text.find('\n')), R"("load, scaled","say ""E""","#1")");
  EXPECT_EQ(cases::read_points_csv(write("rt.csv", text), box), pts);  // shortest round-trip text: exact
}

TEST_F(CsvFiles, HeaderInAnyOrderCommentsBlanksAndCrlf) {
  const ParameterBox box = box3();
  const std::string path = write("p.csv",
                                 "# measured points\r\n"
                                 "\r\n"
                                 "  c ,b,a\r\n"
                                 "3, 12.5, 0.25\r\n"
                                 "   # a comment between points\n"
                                 "\n"
                                 "3,+20,1e-1\n"
                                 "3,10,0");  // no final newline
  const std::vector<VectorXd> pts = cases::read_points_csv(path, box);
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_EQ(pts[0], vec({0.25, 12.5, 3}));
  EXPECT_EQ(pts[1], vec({0.1, 20, 3}));
  EXPECT_EQ(pts[2], vec({0, 10, 3}));
}

TEST_F(CsvFiles, WithoutHeaderTheColumnsAreInParameterOrder) {
  EXPECT_EQ(cases::read_points_csv(write("p.csv", "0.5, 1.5\n1,2\n"), box2()),
            (std::vector<VectorXd>{vec({0.5, 1.5}), vec({1, 2})}));
  const ParameterBox one{{"mu"}, vec({0.15}), vec({0.45})};
  EXPECT_EQ(cases::read_points_csv(write("q.csv", "0.15\n0.2\n0.45\n"), one),
            (std::vector<VectorXd>{vec({0.15}), vec({0.2}), vec({0.45})}));
  EXPECT_EQ(cases::read_points_csv(write("r.csv", "mu\n0.3\n"), one), std::vector<VectorXd>{vec({0.3})});
  // A quoted field makes the line a header, so that a name reading as a number can be used.
  const ParameterBox numeric{{"1"}, vec({0.0}), vec({1.0})};
  EXPECT_EQ(cases::read_points_csv(write("s.csv", "\"1\"\n0.5\n"), numeric), std::vector<VectorXd>{vec({0.5})});
}

TEST_F(CsvFiles, HeaderMistakesAreNamedTogether) {
  const std::string m = read_error("# c\nb, d, b, e\n0.5, 1, 1, 1\n", box3());
  expect_mentions(m, {"p.csv:2:", "exactly once", "missing: 'a', 'c'", "unknown: 'd', 'e'", "repeated: 'b'"});
  expect_mentions(read_error("0.5, x\n", box2()), {"p.csv:1:", "unknown: '0.5', 'x'", "read as a header"});
  expect_mentions(read_error("\"a, b\n", box2()), {"p.csv:1:", "no closing quote"});
  expect_mentions(read_error("\"a\" x, b\n", box2()), {"p.csv:1:", "text after the quoted field \"a\""});
}

TEST_F(CsvFiles, ValueMistakesNameTheLineAndTheParameter) {
  const ParameterBox box = box2();
  expect_mentions(read_error("b,a\n1.5,0.5\n1.5\n", box), {"p.csv:3:", "1 values, expected 2", "'a', 'b'"});
  expect_mentions(read_error("b,a\n1.5,0.5,1\n", box), {"p.csv:2:", "3 values, expected 2"});
  expect_mentions(read_error("b,a\n1.5, 0.5x\n", box), {"p.csv:2:", "parameter 'a'", "'0.5x'", "not a number"});
  // File content echoed in a message is made printable (no terminal escape sequences).
  const std::string esc = read_error("b,a\n1.5,\x1b[2J\n", box);
  expect_mentions(esc, {"p.csv:2:", "'\\x1b[2J'", "not a number"});
  EXPECT_EQ(esc.find('\x1b'), std::string::npos);
  expect_mentions(read_error("b,a\n1.5,\n", box), {"p.csv:2:", "parameter 'a'", "''", "not a number"});
  expect_mentions(read_error("b,a\n\n1.5,nan\n", box), {"p.csv:3:", "parameter 'a' is nan", "not a finite"});
  expect_mentions(read_error("b,a\n2.5,0.5\n", box), {"p.csv:2:", "parameter 'b' = 2.5", "outside", "[1, 2]"});
  expect_mentions(read_error("0,1\n#\n0.5,1\n\n0,1\n", box), {"p.csv:5:", "repeats the one on line 1"});
}

TEST_F(CsvFiles, EmptyAndMissingFiles) {
  expect_mentions(read_error("", box2()), {"p.csv", "no point"});
  expect_mentions(read_error("# only\n\n  \n", box2()), {"p.csv", "no point"});
  expect_mentions(read_error("a,b\n# nothing\n", box2()), {"p.csv", "no point after the header"});
  const std::string missing = (dir_ / "none.csv").string();
  expect_mentions(error_of([&] { cases::read_points_csv(missing, box2()); }),
                  {"points file", "none.csv", "does not exist"});
}
