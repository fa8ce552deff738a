// The explicit search with symmetry on larger teams: a class of 24 found swap by swap, what each
// search's symmetry respects, skipping equal robots' rules, and threads that change nothing but
// the speed (split from explicit_search_test.cpp, whose models are counted by hand).
#include <gtest/gtest.h>

#include <cstdlib>

#include "semo/checker/explicit_search.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/symmetry.hpp"
#include "semo/checker/trace.hpp"
#include "ir_support.hpp"

namespace semo::checker {
namespace {

ir::Model parse(const std::string& text) { return test::parseIr(text); }

// 25 robots that count to 2 in two steps, each its own fairness group, but the last counts to 1
// only; an invariant reads them all. The 24 alike are one class (found swap by swap, each looking
// at the rules of the two robots it moves and at the invariant), the last stands alone.
TEST(Symmetry, ALargeClassIsFoundAndItsOrderingsArePrintedAsAPowerOfTen) {
  std::string text = "semo-ir 1;\nrobots";
  for (int r = 0; r < 25; ++r) text += " r" + std::to_string(r);
  text += ";\n";
  std::string all;
  for (int r = 0; r < 25; ++r) {
    const std::string n = "r" + std::to_string(r), top = r == 24 ? "1" : "2";
    text += "var " + n + ".c : 0..2 = 0 @robot(" + n + ");\n";
    text += "rule " + n + ".first @robot(" + n + ") @fair(" + n + ") : " + n + ".c == 0 -> " + n + ".c' = 1;\n";
    text += "rule " + n + ".second @robot(" + n + ") @fair(" + n + ") : " + n + ".c == 1 && " + n + ".c < " + top + " -> " + n + ".c' = 2;\n";
    all += (all.empty() ? "" : " + ") + n + ".c";
  }
  text += "invariant bounded : " + all + " <= 49;\n";
  ir::Model m = parse(text);
  Symmetry sym = Symmetry::find(m);
  const std::vector<std::string> classes = sym.describe(m);
  ASSERT_EQ(classes.size(), 1u);
  EXPECT_EQ(classes[0].rfind("r0 r1 r2 ", 0), 0u) << classes[0];
  EXPECT_NE(classes[0].find(" r23 (24! = 6.2e23 orderings)"), std::string::npos) << classes[0];
  EXPECT_EQ(classes[0].find("r24"), std::string::npos) << classes[0];
  // One state per multiset of the 24 counters (C(26, 2) = 325), times r24's two values.
  const SearchResult reduced = checkSafety(m, SearchLimits{});
  EXPECT_TRUE(reduced.complete);
  EXPECT_EQ(reduced.states, 650u);
}

// A property that names one robot sets it apart only where that property is read: the safety
// search and the other property's product keep all four robots interchangeable.
TEST(Symmetry, EachSearchSetsApartOnlyTheRobotsWhatItReadsNames) {
  std::string text = "semo-ir 1;\nrobots r0 r1 r2 r3;\n";
  std::string sum, all;
  for (int r = 0; r < 4; ++r) {
    const std::string n = "r" + std::to_string(r);
    text += "var " + n + ".c : 0..2 = 0 @robot(" + n + ");\n";
    text += "rule " + n + ".up @robot(" + n + ") @fair : " + n + ".c < 2 -> " + n + ".c' = " + n + ".c + 1;\n";
    sum += (sum.empty() ? "" : " + ") + n + ".c";
    all += (all.empty() ? "" : " && ") + n + ".c == 2";
  }
  text += "invariant bounded : " + sum + " <= 8;\n";
  text += "property first_ends : eventually {r0.c == 2};\n";
  text += "property all_end : eventually {" + all + "};\n";
  ir::Model m = parse(text);
  auto classOf = [&](const SymmetryScope& scope) {
    const std::vector<std::string> c = Symmetry::find(m, scope).describe(m);
    return c.size() == 1 ? c[0].substr(0, c[0].find(" (")) : std::string("(") + std::to_string(c.size()) + " classes)";
  };
  EXPECT_EQ(classOf({}), "r1 r2 r3");  // the whole model: first_ends names r0
  EXPECT_EQ(classOf(SymmetryScope::safety()), "r0 r1 r2 r3");
  EXPECT_EQ(classOf(SymmetryScope::liveness(0)), "r1 r2 r3");
  EXPECT_EQ(classOf(SymmetryScope::liveness(1)), "r0 r1 r2 r3");

  // Safety: one state per multiset of four counters of 0..2 (C(6, 2) = 15), not 3 * C(5, 2) = 30.
  const SearchResult safety = checkSafety(m, SearchLimits{});
  EXPECT_TRUE(safety.complete);
  EXPECT_EQ(safety.states, 15u);
  // Liveness: both proven, each product reduced, with the verdicts of the search without symmetry.
  LivenessOptions whole;
  whole.slicing = false;
  const LivenessResult reduced = checkLiveness(m, SearchLimits{}, whole);
  SearchLimits plain;
  plain.symmetry = false;
  const LivenessResult full = checkLiveness(m, plain, whole);
  ASSERT_EQ(reduced.properties.size(), 2u);
  EXPECT_EQ(reduced.reducedProperties, 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(reduced.properties[p].verdict, Verdict::Proven) << reduced.properties[p].name;
    EXPECT_EQ(full.properties[p].verdict, Verdict::Proven) << full.properties[p].name;
  }
  EXPECT_LT(reduced.states, full.states);
}

// Two searches that must report the same: counts, depth, verdicts, counterexamples step by step.
void expectSameSearch(const SearchResult& a, const SearchResult& b) {
  EXPECT_EQ(a.states, b.states);
  EXPECT_EQ(a.transitions, b.transitions);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.complete, b.complete);
  ASSERT_EQ(a.properties.size(), b.properties.size());
  for (std::size_t p = 0; p < a.properties.size(); ++p) {
    EXPECT_EQ(a.properties[p].verdict, b.properties[p].verdict) << a.properties[p].name;
    ASSERT_EQ(a.properties[p].counterexample.has_value(), b.properties[p].counterexample.has_value()) << a.properties[p].name;
    if (!a.properties[p].counterexample) continue;
    const Trace& x = *a.properties[p].counterexample;
    const Trace& y = *b.properties[p].counterexample;
    ASSERT_EQ(x.steps.size(), y.steps.size());
    for (std::size_t k = 0; k < x.steps.size(); ++k) EXPECT_EQ(x.steps[k].rule, y.steps[k].rule) << "step " << k;
  }
}

// Six robots that find a fact (one of them, once) or learn it from one that holds it, then count
// to 2; invariants over the team, one violated. Rules of one robot and of pairs of robots.
std::string gossipTeam(const std::string& violated) {
  std::string text = "semo-ir 1;\nrobots";
  for (int r = 0; r < 6; ++r) text += " r" + std::to_string(r);
  text += ";\nvar found : bool = false;\n";
  std::string all;
  for (int r = 0; r < 6; ++r) {
    const std::string n = "r" + std::to_string(r);
    text += "var " + n + ".k : bool = false @robot(" + n + ");\nvar " + n + ".c : 0..2 = 0 @robot(" + n + ");\n";
  }
  for (int r = 0; r < 6; ++r) {
    const std::string n = "r" + std::to_string(r);
    text += "rule " + n + ".find @robot(" + n + ") : !found && !" + n + ".k -> found' = true, " + n + ".k' = true;\n";
    for (int q = 0; q < 6; ++q) {
      if (q == r) continue;
      const std::string o = "r" + std::to_string(q);
      text += "rule " + n + ".learn." + o + " @robot(" + n + ") : !" + n + ".k && " + o + ".k -> " + n + ".k' = true;\n";
    }
    text += "rule " + n + ".count @robot(" + n + ") : " + n + ".k && " + n + ".c < 2 -> " + n + ".c' = " + n + ".c + 1;\n";
    all += (all.empty() ? "" : " + ") + n + ".c";
  }
  return text + "invariant bounded : " + all + " <= 12;\ninvariant small : " + all + " <= " + violated + ";\n";
}

// Skipping the rules that a swap of equal neighbouring robots maps to lower ones changes nothing
// the search reports: states, transitions, depth, verdicts and counterexamples, on any threads.
TEST(Symmetry, SkippingTheRulesOfEqualRobotsChangesNoResult) {
  for (const std::string& model : {gossipTeam("9"), gossipTeam("12")}) {
    const ir::Model m = parse(model);
    ASSERT_FALSE(Symmetry::find(m).empty());
    for (unsigned threads : {1u, 2u}) {
      SearchLimits limits;
      limits.threads = threads;
      setenv("SEMO_NO_EQUAL_ROBOT_PRUNING", "1", 1);
      const SearchResult every = checkSafety(m, limits);
      unsetenv("SEMO_NO_EQUAL_ROBOT_PRUNING");
      const SearchResult pruned = checkSafety(m, limits);
      EXPECT_GT(every.states, 20u);
      EXPECT_EQ(every.transitionsSkipped, 0u);
      EXPECT_GT(pruned.transitionsSkipped, every.transitions / 4) << "the rules of equal robots are skipped";
      expectSameSearch(pruned, every);
    }
  }
}

TEST(ExplicitSearch, ThreadsChangeNothingButSpeed) {
  std::size_t models = test::forEachShippedModel([](const std::string&, const std::string& text) {
    ir::Model m = parse(text);
    for (bool symmetry : {false, true}) {
      SearchLimits one, three;
      one.symmetry = three.symmetry = symmetry;
      one.threads = 1;
      three.threads = 3;
      SearchResult a = checkSafety(m, one), b = checkSafety(m, three);
      expectSameSearch(a, b);
    }
  });
  EXPECT_GE(models, 8u);
}

}  // namespace
}  // namespace semo::checker
