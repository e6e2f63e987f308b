#pragma once
// The one way an enum's name is read back (STYLE.md, item 11): every enum of the library has a
// `to_string` beside it, and its `*_from_string` is enum_from_string over the enum's values, so
// that the accepted names are the written ones and the error names them all.
#include <array>
#include <cstddef>
#include <string>

#include "contactrb/common/error.hpp"

namespace contactrb {

// The value of `values` whose to_string is `name`. Throws contactrb::Error
// "unknown <what> '<name>' (expected a, b or c)" for any other name.
template <class Enum, std::size_t K>
Enum enum_from_string(const std::string& name, const char* what, const std::array<Enum, K>& values) {
  for (Enum value : values) {
    if (name == to_string(value)) return value;
  }
  std::string expected;
  for (std::size_t k = 0; k < K; ++k) {
    expected += (k == 0 ? "" : k + 1 == K ? " or " : ", ") + std::string(to_string(values[k]));
  }
  throw Error("unknown " + std::string(what) + " '" + name + "' (expected " + expected + ")");
}

}  // namespace contactrb
