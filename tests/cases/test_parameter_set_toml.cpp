// The [sets] forms of a TOML case file in p dimensions (parameter_set_toml.hpp): each form
// gives the points of the corresponding function, and each mistake one message naming the
// file, the line and the dotted key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <toml++/toml.h>
#include <unistd.h>

#include "contactrb/cases/parameter_set_toml.hpp"
#include "contactrb/cases/parameter_sets.hpp"
#include "contactrb/common/error.hpp"

using namespace contactrb;
using cases::ParameterBox;
using Eigen::VectorXd;
namespace fs = std::filesystem;

namespace {

const std::string kOrigin = "/nowhere/case.toml";

VectorXd vec(std::initializer_list<double> v) {
  VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const double d : v) x[i++] = d;
  return x;
}

ParameterBox box2() { return {{"a", "b"}, vec({0.0, 1.0}), vec({1.0, 2.0})}; }
ParameterBox box3() { return {{"a", "b", "c"}, vec({0.0, 1.0, 3.0}), vec({1.0, 2.0, 3.0})}; }  // c frozen
ParameterBox box1() { return {{"mu"}, vec({0.15}), vec({0.45})}; }

// The set `sets.training` of a document whose text follows two lines ("# case", "[sets]"),
// so that `training = ...` is on line 3.
std::vector<VectorXd> read_set(const std::string& body, const ParameterBox& box,
                               const fs::path& base_dir = "/nowhere") {
  const toml::table root = toml::parse("# case\n[sets]\n" + body + "\n", kOrigin);
  const toml::node* node = root["sets"]["training"].node();
  if (node == nullptr) throw std::runtime_error("test bug: no sets.training in: " + body);
  return cases::parameter_set_from_toml(*node, box, base_dir, "sets.training", kOrigin);
}

std::vector<VectorXd> training(const std::string& value, const ParameterBox& box) {
  return read_set("training = " + value, box);
}

std::string error_of(const std::string& body, const ParameterBox& box, const fs::path& base_dir = "/nowhere") {
  try {
    read_set(body, box, base_dir);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string training_error(const std::string& value, const ParameterBox& box) {
  return error_of("training = " + value, box);
}

void expect_mentions(const std::string& message, std::initializer_list<const char*> words) {
  for (const char* w : words) EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' not in: " << message;
}

}  // namespace

TEST(ParameterSetToml, GridOfCountsExplicitAxesOrBoth) {
  const std::vector<VectorXd> g = training("{ grid = [3, 2] }", box2());
  ASSERT_EQ(g.size(), 6u);
  EXPECT_EQ(g[0], vec({0.0, 1.0}));
  EXPECT_EQ(g[1], vec({0.5, 1.0}));  // the first parameter varies fastest
  EXPECT_EQ(g[3], vec({0.0, 2.0}));
  EXPECT_EQ(g[5], vec({1.0, 2.0}));

  const std::vector<VectorXd> e = training("{ grid = [[0.1, 0.2], [1, 1.5, 2]] }", box2());
  ASSERT_EQ(e.size(), 6u);
  EXPECT_EQ(e[1], vec({0.2, 1.0}));
  EXPECT_EQ(e[4], vec({0.1, 2.0}));

  EXPECT_EQ(training("{ grid = [2, [1.5]] }", box2()), (std::vector<VectorXd>{vec({0, 1.5}), vec({1, 1.5})}));
  // A count of 1 is the midpoint; a frozen parameter takes its value.
  EXPECT_EQ(training("{ grid = [1, 1, 1] }", box3()), std::vector<VectorXd>{vec({0.5, 1.5, 3.0})});
  // A [sets.training] table is the same as an inline one.
  EXPECT_EQ(read_set("[sets.training]\ngrid = [3, 2]", box2()), g);
}

TEST(ParameterSetToml, RandomFormsEqualTheFunctionsWithTheSeed) {
  const ParameterBox box = box3();
  EXPECT_EQ(training("{ latin-hypercube = 20, seed = 4 }", box), cases::latin_hypercube(box, 20, 4));
  EXPECT_EQ(training("{ latin-hypercube = 20 }", box), cases::latin_hypercube(box, 20, 1));  // default seed 1
  EXPECT_EQ(training("{ random = 7, seed = 0 }", box), cases::uniform_random(box, 7, 0));
  EXPECT_EQ(training("{ random = 7 }", box), cases::uniform_random(box, 7, 1));
  EXPECT_NE(training("{ random = 7, seed = 2 }", box), training("{ random = 7, seed = 3 }", box));
}

TEST(ParameterSetToml, ListedPoints) {
  const std::vector<VectorXd> expected = {vec({0.2, 1.0}), vec({0.3, 1.2})};
  EXPECT_EQ(training("{ points = [[0.2, 1.0], [0.3, 1.2]] }", box2()), expected);
  EXPECT_EQ(training("[[0.2, 1], [0.3, 1.2]]", box2()), expected);  // an integer is a number
  // One parameter: bare numbers, one-element arrays, or both.
  const std::vector<VectorXd> one = {vec({0.15}), vec({0.2}), vec({0.45})};
  EXPECT_EQ(training("[0.15, 0.2, 0.45]", box1()), one);
  EXPECT_EQ(training("{ points = [[0.15], 0.2, [0.45]] }", box1()), one);
}

TEST(ParameterSetToml, FileIsRelativeToTheBaseDirectory) {
  const fs::path dir = fs::temp_directory_path() / ("contactrb_set_toml_" + std::to_string(::getpid()));
  fs::create_directories(dir / "data");
  { std::ofstream(dir / "data" / "p.csv") << "b,a\n1.5,0.25\n2,1\n"; }
  { std::ofstream(dir / "data" / "bad.csv") << "b,a\n1.5,0.25\n2,7\n"; }
  EXPECT_EQ(read_set("training = { file = \"data/p.csv\" }", box2(), dir),
            (std::vector<VectorXd>{vec({0.25, 1.5}), vec({1, 2})}));
  EXPECT_EQ(read_set("training = { file = \"" + (dir / "data" / "p.csv").string() + "\" }", box2(), "/elsewhere")
                .size(),
            2u);  // an absolute path is kept
  expect_mentions(error_of("training = { file = \"data/bad.csv\" }", box2(), dir),
                  {"case.toml:3:", "sets.training.file", "bad.csv:3:", "parameter 'a' = 7", "[0, 1]"});
  expect_mentions(error_of("training = { file = \"data/none.csv\" }", box2(), dir),
                  {"case.toml:3:", "sets.training.file", "none.csv", "does not exist"});
  fs::remove_all(dir);
}

TEST(ParameterSetToml, FormMistakes) {
  const ParameterBox box = box2();
  expect_mentions(training_error("\"grid\"", box),
                  {"case.toml:3:", "key 'sets.training' must be a table", "or an array of points", "got a string"});
  expect_mentions(training_error("{ grid = [2, 2], step = 1 }", box),
                  {"case.toml:3:", "unknown key 'sets.training.step'", "allowed: grid, latin-hypercube"});
  expect_mentions(training_error("{ grid = [2, 2], random = 3 }", box), {"both 'grid' and 'random'"});
  expect_mentions(training_error("{ seed = 3 }", box), {"case.toml:3:", "'sets.training' needs one of grid"});
  expect_mentions(error_of("[sets.training]\ngrid = [2, 2]\nseed = 5", box),
                  {"case.toml:5:", "'sets.training.seed' needs latin-hypercube or random, not grid"});
  expect_mentions(training_error("{ random = 3, seed = -1 }", box), {"'sets.training.seed' must be >= 0, got -1"});
  expect_mentions(training_error("{ random = 3, seed = 1.5 }", box), {"'sets.training.seed' must be an integer"});
}

TEST(ParameterSetToml, GridMistakes) {
  const ParameterBox box = box2();
  expect_mentions(training_error("{ grid = 5 }", box),
                  {"case.toml:3:", "'sets.training.grid' must be an array of 2 counts", "'a', 'b'", "got an integer"});
  expect_mentions(training_error("{ grid = [5] }", box),
                  {"'sets.training.grid' must be an array of 2", "got 1 entries"});
  expect_mentions(training_error("{ grid = [5, 0] }", box),
                  {"case.toml:3:", "'sets.training.grid[2]' must be in [1, 10000000], got 0"});
  expect_mentions(training_error("{ grid = [2.5, 2] }", box),
                  {"'sets.training.grid[1]' must be a count (an integer) or an array of values of parameter 'a'",
                   "got a float"});
  expect_mentions(training_error("{ grid = [2, 2, 3] }", box3()),
                  {"'sets.training.grid[3]' = 3, but parameter 'c' has the single value 3: use 1"});
  expect_mentions(training_error("{ grid = [2, []] }", box), {"'sets.training.grid[2]' holds no value"});
  expect_mentions(training_error("{ grid = [[0.5, 0.5], 2] }", box),
                  {"'sets.training.grid[1]' must be strictly increasing", "value 2 (0.5) is not above value 1 (0.5)"});
  expect_mentions(training_error("{ grid = [2, [1.5, 2.5]] }", box),
                  {"'sets.training.grid[2][2]'", "parameter 'b' = 2.5 is outside its domain [1, 2]"});
  expect_mentions(training_error("{ grid = [5000, 5000, 3] }", box3()), {"(5000 x 5000 x ...)"});
  expect_mentions(training_error("{ grid = [4000, 4000] }", box),
                  {"case.toml:3:", "'sets.training.grid' gives more than 10000000 points (4000 x 4000)"});
}

TEST(ParameterSetToml, CountMistakes) {
  const ParameterBox box = box2();
  expect_mentions(training_error("{ latin-hypercube = 0 }", box),
                  {"case.toml:3:", "'sets.training.latin-hypercube' must be in [1, 10000000], got 0"});
  expect_mentions(training_error("{ random = 100000000 }", box), {"'sets.training.random' must be in [1, 10000000]"});
  expect_mentions(training_error("{ random = 1e3 }", box), {"'sets.training.random' must be an integer, got a float"});
  // Every parameter frozen: two points of a Latin hypercube are the same point.
  const ParameterBox frozen{{"a"}, vec({1.0}), vec({1.0})};
  expect_mentions(training_error("{ latin-hypercube = 2 }", frozen),
                  {"case.toml:3:", "key 'sets.training': point 2 repeats point 1"});
  EXPECT_EQ(training("{ latin-hypercube = 1 }", frozen), std::vector<VectorXd>{vec({1.0})});
}

TEST(ParameterSetToml, FileMistakes) {
  expect_mentions(training_error("{ file = 3 }", box2()), {"'sets.training.file' must be a string", "got an integer"});
  expect_mentions(training_error("{ file = \"\" }", box2()), {"'sets.training.file' is empty"});
}

TEST(ParameterSetToml, PointMistakesNameTheElementAndItsLine) {
  const ParameterBox box = box2();
  expect_mentions(training_error("{ points = [] }", box), {"case.toml:3:", "'sets.training.points' holds no point"});
  expect_mentions(training_error("{ points = 0.5 }", box), {"'sets.training.points' must be an array of points"});
  expect_mentions(training_error("[[0.2, 1.0], [0.3]]", box),
                  {"'sets.training[2]' must be an array of 2 numbers ('a', 'b'), got 1 values"});
  expect_mentions(training_error("[[0.2, 1.0], 0.3]", box),
                  {"'sets.training[2]' must be an array of 2", "got a float"});
  expect_mentions(training_error("[[0.2, \"x\"]]", box), {"'sets.training[1][2]' must be a number, got a string"});
  expect_mentions(training_error("[0.5]", box1()), {"'sets.training[1]': parameter 'mu' = 0.5", "[0.15, 0.45]"});
  const std::string multiline = "training = [\n  [0.2, 1.0],\n  [0.3, 1.0],\n  [0.3, 5.0],\n]";
  expect_mentions(error_of(multiline, box),
                  {"case.toml:6:", "'sets.training[3][2]': parameter 'b' = 5 is outside its domain [1, 2]"});
  const std::string repeated = "training = { points = [\n  [0.2, 1.0],\n  [0.3, 1.0],\n  [0.2, 1]] }";
  // An inline table spans one line in TOML 1.0; toml++ accepts the array's newlines inside it.
  expect_mentions(error_of(repeated, box), {"'sets.training.points[3]' repeats 'sets.training.points[1]'"});
  expect_mentions(error_of("training = [\n  [0.2, 1.0],\n  [0.3, 1.0],\n  [0.2, 1]]", box),
                  {"case.toml:6:", "'sets.training[3]' repeats 'sets.training[1]'"});
}

TEST(ParameterSetToml, InvalidBoxIsNamed) {
  ParameterBox box = box2();
  box.min[0] = 2.0;
  expect_mentions(training_error("[[0.2, 1.0]]", box), {"case.toml", "inverted", "sets.training"});
}
