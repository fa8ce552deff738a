// Hostile nesting (issue 19): conditions, statements and formulas nested tens of thousands deep, and
// IR expressions likewise, end in one positioned error ("nested too deeply (limit 256)"), never in
// a stack overflow. The inputs are generated here, not stored.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

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

// How deep a tree is, without recursion (the trees below are what must not be deep).
template <typename Node>
std::size_t depthOf(const Node& root) {
  std::size_t deepest = 0;
  std::vector<std::pair<const Node*, std::size_t>> todo{{&root, 1}};
  while (!todo.empty()) {
    const auto [node, depth] = todo.back();
    todo.pop_back();
    deepest = std::max(deepest, depth);
    for (const Node& a : node->args) todo.emplace_back(&a, depth + 1);
  }
  return deepest;
}

// Long flat chains are not nesting: 200,000 terms joined by && (or ||, +, *) read into a balanced
// tree, written back as the same flat text; a chain of an operator that does not associate nests
// one level per operator, and past 1,024 levels it is an error, positioned at the expression.
TEST(NestingLimits, LongFlatIrChainsAreShallowTreesOrOneError) {
  const std::string terms = "x == 0" + repeat(" && x == 0", 199999);
  const std::string sum = "x" + repeat(" + x", 199999);
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const std::string text = "semo-ir 1\nvar x : 0..1 = 0;\nvar y : 0..3 = 0;\nrule r : " + terms + " -> y' = (" + sum + ") % 4;\n";
  const FileId file = sources.add("long.ir", text);
  std::optional<ir::Model> m = ir::parseText(sources, file, diags);
  ASSERT_TRUE(m.has_value());
  EXPECT_LE(depthOf(m->rules.at(0).guard), 20u) << "log2(200,000) + the comparison";
  EXPECT_LE(depthOf(m->rules.at(0).branches.at(0).assignments.at(0).value), 22u);
  // (EXPECT_TRUE, not EXPECT_EQ: a failure must not print megabytes.)
  EXPECT_TRUE(ir::toText(*m, m->rules.at(0).guard) == terms) << "written flat, as read";
  const std::string written = ir::toText(*m);
  EXPECT_NE(written.find(terms + " ->"), std::string::npos) << "the model's text holds the chain flat";
  SourceManager again;
  DiagnosticEngine againDiags(again);
  std::optional<ir::Model> reread = ir::parseText(again, again.add("written.ir", written), againDiags);
  ASSERT_TRUE(reread.has_value());
  EXPECT_TRUE(ir::toText(*reread) == written) << "read back and written again: the same bytes";
  EXPECT_LE(depthOf(ir::conjunction(std::vector<ir::Expr>(1000, ir::Expr::var(0)))), 11u);

  SourceManager sources2;
  DiagnosticEngine diags2(sources2);
  const FileId deep = sources2.add("minus.ir", "semo-ir 1\nvar x : 0..1 = 0;\nrule r : x - " + repeat("1 - ", 5000) + "1 < 0 -> x' = 1;\n");
  EXPECT_FALSE(ir::parseText(sources2, deep, diags2).has_value());
  ASSERT_EQ(diags2.diagnostics().size(), 1u);
  EXPECT_NE(diags2.diagnostics().front().message.find("expression nested too deeply (at least 5002 levels, limit 1024)"), std::string::npos)
      << diags2.diagnostics().front().message;
  EXPECT_EQ(diags2.diagnostics().front().range.begin.line, 3u);
  EXPECT_EQ(diags2.diagnostics().front().range.begin.column, 10u);
}

// The same in a mission: a condition of 100,000 `and`-ed tests parses into a shallow tree.
TEST(NestingLimits, LongFlatConditionsAreShallowTrees) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const FileId file = sources.add("long.semo", "Team: TurtlebotBurger b[2]\nTeam.Action.Go { if (Team.x == 1" + repeat(" and Team.x == 1", 99999) +
                                                   ") move(\"a\") }\n");
  const ast::Mission mission = parseMission(sources, file, diags);
  ASSERT_EQ(diags.errorCount(), 0u);
  const ast::Cond* cond = nullptr;
  for (const ast::Service& s : mission.services) {
    for (const ast::Stmt& st : s.body) {
      if (st.cond) cond = st.cond.get();
    }
  }
  ASSERT_NE(cond, nullptr);
  std::size_t deepest = 0;
  std::vector<std::pair<const ast::Cond*, std::size_t>> todo{{cond, 1}};
  while (!todo.empty()) {
    const auto [c, depth] = todo.back();
    todo.pop_back();
    deepest = std::max(deepest, depth);
    if (c->left) todo.emplace_back(c->left.get(), depth + 1);
    if (c->right) todo.emplace_back(c->right.get(), depth + 1);
  }
  EXPECT_LE(deepest, 18u) << "log2(100,000) + 1";
}

}  // namespace
}  // namespace semo
