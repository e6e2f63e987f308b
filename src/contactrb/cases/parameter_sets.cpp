#include "contactrb/cases/parameter_sets.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>

#include "contactrb/cases/parameter_sets_detail.hpp"
#include "contactrb/common/error.hpp"

namespace contactrb::cases {

namespace detail {

std::string shortest(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string domain_text(const ParameterBox& box, int k) {
  // Appended piece by piece: "[" + std::string draws a -Wrestrict false positive from g++ 12.
  std::string s = "[";
  s += shortest(box.min[k]);
  s += ", ";
  s += shortest(box.max[k]);
  s += "]";
  return s;
}

std::string value_error(const ParameterBox& box, int k, double value) {
  const std::string name = "parameter '" + box.names[static_cast<std::size_t>(k)] + "'";
  if (!std::isfinite(value)) return name + " is " + shortest(value) + ", not a finite number";
  return name + " = " + shortest(value) + " is outside its domain " + domain_text(box, k);
}

std::optional<std::pair<int, int>> first_repeat(const std::vector<Eigen::VectorXd>& points) {
  // Sorting indices by (point, index) puts equal points next to each other, the earliest
  // first; the earliest repeat is then the smallest second index over neighbouring pairs.
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  const auto less = [&](int a, int b) {
    const Eigen::VectorXd& x = points[static_cast<std::size_t>(a)];
    const Eigen::VectorXd& y = points[static_cast<std::size_t>(b)];
    const auto diff = std::mismatch(x.data(), x.data() + x.size(), y.data());
    if (diff.first != x.data() + x.size()) return *diff.first < *diff.second;
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::optional<std::pair<int, int>> found;
  std::size_t group = 0;  // position in `order` of the first of the current run of equal points
  for (std::size_t i = 1; i < order.size(); ++i) {
    const Eigen::VectorXd& x = points[static_cast<std::size_t>(order[i - 1])];
    const Eigen::VectorXd& y = points[static_cast<std::size_t>(order[i])];
    if (x != y) {
      group = i;
      continue;
    }
    if (!found || order[i] < found->second) found = std::pair{order[group], order[i]};
  }
  return found;
}

}  // namespace detail

namespace {

using detail::shortest;

// A double uniform in [0, 1) from the top 53 bits of one engine output: every platform gets
// the same value (std::uniform_real_distribution may not).
double unit_draw(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

// An integer uniform in [0, bound) (bound >= 1) without modulo bias: outputs below
// 2^64 mod bound are rejected, so the accepted range is a multiple of bound.
std::uint64_t index_draw(std::mt19937_64& engine, std::uint64_t bound) {
  const std::uint64_t reject_below = (0 - bound) % bound;  // == 2^64 mod bound
  std::uint64_t x = engine();
  while (x < reject_below) x = engine();
  return x % bound;
}

// Fisher-Yates: a uniformly random permutation of 0..n-1.
std::vector<int> permutation(std::mt19937_64& engine, int n) {
  std::vector<int> p(static_cast<std::size_t>(n));
  std::iota(p.begin(), p.end(), 0);
  for (int j = n - 1; j >= 1; --j) {
    const auto k = static_cast<std::size_t>(index_draw(engine, static_cast<std::uint64_t>(j) + 1));
    std::swap(p[static_cast<std::size_t>(j)], p[k]);
  }
  return p;
}

// min + t (max - min) for t in [0, 1], kept inside [min, max] against round-off.
double in_range(double min, double max, double t) {
  if (min == max) return min;
  return std::min(max, min + t * (max - min));
}

void check_set_size(long long n, const std::string& what) {
  require(n >= 1 && n <= kMaxParameterSetSize, what + ": the number of points must be in [1, " +
                                                   std::to_string(kMaxParameterSetSize) + "], got " +
                                                   std::to_string(n));
}

// The message is built only on failure: nearest_point calls this online, once per point.
void check_size(const Eigen::VectorXd& mu, const ParameterBox& box, const char* what, std::size_t index = 0) {
  if (mu.size() == box.size()) return;
  throw Error(std::string(what) + (index > 0 ? ": point " + std::to_string(index) : std::string()) + ": " +
              std::to_string(mu.size()) + " values, expected " + std::to_string(box.size()) + " (one per parameter)");
}

}  // namespace

void check_parameter_box(const ParameterBox& box, const std::string& context) {
  const std::string where = context + ": parameter box: ";
  require(!box.names.empty(), where + "no parameter");
  require(box.min.size() == box.size() && box.max.size() == box.size(),
          where + std::to_string(box.names.size()) + " names but " + std::to_string(box.min.size()) + " min and " +
              std::to_string(box.max.size()) + " max values");
  std::set<std::string> seen;
  for (int k = 0; k < box.size(); ++k) {
    const std::string& name = box.names[static_cast<std::size_t>(k)];
    require(!name.empty(), where + "parameter " + std::to_string(k + 1) + " has an empty name");
    require(seen.insert(name).second, where + "the name '" + name + "' is given twice");
    require(std::isfinite(box.min[k]) && std::isfinite(box.max[k]),
            where + "parameter '" + name + "' has a non-finite domain " + detail::domain_text(box, k));
    require(box.min[k] <= box.max[k],
            where + "parameter '" + name + "' has an inverted domain " + detail::domain_text(box, k));
  }
}

std::vector<double> uniform_axis(double min, double max, int count) {
  require(count >= 1, "uniform_axis: count must be >= 1, got " + std::to_string(count));
  require(std::isfinite(min) && std::isfinite(max) && min <= max,
          "uniform_axis: needs finite min <= max, got [" + shortest(min) + ", " + shortest(max) + "]");
  if (count == 1) return {min + 0.5 * (max - min)};
  std::vector<double> v(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) v[static_cast<std::size_t>(i)] = std::min(max, min + (max - min) * i / (count - 1));
  v.back() = max;
  return v;
}

std::vector<Eigen::VectorXd> tensor_grid(const std::vector<std::vector<double>>& axes) {
  require(!axes.empty(), "tensor_grid: no axis");
  long long total = 1;
  for (std::size_t k = 0; k < axes.size(); ++k) {
    require(!axes[k].empty(), "tensor_grid: axis " + std::to_string(k + 1) + " is empty");
    total *= static_cast<long long>(axes[k].size());  // stays below 1e7 * 1e7: no overflow
    require(total <= kMaxParameterSetSize, "tensor_grid: more than " + std::to_string(kMaxParameterSetSize) +
                                               " points (the product of the axis sizes)");
  }
  const auto p = static_cast<Eigen::Index>(axes.size());
  std::vector<Eigen::VectorXd> points(static_cast<std::size_t>(total), Eigen::VectorXd(p));
  for (long long i = 0; i < total; ++i) {
    long long rest = i;  // mixed-radix digits of i, the first parameter's digit the lowest
    for (Eigen::Index k = 0; k < p; ++k) {
      const auto& axis = axes[static_cast<std::size_t>(k)];
      const auto n = static_cast<long long>(axis.size());
      points[static_cast<std::size_t>(i)][k] = axis[static_cast<std::size_t>(rest % n)];
      rest /= n;
    }
  }
  return points;
}

std::vector<Eigen::VectorXd> latin_hypercube(const ParameterBox& box, int n, std::uint64_t seed) {
  check_parameter_box(box, "latin_hypercube");
  check_set_size(n, "latin_hypercube");
  std::mt19937_64 engine(seed);
  std::vector<Eigen::VectorXd> points(static_cast<std::size_t>(n), Eigen::VectorXd(box.size()));
  for (int k = 0; k < box.size(); ++k) {
    const std::vector<int> stratum = permutation(engine, n);
    for (int i = 0; i < n; ++i) {
      const double t = (stratum[static_cast<std::size_t>(i)] + unit_draw(engine)) / n;
      points[static_cast<std::size_t>(i)][k] = in_range(box.min[k], box.max[k], t);
    }
  }
  return points;
}

std::vector<Eigen::VectorXd> uniform_random(const ParameterBox& box, int n, std::uint64_t seed) {
  check_parameter_box(box, "uniform_random");
  check_set_size(n, "uniform_random");
  std::mt19937_64 engine(seed);
  std::vector<Eigen::VectorXd> points(static_cast<std::size_t>(n), Eigen::VectorXd(box.size()));
  for (Eigen::VectorXd& mu : points) {
    for (int k = 0; k < box.size(); ++k) mu[k] = in_range(box.min[k], box.max[k], unit_draw(engine));
  }
  return points;
}

void check_points(const std::vector<Eigen::VectorXd>& points, const ParameterBox& box, const std::string& context) {
  require(!points.empty(), context + ": the parameter set is empty");
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_size(points[i], box, context.c_str(), i + 1);
    for (int k = 0; k < box.size(); ++k) {
      const double v = points[i][k];
      if (!(v >= box.min[k] && v <= box.max[k])) {  // also false for NaN
        throw Error(context + ": point " + std::to_string(i + 1) + ": " + detail::value_error(box, k, v));
      }
    }
  }
  if (const auto repeat = detail::first_repeat(points)) {
    throw Error(context + ": point " + std::to_string(repeat->second + 1) + " repeats point " +
                std::to_string(repeat->first + 1));
  }
}

Eigen::VectorXd scaled(const Eigen::VectorXd& mu, const ParameterBox& box) {
  check_size(mu, box, "scaled");
  Eigen::VectorXd s(box.size());
  for (int k = 0; k < box.size(); ++k) {
    const double width = box.max[k] - box.min[k];
    s[k] = width > 0.0 ? (mu[k] - box.min[k]) / width : 0.0;
  }
  return s;
}

std::vector<Eigen::VectorXd> scaled(const std::vector<Eigen::VectorXd>& points, const ParameterBox& box) {
  std::vector<Eigen::VectorXd> s;
  s.reserve(points.size());
  for (const Eigen::VectorXd& mu : points) s.push_back(scaled(mu, box));
  return s;
}

namespace {

// Squared scaled distance, without allocating (nearest_point runs online).
double scaled_distance2(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const ParameterBox& box) {
  double sum = 0.0;
  for (int k = 0; k < box.size(); ++k) {
    const double width = box.max[k] - box.min[k];
    if (!(width > 0.0)) continue;
    const double d = (a[k] - b[k]) / width;
    sum += d * d;
  }
  return sum;
}

}  // namespace

double scaled_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const ParameterBox& box) {
  check_size(a, box, "scaled_distance");
  check_size(b, box, "scaled_distance");
  return std::sqrt(scaled_distance2(a, b, box));
}

int nearest_point(const std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& mu, const ParameterBox& box) {
  require(!points.empty(), "nearest_point: no point to choose from");
  check_size(mu, box, "nearest_point");
  require(mu.allFinite(), "nearest_point: the parameter has a non-finite value");
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_size(points[i], box, "nearest_point", i + 1);
    const double d2 = scaled_distance2(points[i], mu, box);
    if (best < 0 || d2 < best_d2) {  // strict: a tie keeps the smaller index
      best = static_cast<int>(i);
      best_d2 = d2;
    }
  }
  return best;
}

}  // namespace contactrb::cases
