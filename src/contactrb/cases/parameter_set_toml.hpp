#pragma once
// One named parameter set of a TOML case file, in p dimensions (docs/cases.md).
//
// ---- User documentation (for docs/cases.md) -------------------------------------------
//
// Each entry of the `[sets]` table is a named set of parameter points (`training`,
// `verification`, ...). Every point lies in the parameter domain, and no point appears twice.
// A set has one of these forms:
//
//   [sets]
//   # Tensor grid: per parameter, in [[parameter]] order, either a count of uniformly spaced
//   # values (min and max included; a count of 1 is the midpoint) or the list of values
//   # (strictly increasing, inside the domain). The first parameter varies fastest.
//   training     = { grid = [5, 4, 3] }
//   coarse       = { grid = [[0.1, 0.2], [1, 2, 3]] }
//   mixed        = { grid = [5, [1.0, 1.5, 2.0]] }
//
//   # Latin hypercube of n points: each parameter's domain, cut into n equal strata, has
//   # exactly one point in each. `seed` (an integer >= 0, default 1) fixes the points: the same
//   # case file gives the same set on every machine.
//   large        = { latin-hypercube = 1000, seed = 1 }
//
//   # n points drawn uniformly in the domain (same `seed` rule).
//   verification = { random = 200, seed = 7 }
//
//   # Points from a CSV file (a path relative to the case file's directory).
//   measured     = { file = "points.csv" }
//
//   # Points listed: each an array of p numbers in [[parameter]] order. A plain array is
//   # short for { points = ... }; with one parameter each point may be a bare number.
//   listed       = { points = [[0.2, 1.0], [0.3, 1.2]] }
//   short        = [[0.2, 1.0], [0.3, 1.2]]
//   scalar       = [0.15, 0.2, 0.25]          # one parameter only
//
// A set holds at most 10^7 points (a grid: the product of its counts; a CSV file: its lines).
//
// The CSV file: a header line naming every parameter exactly once, in any order, then one
// point per line, values separated by commas:
//
//   # load scale and radius
//   radius, load
//   1.0, 0.2
//   1.2, 0.3
//
// Blank lines and lines starting with '#' are ignored. Without a header (when every field of
// the first line is a number), each line holds the p values in [[parameter]] order; with one
// parameter that is simply one number a line. A name containing a comma, or one that reads as
// a number, is written in double quotes in the header ("a, b"; "" stands for a quote).
//
// Every mistake (an unknown key, a wrong type, a count below 1, a point of the wrong length,
// a value outside the domain, a repeated point) is reported with the file, the line and the
// dotted key, e.g.  case.toml:12: key 'sets.training.grid[2]' must be >= 1, got 0
// -------------------------------------------------------------------------------------------
//
// This header includes toml++, which is a private dependency of contactrb_cases: include it
// from the case readers in cases/ only (or link tomlplusplus::tomlplusplus, as the tests do).
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "contactrb/cases/parameter_sets.hpp"

namespace contactrb::cases {

// The points of one set from `node`, the value of `key` (the dotted key used in messages,
// e.g. "sets.training") in the file named `origin`; `file = ...` is resolved against
// `base_dir`. The result has passed check_points. Throws contactrb::Error
// "<origin>:<line>: key '<key>...' ..." for every invalid form or value, and for an invalid box.
std::vector<Eigen::VectorXd> parameter_set_from_toml(const toml::node& node, const ParameterBox& box,
                                                     const std::filesystem::path& base_dir, const std::string& key,
                                                     const std::string& origin);

}  // namespace contactrb::cases
