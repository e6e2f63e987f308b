#pragma once
// Usage errors: invalid input a caller can fix (a missing file, a parameter outside its
// domain, mismatched sizes). Numerical outcomes (non-convergence) are statuses in result
// values, never exceptions (STYLE.md, item 2).
#include <stdexcept>
#include <string>

namespace contactrb {

// A message quoting user input may hold a NUL byte, which would end what() there: it is kept
// as the text \x00 (printable() writes every other control byte the same way).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(without_nul(what)) {}

 private:
  static std::string without_nul(const std::string& s) {
    if (s.find('\0') == std::string::npos) return s;
    std::string out;
    for (const char c : s) {
      if (c == '\0') {
        out += "\\x00";
      } else {
        out += c;
      }
    }
    return out;
  }
};

// Throws Error(message) when the condition fails. Use for argument and size checks whose
// message names the argument and the sizes.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace contactrb
