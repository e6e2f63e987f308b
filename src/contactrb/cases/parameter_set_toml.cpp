#include "contactrb/cases/parameter_set_toml.hpp"

#include <sstream>

#include "contactrb/cases/parameter_sets_detail.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/printable.hpp"

namespace contactrb::cases {

namespace {

namespace fs = std::filesystem;

// The keys of a set's table that choose its form; exactly one is given.
constexpr const char* kForms[] = {"grid", "latin-hypercube", "random", "file", "points"};

// The seed of latin-hypercube and random sets when none is given.
constexpr long long kDefaultSeed = 1;

std::string type_name(const toml::node& n) {
  if (n.is_table()) return "a table";
  if (n.is_array()) return "an array";
  if (n.is_string()) return "a string";
  if (n.is_integer()) return "an integer";
  if (n.is_floating_point()) return "a float";
  if (n.is_boolean()) return "a boolean";
  return "a date/time";
}

// "[1]"-style suffix of the i-th (0-based) array element, counted from 1 as in case_toml.cpp.
std::string element(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i + 1) + "]"; }

class SetReader {
 public:
  SetReader(const ParameterBox& box, fs::path base_dir, std::string origin)
      : box_(box), base_dir_(std::move(base_dir)), origin_(std::move(origin)) {}

  std::vector<Eigen::VectorXd> read(const toml::node& node, const std::string& key) const {
    std::vector<Eigen::VectorXd> points;
    if (node.is_array()) {
      points = listed(node, key);
    } else if (const toml::table* t = node.as_table()) {
      points = from_table(*t, key);
    } else {
      wrong_type(node, key,
                 "a table ({ grid = ... }, { latin-hypercube = n }, { random = n }, { file = \"...\" }, "
                 "{ points = [...] }) or an array of points");
    }
    try {
      check_points(points, box_, "key '" + key + "'");
    } catch (const Error& e) {
      fail(&node, e.what());
    }
    return points;
  }

 private:
  [[noreturn]] void fail(const toml::node* n, const std::string& what) const {
    std::ostringstream os;
    os << origin_;
    if (n != nullptr && n->source().begin.line > 0) os << ":" << n->source().begin.line;
    os << ": " << what;
    throw Error(os.str());
  }

  [[noreturn]] void wrong_type(const toml::node& n, const std::string& key, const std::string& expected) const {
    fail(&n, "key '" + key + "' must be " + expected + ", got " + type_name(n));
  }

  std::string names() const {
    std::string s;
    for (const std::string& n : box_.names) s += (s.empty() ? "'" : ", '") + n + "'";
    return s;
  }

  // An integer in [1, kMaxParameterSetSize].
  int count(const toml::node& n, const std::string& key) const {
    const auto* i = n.as_integer();
    if (i == nullptr) wrong_type(n, key, "an integer");
    if (i->get() < 1 || i->get() > kMaxParameterSetSize) {
      fail(&n, "key '" + key + "' must be in [1, " + std::to_string(kMaxParameterSetSize) + "], got " +
                   std::to_string(i->get()));
    }
    return static_cast<int>(i->get());
  }

  double number(const toml::node& n, const std::string& key) const {
    if (const auto* f = n.as_floating_point()) return f->get();
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    wrong_type(n, key, "a number");
  }

  // Value of parameter k, inside its domain.
  double value(const toml::node& n, const std::string& key, int k) const {
    const double v = number(n, key);
    if (!(v >= box_.min[k] && v <= box_.max[k])) fail(&n, "key '" + key + "': " + detail::value_error(box_, k, v));
    return v;
  }

  std::vector<Eigen::VectorXd> from_table(const toml::table& t, const std::string& key) const {
    const char* form = nullptr;
    for (auto&& [k, v] : t) {
      bool known = k.str() == "seed";
      for (const char* f : kForms) {
        if (k.str() != f) continue;
        known = true;
        if (form != nullptr) {
          fail(&v, "key '" + key + "' has both '" + form + "' and '" + f + "': give one of grid, latin-hypercube, "
                   "random, file, points");
        }
        form = f;
      }
      if (!known) {
        fail(&v, "unknown key '" + key + "." + printable_line(std::string(k.str())) +
                     "' (allowed: grid, latin-hypercube, random, seed, file, points)");
      }
    }
    if (form == nullptr) fail(&t, "key '" + key + "' needs one of grid, latin-hypercube, random, file, points");
    const std::string form_key = key + "." + form;
    const toml::node& value_node = *t.get(form);
    const std::string f = form;
    if (f != "latin-hypercube" && f != "random" && t.contains("seed")) {
      fail(t.get("seed"), "key '" + key + ".seed' needs latin-hypercube or random, not " + f);
    }
    if (f == "grid") return grid(value_node, form_key);
    if (f == "file") return file(value_node, form_key);
    if (f == "points") return listed(value_node, form_key);
    const int n = count(value_node, form_key);
    const std::uint64_t s = seed(t, key);
    return f == "random" ? uniform_random(box_, n, s) : latin_hypercube(box_, n, s);
  }

  std::uint64_t seed(const toml::table& t, const std::string& key) const {
    const toml::node* n = t.get("seed");
    if (n == nullptr) return static_cast<std::uint64_t>(kDefaultSeed);
    const auto* i = n->as_integer();
    if (i == nullptr) wrong_type(*n, key + ".seed", "an integer");
    if (i->get() < 0) fail(n, "key '" + key + ".seed' must be >= 0, got " + std::to_string(i->get()));
    return static_cast<std::uint64_t>(i->get());
  }

  std::vector<Eigen::VectorXd> grid(const toml::node& n, const std::string& key) const {
    const auto* a = n.as_array();
    const std::string expected = "an array of " + std::to_string(box_.size()) +
                                 " counts or value arrays (one per parameter: " + names() + ")";
    if (a == nullptr) wrong_type(n, key, expected);
    if (static_cast<int>(a->size()) != box_.size()) {
      fail(&n, "key '" + key + "' must be " + expected + ", got " + std::to_string(a->size()) + " entries");
    }
    std::vector<std::vector<double>> axes;
    long long total = 1;
    std::string sizes;
    for (std::size_t k = 0; k < a->size(); ++k) {
      axes.push_back(axis(*a->get(k), element(key, k), static_cast<int>(k)));
      total *= static_cast<long long>(axes.back().size());  // each factor <= 1e7, checked at every step
      sizes += (k > 0 ? " x " : "") + std::to_string(axes.back().size());
      if (total > kMaxParameterSetSize) {
        fail(&n, "key '" + key + "' gives more than " + std::to_string(kMaxParameterSetSize) + " points (" + sizes +
                     (k + 1 < a->size() ? " x ..." : "") + ")");
      }
    }
    return tensor_grid(axes);
  }

  // One grid axis: a count of uniform values, or the values themselves.
  std::vector<double> axis(const toml::node& n, const std::string& key, int k) const {
    const std::string& name = box_.names[static_cast<std::size_t>(k)];
    if (n.is_integer()) {
      const int c = count(n, key);
      if (c > 1 && box_.min[k] == box_.max[k]) {
        fail(&n, "key '" + key + "' = " + std::to_string(c) + ", but parameter '" + name + "' has the single value " +
                     detail::shortest(box_.min[k]) + ": use 1");
      }
      return uniform_axis(box_.min[k], box_.max[k], c);
    }
    const auto* a = n.as_array();
    if (a == nullptr) wrong_type(n, key, "a count (an integer) or an array of values of parameter '" + name + "'");
    if (a->empty()) fail(&n, "key '" + key + "' holds no value");
    std::vector<double> v;
    for (std::size_t i = 0; i < a->size(); ++i) {
      v.push_back(value(*a->get(i), element(key, i), k));
      if (i > 0 && !(v[i] > v[i - 1])) {
        fail(a->get(i), "key '" + key + "' must be strictly increasing, but value " + std::to_string(i + 1) + " (" +
                            detail::shortest(v[i]) + ") is not above value " + std::to_string(i) + " (" +
                            detail::shortest(v[i - 1]) + ")");
      }
    }
    return v;
  }

  std::vector<Eigen::VectorXd> file(const toml::node& n, const std::string& key) const {
    const auto* s = n.as_string();
    if (s == nullptr) wrong_type(n, key, "a string (a CSV file's path)");
    if (s->get().empty()) fail(&n, "key '" + key + "' is empty");
    fs::path p(s->get());
    if (p.is_relative()) p = base_dir_ / p;
    try {
      return read_points_csv(p.lexically_normal().string(), box_);
    } catch (const Error& e) {
      fail(&n, "key '" + key + "': " + e.what());
    }
  }

  // An array of points, each an array of p numbers (or a number when p == 1).
  std::vector<Eigen::VectorXd> listed(const toml::node& n, const std::string& key) const {
    const auto* a = n.as_array();
    if (a == nullptr) wrong_type(n, key, "an array of points");
    if (a->empty()) fail(&n, "key '" + key + "' holds no point");
    if (static_cast<long long>(a->size()) > kMaxParameterSetSize) {
      fail(&n, "key '" + key + "' holds more than " + std::to_string(kMaxParameterSetSize) + " points");
    }
    std::vector<Eigen::VectorXd> points;
    points.reserve(a->size());
    for (std::size_t i = 0; i < a->size(); ++i) points.push_back(point(*a->get(i), element(key, i)));
    if (const auto repeat = detail::first_repeat(points)) {
      fail(a->get(static_cast<std::size_t>(repeat->second)),
           "key '" + element(key, static_cast<std::size_t>(repeat->second)) + "' repeats '" +
               element(key, static_cast<std::size_t>(repeat->first)) + "'");
    }
    return points;
  }

  Eigen::VectorXd point(const toml::node& n, const std::string& key) const {
    const int p = box_.size();
    Eigen::VectorXd mu(p);
    if (p == 1 && n.is_number()) {
      mu[0] = value(n, key, 0);
      return mu;
    }
    const std::string expected = "an array of " + std::to_string(p) + " numbers (" + names() + ")" +
                                 (p == 1 ? std::string(" or a number") : std::string());
    const auto* a = n.as_array();
    if (a == nullptr) wrong_type(n, key, expected);
    if (static_cast<int>(a->size()) != p) {
      fail(&n, "key '" + key + "' must be " + expected + ", got " + std::to_string(a->size()) + " values");
    }
    for (int k = 0; k < p; ++k) {
      const auto i = static_cast<std::size_t>(k);
      mu[k] = value(*a->get(i), element(key, i), k);
    }
    return mu;
  }

  const ParameterBox& box_;
  fs::path base_dir_;
  std::string origin_;
};

}  // namespace

std::vector<Eigen::VectorXd> parameter_set_from_toml(const toml::node& node, const ParameterBox& box,
                                                     const fs::path& base_dir, const std::string& key,
                                                     const std::string& origin) {
  try {
    check_parameter_box(box, origin);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " (reading key '" + key + "')");
  }
  return SetReader(box, base_dir, origin).read(node, key);
}

}  // namespace contactrb::cases
