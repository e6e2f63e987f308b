#pragma once
// Usage errors: invalid input a caller can fix (a missing file, a parameter outside its
// domain, mismatched sizes). Numerical outcomes (non-convergence) are statuses in result
// values, never exceptions (STYLE.md, item 2).
#include <stdexcept>
#include <string>

namespace contactrb {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Throws Error(message) when the condition fails. Use for argument and size checks whose
// message names the argument and the sizes.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace contactrb
