#pragma once

namespace contactrb {

inline constexpr const char* kVersion = "0.1.0";

}  // namespace contactrb
