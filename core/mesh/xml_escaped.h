// Text escaping for the XML writers (VTU, SVG).
#pragma once

#include <string>

namespace meshd {

// The five characters XML reserves, escaped for an attribute value or text.
inline std::string xml_escaped(const std::string& s) {
  std::string r;
  for (const char c : s) {
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      case '\'':
        r += "&apos;";
        break;
      default:
        r += c;
    }
  }
  return r;
}

}  // namespace meshd
