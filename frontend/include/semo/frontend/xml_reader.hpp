#pragma once
// Positions and checked attribute access for XML inputs (strategies, URDF files, SDF3 graphs). tinyxml2 gives
// element lines only; columns are recovered from the source text so that carets point at the
// element or the attribute value.
#include <tinyxml2.h>

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "semo/frontend/diagnostics.hpp"

namespace semo::xml {

class Reader {
 public:
  Reader(const SourceManager& sources, FileId file, DiagnosticEngine& diags)
      : sources_(sources), file_(file), diags_(diags) {}

  // Parses the document; on a syntax error reports it and returns false.
  bool parse(tinyxml2::XMLDocument& doc);

  [[nodiscard]] SourceRange at(const tinyxml2::XMLElement* e) const;
  // Points at the attribute's value, or at its name when `atValue` is false.
  [[nodiscard]] SourceRange attributeAt(const tinyxml2::XMLElement* e, std::string_view attribute, bool atValue = true) const;

  Diagnostic& error(const tinyxml2::XMLElement* e, const std::string& message) { return diags_.error(at(e), message); }
  Diagnostic& attributeError(const tinyxml2::XMLElement* e, std::string_view attribute, const std::string& message) {
    return diags_.error(attributeAt(e, attribute), message);
  }
  Diagnostic& warning(const tinyxml2::XMLElement* e, const std::string& message) { return diags_.warning(at(e), message); }

  // Reports attributes not in `allowed` and child elements not in `children`.
  void checkAttributes(const tinyxml2::XMLElement* e, std::initializer_list<std::string_view> allowed);
  void checkChildren(const tinyxml2::XMLElement* e, std::initializer_list<std::string_view> allowed);

  std::optional<std::string> required(const tinyxml2::XMLElement* e, const char* attribute);
  std::optional<std::int64_t> integer(const tinyxml2::XMLElement* e, const char* attribute, std::int64_t min,
                                      std::int64_t max);
  // Durations: "500 MSEC", "2 SEC", "1 MIN", "250 USEC" and the short forms ms, s, min, us.
  std::optional<std::int64_t> durationMicros(const tinyxml2::XMLElement* e, const char* attribute);
  std::optional<double> number(const tinyxml2::XMLElement* e, const char* attribute);

  [[nodiscard]] DiagnosticEngine& diags() { return diags_; }
  [[nodiscard]] FileId file() const { return file_; }

 private:
  const SourceManager& sources_;
  FileId file_;
  DiagnosticEngine& diags_;
  mutable std::map<std::pair<std::uint32_t, std::string>, std::uint32_t> columns_;  // at(): (line, "<name") -> column, 0 if not found
};

// Splits a whitespace- or comma-separated list.
std::vector<std::string> splitList(std::string_view text);

}  // namespace semo::xml
