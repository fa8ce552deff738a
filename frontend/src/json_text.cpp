#include "semo/frontend/json_text.hpp"

namespace semo {

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
