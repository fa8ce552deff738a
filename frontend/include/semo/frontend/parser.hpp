#pragma once
#include "semo/frontend/ast.hpp"
#include "semo/frontend/diagnostics.hpp"

namespace semo {

// Parses a whole mission file. Syntax errors are reported to `diags`; the parser recovers at
// statement and definition boundaries, so the returned AST holds everything that parsed.
ast::Mission parseMission(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo
