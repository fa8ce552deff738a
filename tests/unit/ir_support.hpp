#pragma once
// Helpers for the unit tests of the IR and its engines: read IR text held in memory, and walk the
// hand-written models shipped in tests/e2e/ir.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "semo/semantics/ir_text.hpp"

namespace semo::test {

// The model, or an empty one with a test failure per diagnostic.
inline ir::Model parseIr(const std::string& text) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  FileId file = sources.add("test.ir", text);
  std::optional<ir::Model> m = ir::parseText(sources, file, diags);
  if (!m) {
    for (const Diagnostic& d : diags.diagnostics()) ADD_FAILURE() << d.range.begin.line << ":" << d.range.begin.column << ": " << d.message;
    return {};
  }
  return *m;
}

// Calls f(path, text) for every .ir file of tests/e2e/ir; returns how many there were.
template <typename F>
std::size_t forEachShippedModel(F f) {
  std::size_t models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SEMO_SOURCE_DIR "/tests/e2e/ir")) {
    if (entry.path().extension() != ".ir") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    SCOPED_TRACE(entry.path().string());
    f(entry.path().string(), text.str());
    ++models;
  }
  return models;
}

}  // namespace semo::test
