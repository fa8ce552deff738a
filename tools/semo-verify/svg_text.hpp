#pragma once
// Text put into the SVG pictures semo-verify draws (charts, sequence charts): XML's special
// characters escaped.
#include <string>

namespace semo::cli {

inline std::string svgEscaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

}  // namespace semo::cli
