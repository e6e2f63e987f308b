#pragma once
// Sampling the parameter domain for uncertainty quantification (`contactrb sample`,
// docs/parallel.md): random points drawn from a distribution over the model's domain, and the
// statistics and histograms of scalar outputs of their online answers.
//
// Point i of a sample is a function of (seed, i) alone (a counter-based generator: splitmix64
// of the seed, i, the parameter and the draw), so a sample does not depend on the number of
// threads or ranks that answer it, and a larger n extends a smaller one.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contactrb/cases/parameter.hpp"

namespace contactrb::online {

struct SampleDistribution {
  enum class Kind { Uniform, Normal };
  Kind kind = Kind::Uniform;
  // Normal: per parameter. Truncated to the domain (a draw outside is drawn again).
  std::vector<double> mean, sd;
};
const char* to_string(SampleDistribution::Kind value);  // "uniform" | "normal"
SampleDistribution::Kind sample_distribution_kind_from_string(const std::string& name);  // throws contactrb::Error

// "uniform": each parameter uniform on [min, max]. "normal": each parameter normal with mean
// the middle of its interval and standard deviation a sixth of its length. "normal:M:S" (one
// parameter) or "normal:M1:S1,M2:S2,..." (one M:S per parameter, in order): those means and
// standard deviations. Both truncated to the domain. Throws contactrb::Error naming `flag` for
// anything else, a mean outside the domain, a standard deviation that is not > 0.
SampleDistribution parse_distribution(const std::string& text, const std::vector<cases::ParameterSpec>& parameters,
                                      const std::string& flag = "--dist");

// Point i of the sample. Throws contactrb::Error when 1000 draws of a truncated normal all
// fall outside the domain (a distribution almost entirely outside it).
cases::Mu sample_point(const SampleDistribution& dist, const std::vector<cases::ParameterSpec>& parameters,
                       std::uint64_t seed, std::uint64_t i);

// Statistics of the finite values of one output.
struct OutputStats {
  std::string name;
  std::size_t count = 0;  // finite values (NaN: no answer)
  double mean = 0.0, sd = 0.0;  // sd: sample standard deviation (n - 1)
  double min = 0.0, max = 0.0;
  double q05 = 0.0, q50 = 0.0, q95 = 0.0;  // quantiles, linear between order statistics
  // `bins` equal bins over [min, max] (the last one closed); one bin when min == max.
  std::vector<std::size_t> histogram;
};

// In index order, so the figures do not depend on how the values were computed. Throws
// contactrb::Error for bins < 1.
OutputStats output_stats(const std::string& name, const std::vector<double>& values, int bins);

}  // namespace contactrb::online
