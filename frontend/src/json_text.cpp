#include "semo/frontend/json_text.hpp"

#include "semo/frontend/nesting.hpp"

namespace semo {

std::optional<std::size_t> jsonNestedDeeperThan(std::string_view t, std::size_t limit) {
  std::size_t depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

SourceRange jsonRangeAt(FileId file, const std::string& text, std::size_t offset) {
  std::uint32_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return SourceRange{{file, line, column}, 1};
}

std::optional<nlohmann::json> parseJsonFile(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  const std::string& text = sources.text(file);
  // The JSON parser would stop at a NUL byte and ignore what follows it.
  if (const auto nul = text.find('\0'); nul != std::string::npos) {
    diags.error(jsonRangeAt(file, text, nul), "not valid JSON: a NUL byte");
    return std::nullopt;
  }
  if (const auto deep = jsonNestedDeeperThan(text, kMaxNesting)) {
    diags.error(jsonRangeAt(file, text, *deep), "nested too deeply (limit " + std::to_string(kMaxNesting) + ")");
    return std::nullopt;
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    if (const auto colon = what.find("syntax error"); colon != std::string::npos) what = what.substr(colon);
    diags.error(jsonRangeAt(file, text, e.byte == 0 ? 0 : e.byte - 1), "not valid JSON: " + what);
  } catch (const nlohmann::json::exception& e) {  // a number past what a double holds: nlohmann gives no position
    std::string what = e.what();
    if (const auto bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
    diags.error(jsonRangeAt(file, text, 0), "not valid JSON: " + what);
  }
  return std::nullopt;
}

}  // namespace semo
