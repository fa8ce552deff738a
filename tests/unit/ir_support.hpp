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

// Eight counters (0..3) that each count up by a fair rule and come back to 0 only all together, by
// a fair `reset` rule: a property that reads them all keeps every slice as large as the product,
// and a breadth-first search of 1,000 states holds no loop. The hunts' tests (liveness_test.cpp,
// lasso_walks_test.cpp) put their violation beside them.
struct ResettingCounters {
  std::string declarations;  // the counters and their tick rules (rules 0..7)
  std::string resetRule;     // the rule that sets them all back to 0 (put it after the others)
  std::string sum;           // c1 + ... + c8, for a property that reads every counter
};
inline ResettingCounters resettingCounters() {
  ResettingCounters out;
  std::string full, reset;
  for (int k = 1; k <= 8; ++k) {
    const std::string c = "c" + std::to_string(k);
    out.declarations += "var " + c + " : 0..3 = 0;\nrule tick" + std::to_string(k) + " @fair : " + c + " < 3 -> " + c + "' = " + c + " + 1;\n";
    out.sum += (out.sum.empty() ? "" : " + ") + c;
    full += (full.empty() ? "" : " && ") + c + " == 3";
    reset += (reset.empty() ? "" : ", ") + c + "' = 0";
  }
  out.resetRule = "rule reset @fair : " + full + " -> " + reset + ";\n";
  return out;
}

}  // namespace semo::test
