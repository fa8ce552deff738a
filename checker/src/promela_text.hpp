#pragma once
// Small text helpers of the Promela export (promela_export.cpp, promela_liveness.cpp).
#include <string>

namespace semo::checker::detail {

// Concatenation by appending (GCC 12 warns falsely about `"literal" + std::string&&`).
template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  (out.append(parts), ...);
  return out;
}

// Comments must not end early, and must stay on their line.
inline std::string commentText(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    char c = s[i];
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    out += c;
    if (c == '*' && i + 1 < s.size() && s[i + 1] == '/') out += ' ';
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '*') out += ' ';
  }
  return out;
}

}  // namespace semo::checker::detail
