#pragma once
// Reading a JSON file into nlohmann::json with semo's diagnostics: a NUL byte, a syntax error or a
// number too large for a double is reported at its line and column (bytes, as everywhere in semo),
// and nothing is returned. Shared by every reader of a JSON input (task graphs, traces).
#include <nlohmann/json.hpp>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"

namespace semo {

// The line and column of a byte offset of `text` (the file's contents).
SourceRange jsonRangeAt(FileId file, const std::string& text, std::size_t offset);

// The offset of the first bracket of `text` nested deeper than `limit` (brackets inside strings do
// not count), if there is one. Readers refuse such input before the parser sees it: code that walks
// the parsed value (and JSON pointers to its members, whose length grows with the depth) would pay
// for a depth bomb quadratically.
std::optional<std::size_t> jsonNestedDeeperThan(std::string_view text, std::size_t limit);

// Parses the file's text (nested at most kMaxNesting deep); nullopt (with one error) when it is not JSON.
std::optional<nlohmann::json> parseJsonFile(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo
