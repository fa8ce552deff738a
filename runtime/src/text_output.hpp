#pragma once
// What the runtime's writers (the trace's JSON and SVG, a starting world's JSON) share: text made
// safe for either format, and numbers with a fixed number of decimals so that the same input always
// gives the same bytes.
#include <cmath>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace semo::runtime::detail {

// The text as valid UTF-8: each byte that does not start a well-formed sequence (overlong forms and
// surrogates included) becomes U+FFFD. Names in a trace come from user files; a stray Latin-1 byte
// must not make the whole JSON or SVG unreadable.
inline std::string validUtf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    std::size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 0;
    bool ok = n != 0 && i + n <= s.size();
    unsigned code = n == 1 ? b : n == 2 ? b & 0x1Fu : n == 3 ? b & 0x0Fu : b & 0x07u;
    for (std::size_t k = 1; ok && k < n; ++k) {
      const auto c = static_cast<unsigned char>(s[i + k]);
      ok = (c & 0xC0) == 0x80;
      code = (code << 6) | (c & 0x3Fu);
    }
    const unsigned least[] = {0, 0, 0x80, 0x800, 0x10000};
    ok = ok && code >= least[n] && code <= 0x10FFFF && (code < 0xD800 || code > 0xDFFF);
    if (ok) {
      out.append(s.substr(i, n));
      i += n;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

// `x` with `decimals` decimals; "-0.000" (a tiny negative) prints as "0.000", and a value that is
// not finite as `otherwise`.
inline std::string fixed(double x, int decimals, std::string_view otherwise = "0") {
  if (!std::isfinite(x)) return std::string(otherwise);
  std::string s = fmt::format("{:.{}f}", x, decimals);
  if (s.front() == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

// A JSON string (RFC 8259) of the text made valid UTF-8: quotes, backslashes and control characters
// escaped.
inline std::string jsonString(std::string_view raw) {
  std::string out = "\"";
  for (char c : validUtf8(raw)) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        else out += c;
    }
  }
  return out + "\"";
}

}  // namespace semo::runtime::detail
