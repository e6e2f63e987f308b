#include "contactrb/online/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::online {

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// A uniform double in [0, 1) for (seed, point, parameter, draw): 53 random bits.
double uniform01(std::uint64_t seed, std::uint64_t i, std::uint64_t k, std::uint64_t draw) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ i);
  h = splitmix64(h ^ (k << 32 | (draw & 0xffffffffULL)));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

double number(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  require(!text.empty() && end == text.c_str() + text.size() && std::isfinite(x), what + ": '" + text + "' is not a finite number");
  return x;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep)) out.push_back(item);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

}  // namespace

SampleDistribution parse_distribution(const std::string& text, const std::vector<cases::ParameterSpec>& parameters,
                                      const std::string& flag) {
  SampleDistribution d;
  const std::size_t p = parameters.size();
  if (text == "uniform") return d;
  const std::string usage = flag + " '" + text + "': expected uniform, normal, or normal:MEAN:SD (one MEAN:SD per parameter, separated by commas)";
  require(text.rfind("normal", 0) == 0, usage);
  d.kind = SampleDistribution::Kind::Normal;
  if (text == "normal") {
    for (const cases::ParameterSpec& q : parameters) {
      d.mean.push_back(0.5 * (q.min + q.max));
      d.sd.push_back((q.max - q.min) / 6.0);
    }
  } else {
    require(text.rfind("normal:", 0) == 0, usage);
    const std::vector<std::string> items = split(text.substr(7), ',');
    require(items.size() == p, flag + " '" + text + "': " + std::to_string(items.size()) + " MEAN:SD pairs for " +
                                   std::to_string(p) + (p == 1 ? " parameter" : " parameters"));
    for (const std::string& item : items) {
      const std::vector<std::string> ms = split(item, ':');
      require(ms.size() == 2, usage);
      d.mean.push_back(number(ms[0], flag + " mean"));
      d.sd.push_back(number(ms[1], flag + " standard deviation"));
    }
  }
  for (std::size_t k = 0; k < p; ++k) {
    const cases::ParameterSpec& q = parameters[k];
    require(d.sd[k] > 0.0, flag + ": the standard deviation of " + q.name + " must be > 0");
    require(d.mean[k] >= q.min && d.mean[k] <= q.max,
            flag + ": the mean of " + q.name + " is outside the model's domain [" + number_text(q.min) + ", " +
                number_text(q.max) + "]");
  }
  return d;
}

cases::Mu sample_point(const SampleDistribution& dist, const std::vector<cases::ParameterSpec>& parameters,
                       std::uint64_t seed, std::uint64_t i) {
  cases::Mu mu(static_cast<Eigen::Index>(parameters.size()));
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const cases::ParameterSpec& q = parameters[k];
    double x = 0.0;
    if (dist.kind == SampleDistribution::Kind::Uniform) {
      // min + (max - min) u, u in [0, 1): never above max.
      x = std::min(q.max, q.min + (q.max - q.min) * uniform01(seed, i, k, 0));
    } else {
      bool inside = false;
      for (std::uint64_t draw = 0; draw < 1000 && !inside; ++draw) {
        // Box-Muller: 1 - u is in (0, 1], so its logarithm is finite.
        const double u1 = 1.0 - uniform01(seed, i, k, 2 * draw);
        const double u2 = uniform01(seed, i, k, 2 * draw + 1);
        const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
        x = dist.mean[k] + dist.sd[k] * z;
        inside = x >= q.min && x <= q.max;
      }
      require(inside, "the normal distribution of " + q.name + " lies almost entirely outside the model's domain "
                      "(1000 draws outside it)");
    }
    mu(static_cast<Eigen::Index>(k)) = x;
  }
  return mu;
}

OutputStats output_stats(const std::string& name, const std::vector<double>& values, int bins) {
  require(bins >= 1, "the number of histogram bins must be >= 1 (got " + std::to_string(bins) + ")");
  OutputStats s;
  s.name = name;
  std::vector<double> v;
  v.reserve(values.size());
  for (double x : values) {
    if (std::isfinite(x)) v.push_back(x);
  }
  s.count = v.size();
  if (v.empty()) return s;
  // Mean and variance in index order (Welford), then the order statistics.
  double mean = 0.0, m2 = 0.0;
  for (std::size_t j = 0; j < v.size(); ++j) {
    const double d = v[j] - mean;
    mean += d / static_cast<double>(j + 1);
    m2 += d * (v[j] - mean);
  }
  s.mean = mean;
  s.sd = v.size() > 1 ? std::sqrt(m2 / static_cast<double>(v.size() - 1)) : 0.0;
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  const auto quantile = [&](double q) {
    const double h = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(h));
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
  };
  s.q05 = quantile(0.05);
  s.q50 = quantile(0.5);
  s.q95 = quantile(0.95);
  const std::size_t nb = s.max > s.min ? static_cast<std::size_t>(bins) : 1;
  s.histogram.assign(nb, 0);
  for (double x : v) {
    std::size_t b = nb == 1 ? 0 : static_cast<std::size_t>((x - s.min) / (s.max - s.min) * static_cast<double>(nb));
    s.histogram[std::min(b, nb - 1)] += 1;
  }
  return s;
}

const char* to_string(SampleDistribution::Kind value) {
  switch (value) {
    case SampleDistribution::Kind::Uniform: return "uniform";
    case SampleDistribution::Kind::Normal: return "normal";
  }
  return "unknown";
}

SampleDistribution::Kind sample_distribution_kind_from_string(const std::string& name) {
  using enum SampleDistribution::Kind;
  return enum_from_string(name, "sample distribution", std::array{Uniform, Normal});
}

}  // namespace contactrb::online
