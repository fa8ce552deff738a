// The text-level half of the world reader (world_scan.hpp): where a byte offset is, and a scan of
// the raw text before nlohmann::json parses it. The scan exists because the parser can neither
// bound the nesting depth (a depth bomb must be stopped before it reaches the library) nor say where
// a duplicate member or an overflowing number is written.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "world_scan.hpp"

namespace semo::runtime {

namespace detail {

std::vector<std::size_t> lineStarts(std::string_view text) {
  std::vector<std::size_t> starts{0};
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n') starts.push_back(i + 1);
  }
  return starts;
}

// Line and column (1-based, columns count bytes as everywhere in semo) of a byte offset, with the
// line's text: of a long line only a window around the column, so that each of many errors on a
// line of megabytes costs what its message does, not what the line does.
WorldError errorAt(std::string_view text, const std::vector<std::size_t>& starts, const std::string& path, std::size_t offset,
                   std::string message) {
  constexpr std::size_t kShownLine = 200, kShownBefore = 80;
  offset = std::min(offset, text.size());
  const auto line = static_cast<std::size_t>(std::upper_bound(starts.begin(), starts.end(), offset) - starts.begin());
  const std::size_t lineStart = starts[line - 1];
  std::size_t lineEnd = line < starts.size() ? starts[line] - 1 : text.size();
  if (lineEnd > lineStart && text[lineEnd - 1] == '\r') --lineEnd;
  WorldError e{path, line, offset - lineStart + 1, std::move(message), ""};
  const std::string_view whole = text.substr(lineStart, lineEnd - lineStart);
  if (whole.size() <= kShownLine) {
    e.lineText = whole;
    return e;
  }
  const std::size_t column0 = e.column - 1;
  std::size_t begin = column0 > kShownBefore ? std::min(column0, whole.size()) - kShownBefore : 0;
  std::size_t end = std::min(whole.size(), begin + kShownLine);
  // Cut between characters, not inside a UTF-8 sequence.
  while (begin > 0 && (static_cast<unsigned char>(whole[begin]) & 0xC0) == 0x80) --begin;
  while (end < whole.size() && end > begin && (static_cast<unsigned char>(whole[end]) & 0xC0) == 0x80) --end;
  const std::string lead = begin > 0 ? "..." : "";
  e.lineText = lead + std::string(whole.substr(begin, end - begin)) + (end < whole.size() ? "..." : "");
  e.caret = lead.size() + e.column - begin;
  return e;
}

WorldError errorAt(std::string_view text, const std::string& path, std::size_t offset, std::string message) {
  return errorAt(text, lineStarts(text), path, offset, std::move(message));
}

// What nlohmann cannot tell with a position: nesting beyond kMaxWorldDepth (found before parsing, so a
// depth bomb never reaches the recursive parts of the library), members given twice in one object
// (the parser silently keeps the last) and numbers no double holds. The text may be anything: the
// scan only reads within bounds and reports what it recognises.
PreScan preScan(std::string_view t) {
  PreScan out;
  struct Frame {
    bool object;
    bool expectKey;
    std::set<std::string> keys;
  };
  std::vector<Frame> stack;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (c == '{' || c == '[') {
      if (stack.size() == kMaxWorldDepth) {
        out.problems = {{i, "nesting deeper than " + std::to_string(kMaxWorldDepth) + " levels"}};
        out.tooDeep = true;
        return out;
      }
      stack.push_back({c == '{', c == '{', {}});
    } else if (c == '}' || c == ']') {
      if (!stack.empty()) stack.pop_back();
    } else if (c == ',') {
      if (!stack.empty() && stack.back().object) stack.back().expectKey = true;
    } else if (c == '"') {
      const std::size_t start = i;
      std::string s;
      for (++i; i < t.size() && t[i] != '"'; ++i) {
        if (t[i] == '\\' && i + 1 < t.size()) ++i;  // the escaped character stands for itself (\uXXXX stays as written)
        s += t[i];
      }
      if (!stack.empty() && stack.back().expectKey) {
        stack.back().expectKey = false;
        if (!stack.back().keys.insert(s).second && !isComment(s)) out.problems.push_back({start, "member '" + s + "' given twice"});
      }
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const std::size_t start = i;
      while (i + 1 < t.size() && std::string_view("0123456789+-.eE").find(t[i + 1]) != std::string_view::npos) ++i;
      const std::string number(t.substr(start, i - start + 1));
      if (!std::isfinite(std::strtod(number.c_str(), nullptr))) out.problems.push_back({start, "number " + number + " is out of range"});
    }
  }
  return out;
}

}  // namespace detail

std::string formatWorldError(const WorldError& e) {
  std::string out = e.file;
  if (e.line != 0) out += ":" + std::to_string(e.line) + ":" + std::to_string(std::max<std::size_t>(e.column, 1));
  out += ": error: " + e.message + "\n";
  if (e.line == 0 || e.lineText.empty()) return out;
  out += e.lineText + "\n";
  // Keep tabs so that the caret lines up under the same column as the line above.
  const std::size_t caret = e.caret != 0 ? e.caret : e.column;
  for (std::size_t i = 1; i < caret && i - 1 < e.lineText.size(); ++i) out += e.lineText[i - 1] == '\t' ? '\t' : ' ';
  return out + "^\n";
}

}  // namespace semo::runtime
