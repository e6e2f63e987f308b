#pragma once
// Conversions between the standard containers' std::size_t and Eigen's signed Eigen::Index, in one
// place: -Wsign-conversion-clean indexing where std::vector positions address Eigen rows/columns.
#include <Eigen/Core>
#include <cstddef>

namespace contactrb {

using Index = Eigen::Index;

// A container position as an Eigen index.
inline Index ix(std::size_t i) { return static_cast<Index>(i); }

// A (non-negative) Eigen index as a container position.
inline std::size_t sz(Index i) { return static_cast<std::size_t>(i); }

}  // namespace contactrb
