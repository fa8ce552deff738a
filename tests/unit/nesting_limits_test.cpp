// Hostile nesting (issue 19): conditions, statements and formulas nested tens of thousands deep, and
// IR expressions likewise, end in one positioned error ("nested too deeply (limit 256)"), never in
// a stack overflow. The inputs are generated here, not stored.
#include <gtest/gtest.h>

#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/parser.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo {
namespace {

std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

// Parses a mission text; returns the diagnostics printed.
std::string parseMissionText(const std::string& text, std::size_t& errors) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const FileId file = sources.add("deep.semo", text);
  parseMission(sources, file, diags);
  errors = diags.errorCount();
  std::string out;
  for (const Diagnostic& d : diags.diagnostics()) out += d.message + "\n";
  return out;
}

TEST(NestingLimits, DeepConditionsStatementsAndFormulasAreErrorsNotCrashes) {
  const std::string head = "Team: TurtlebotBurger b[2]\n";
  std::size_t errors = 0;
  std::string out = parseMissionText(head + "Team.Action.Go { if (" + repeat("(", 20000) + "Team.x == 1" + repeat(")", 20000) + ") move(\"a\") }\n", errors);
  EXPECT_NE(out.find("nested too deeply (limit 256)"), std::string::npos) << out.substr(0, 300);
  EXPECT_LE(errors, 3u) << "one error, not one per level";
  out = parseMissionText(head + "Team.Action.Go { " + repeat("if (Team.x == 1) { ", 100000) + "move(\"a\")" + repeat(" }", 100000) + " }\n", errors);
  EXPECT_NE(out.find("nested too deeply (limit 256)"), std::string::npos) << out.substr(0, 300);
  EXPECT_LE(errors, 3u);
  out = parseMissionText(head + "Team.Action.Go { if (" + repeat("not ", 50000) + "Team.x == 1) move(\"a\") }\n", errors);
  EXPECT_NE(out.find("nested too deeply (limit 256)"), std::string::npos);
  out = parseMissionText(head + "verify { property p: always " + repeat("(", 20000) + "b_0.alive" + repeat(")", 20000) + " }\n", errors);
  EXPECT_NE(out.find("nested too deeply (limit 256)"), std::string::npos);
  // Within the limit, deep but legal nesting parses.
  out = parseMissionText(head + "Team.Action.Go { if (" + repeat("(", 200) + "Team.x == 1" + repeat(")", 200) + ") move(\"a\") }\n", errors);
  EXPECT_EQ(errors, 0u) << out;
}

TEST(NestingLimits, DeepIrExpressionsAreErrorsNotCrashes) {
  for (const std::string& guard : {repeat("(", 20000) + "x == 0" + repeat(")", 20000), repeat("!", 20000) + "(x == 0)",
                                   repeat("x == 0 => ", 20000) + "x == 0", repeat("x == 0 ? 1 : ", 20000) + "0"}) {
    SourceManager sources;
    DiagnosticEngine diags(sources);
    const FileId file = sources.add("deep.ir", "semo-ir 1;\nvar x : 0..1 = 0;\nrule r : " + guard + " -> x' = 1;\n");
    EXPECT_FALSE(ir::parseText(sources, file, diags).has_value());
    ASSERT_FALSE(diags.diagnostics().empty());
    EXPECT_NE(diags.diagnostics().front().message.find("nested too deeply (limit 256)"), std::string::npos) << diags.diagnostics().front().message;
    EXPECT_EQ(diags.diagnostics().front().range.begin.line, 3u);
  }
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const FileId file = sources.add("ok.ir", "semo-ir 1;\nvar x : 0..1 = 0;\nrule r : " + repeat("(", 200) + "x == 0" + repeat(")", 200) + " -> x' = 1;\n");
  EXPECT_TRUE(ir::parseText(sources, file, diags).has_value()) << "200 levels are within the limit";
}

}  // namespace
}  // namespace semo
