#pragma once
// Reading a JSON file into nlohmann::json with semo's diagnostics: a NUL byte, a syntax error or a
// number too large for a double is reported at its line and column (bytes, as everywhere in semo),
// and nothing is returned. Shared by every reader of a JSON input (task graphs, traces).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"

namespace semo {

// The line and column of a byte offset of `text` (the file's contents).
SourceRange jsonRangeAt(FileId file, const std::string& text, std::size_t offset);

// Parses the file's text; nullopt (with one error) when it is not JSON.
std::optional<nlohmann::json> parseJsonFile(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo
