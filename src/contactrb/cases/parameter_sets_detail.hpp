#pragma once
// Helpers shared by parameter_sets.cpp, parameter_sets_csv.cpp and parameter_set_toml.cpp
// (not part of the API).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contactrb/cases/parameter_sets.hpp"

namespace contactrb::cases::detail {

// Shortest round-trip text of a double (nan and inf as such), for messages and CSV output.
std::string shortest(double x);

// "[min, max]" of parameter k.
std::string domain_text(const ParameterBox& box, int k);

// "parameter 'b' = 3.5 is outside its domain [1, 2]" (or "... is nan, not a finite number").
std::string value_error(const ParameterBox& box, int k, double value);

// The earliest repeat in the order of the set: (i, j), i < j, points[j] == points[i], j the
// smallest such index and i the first index holding that point. O(n log n).
std::optional<std::pair<int, int>> first_repeat(const std::vector<Eigen::VectorXd>& points);

}  // namespace contactrb::cases::detail
