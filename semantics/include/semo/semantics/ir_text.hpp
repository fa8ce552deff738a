#pragma once
// The plain-text form of the IR (specs/ir.md): semo writes it (`semo-verify export --ir`) and reads
// it (`semo-verify check model.ir`), so that every engine can also run on models written by hand.
#include <optional>
#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::ir {

std::string toText(const Model& model);
std::string toText(const Model& model, const Expr& e);
std::string toText(const Model& model, const Ltl& f);  // atoms in braces: always ({x == 1} => eventually {y > 0})

// Parses a model; errors (with positions) go to `diags`; nullopt if there was any.
// Whether a text is an IR model: its first word, after blank lines and `#` comments, is `semo-ir`.
bool looksLikeIr(const std::string& text);

std::optional<Model> parseText(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo::ir
