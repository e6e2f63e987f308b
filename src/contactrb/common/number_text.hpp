#pragma once
// Numbers in messages and progress lines: six significant digits, as printf's %g ("1e+300",
// "0.062822", "1.01"), where std::to_string writes a fixed six decimals (a 300-digit number for
// 1e300, "0.000000" for 1e-9) and the shortest round-trip form can carry 17 digits
// ("1.0100000000000002"). Messages that must not round a value (a mu just outside its domain)
// use the round-trip form instead (cases::mu_text).
#include <cstdio>
#include <string>

namespace contactrb {

inline std::string number_text(double x) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%g", x);
  return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
}

}  // namespace contactrb
