#pragma once
// Parameter sets in p dimensions (docs/cases.md): the box P = [min_1, max_1] x ... x [min_p, max_p],
// tensor grids, seeded Latin hypercube and uniform random sets, CSV files of points, and the
// scaled distance that picks the nearest training point for the online initial guess.
//
// Random sets are the same on every platform: std::mt19937_64 is fully specified by the
// standard, but std::uniform_*_distribution are not (libstdc++, libc++ and MSVC draw different
// numbers from the same engine), so the conversions to [0, 1) and to an index are our own.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace contactrb::cases {

// The largest number of points a generated or read set may hold (a tensor grid's product of
// counts, a Latin hypercube's or a random set's n): 1e7 points of p = 10 is already ~1 GB.
inline constexpr long long kMaxParameterSetSize = 10'000'000;

// One entry per parameter, in parameter order.
struct ParameterBox {
  std::vector<std::string> names;
  Eigen::VectorXd min;
  Eigen::VectorXd max;

  int size() const { return static_cast<int>(names.size()); }
};

// Throws contactrb::Error naming `context` and the first inconsistency: no parameter, sizes
// of names/min/max that differ, an empty or repeated name, a non-finite bound, min > max.
// (min == max is allowed: a frozen parameter.)
void check_parameter_box(const ParameterBox& box, const std::string& context);

// {min + i (max - min) / (count - 1), i = 0..count-1}, the last value exactly max, every value
// inside [min, max]; count == 1 gives the midpoint. Throws contactrb::Error for count < 1,
// non-finite bounds or min > max.
std::vector<double> uniform_axis(double min, double max, int count);

// The Cartesian product of the axes (one axis per parameter), the FIRST parameter varying
// fastest: point index = i_1 + n_1 (i_2 + n_2 (i_3 + ...)) holds (axes[0][i_1], axes[1][i_2], ...).
// Throws contactrb::Error when there is no axis, an axis is empty, or the product of the sizes
// exceeds kMaxParameterSetSize.
std::vector<Eigen::VectorXd> tensor_grid(const std::vector<std::vector<double>>& axes);

// Latin hypercube of n points in the box: for each parameter the n strata [min + j w/n,
// min + (j+1) w/n) (w = max - min) hold exactly one point each. Draw order, fixed so that the
// set depends on (box, n, seed) only: for each parameter in order, a Fisher-Yates permutation
// of the strata (j = n-1 down to 1), then n offsets in the strata (point by point).
// A degenerate parameter (min == max) takes that value but still consumes its draws, so that
// freezing one parameter leaves the other coordinates unchanged.
// Throws contactrb::Error for n outside [1, kMaxParameterSetSize] or an invalid box.
std::vector<Eigen::VectorXd> latin_hypercube(const ParameterBox& box, int n, std::uint64_t seed);

// n points uniform in the box, drawn point by point, parameter by parameter. A degenerate
// parameter takes its value (and consumes its draw). Throws as latin_hypercube.
std::vector<Eigen::VectorXd> uniform_random(const ParameterBox& box, int n, std::uint64_t seed);

// Reads a CSV file of points (docs: parameter_set_toml.hpp). Format:
//  - lines are separated by LF or CRLF; blank lines and lines whose first non-blank character
//    is '#' are ignored anywhere in the file;
//  - fields are separated by commas; spaces and tabs around a field are ignored; a field may
//    be double-quoted ("a, b" with "" for a quote), so names holding commas can be written;
//  - the first line is a header naming every parameter exactly once, in any order, UNLESS
//    every one of its fields reads as a number: then the file has no header and each line
//    holds the p values in parameter order (so a one-parameter file can be one number a line;
//    a parameter whose name reads as a number cannot be named in a header);
//  - every value is a finite decimal number inside its parameter's domain; no point twice;
//    at least one point, at most kMaxParameterSetSize.
// Throws contactrb::Error naming the file, the line and, for a value, the parameter and its
// domain; a header that does not match names every missing, unknown and repeated name.
std::vector<Eigen::VectorXd> read_points_csv(const std::string& path, const ParameterBox& box);

// The CSV text read_points_csv reads back exactly: a header of the (quoted when needed)
// names, then one line per point, each value in its shortest round-trip form.
std::string points_csv_text(const std::vector<Eigen::VectorXd>& points, const ParameterBox& box);

// Throws contactrb::Error naming `context` when the set is empty, a point has a size other
// than p, a value is not finite or outside its domain (naming the point, the parameter and the
// domain), or a point repeats an earlier one (naming both, 1-based: "point 7 repeats point 2";
// the earliest repeat in the order of the set). O(n log n) in the number of points.
void check_points(const std::vector<Eigen::VectorXd>& points, const ParameterBox& box,
                  const std::string& context);

// Coordinates scaled to [0, 1] per parameter: (mu_k - min_k) / (max_k - min_k), and 0 for a
// degenerate parameter. Distances in these coordinates weigh every parameter by its range
// rather than by its units. Sizes are checked (contactrb::Error); the box is not.
Eigen::VectorXd scaled(const Eigen::VectorXd& mu, const ParameterBox& box);
std::vector<Eigen::VectorXd> scaled(const std::vector<Eigen::VectorXd>& points, const ParameterBox& box);

// Euclidean distance between a and b in scaled coordinates (a degenerate parameter counts 0).
double scaled_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const ParameterBox& box);

// Index of the point nearest to mu in scaled coordinates; a tie goes to the smallest index.
// For the online initial guess: no allocation, O(n p). Throws contactrb::Error for an empty
// set, a size other than p or a non-finite mu (mu may lie outside the box).
int nearest_point(const std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& mu, const ParameterBox& box);

}  // namespace contactrb::cases
