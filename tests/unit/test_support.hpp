#pragma once
// Helpers for unit tests: parse text held in memory and collect its diagnostics.
#include <string>

#include "semo/frontend/ast.hpp"
#include "semo/frontend/parser.hpp"

namespace semo::test {

struct Parsed {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  ast::Mission mission;
  // "line:col: message" of every diagnostic, for readable assertions.
  [[nodiscard]] std::vector<std::string> messages() const {
    std::vector<std::string> out;
    for (const Diagnostic& d : diags.diagnostics()) {
      out.push_back(std::to_string(d.range.begin.line) + ":" + std::to_string(d.range.begin.column) + ": " + d.message);
    }
    return out;
  }
};

inline std::unique_ptr<Parsed> parse(const std::string& text) {
  auto p = std::make_unique<Parsed>();
  FileId file = p->sources.add("test.semo", text);
  p->mission = parseMission(p->sources, file, p->diags);
  return p;
}

}  // namespace semo::test
