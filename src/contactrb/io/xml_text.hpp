#pragma once
// Text of an XML attribute value or element content (the VTU and PVD writers): the five
// characters XML reserves, as entities.
#include <string>
#include <string_view>

namespace contactrb::io {

inline std::string xml_escape(std::string_view s) {
  std::string r;
  r.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default: r += c;
    }
  }
  return r;
}

}  // namespace contactrb::io
