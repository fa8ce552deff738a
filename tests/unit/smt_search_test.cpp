// The SMT engine on the shipped hand-written IR models and tiny ones: bounded model checking
// agrees with the explicit engine bounded to the same depth (same violations, shortest
// counterexamples of the same length), and k-induction proves what holds.
#include <gtest/gtest.h>

#include <algorithm>

#include "semo/checker/explicit_search.hpp"
#include "semo/checker/smt_search.hpp"
#include "ir_support.hpp"

namespace semo::checker {
namespace {

TEST(SmtSearch, BoundedModelCheckingAgreesWithBoundedExplicitSearch) {
  for (std::uint32_t depth : {2u, 5u}) {
    std::size_t models = test::forEachShippedModel([&](const std::string&, const std::string& text) {
      ir::Model m = test::parseIr(text);
      SearchLimits limits;
      limits.maxDepth = depth;
      limits.symmetry = false;
      SearchResult explicitResult = checkSafety(m, limits);
      SmtOptions options;
      options.maxDepth = depth;
      options.induction = false;
      options.ic3 = false;
      SmtResult smt = checkSafetySmt(m, options);
      ASSERT_EQ(smt.search.properties.size(), explicitResult.properties.size());
      for (std::size_t j = 0; j < smt.search.properties.size(); ++j) {
        const PropertyResult& a = explicitResult.properties[j];
        const PropertyResult& b = smt.search.properties[j];
        SCOPED_TRACE(a.name + " at depth " + std::to_string(depth));
        EXPECT_EQ(a.verdict == Verdict::Violated, b.verdict == Verdict::Violated);
        if (a.counterexample && b.counterexample) {
          EXPECT_EQ(a.counterexample->steps.size(), b.counterexample->steps.size());
        }
        // A proof needs the whole state space (explicit) or no longer path (BMC): never the other way round.
        if (b.verdict == Verdict::Proven) {
          EXPECT_EQ(a.verdict, Verdict::Proven);
        }
      }
    });
    EXPECT_GE(models, 5u);
  }
}

TEST(SmtSearch, KInductionProvesAnInvariantOfAnUnboundedlyLongRun) {
  // x counts up and wraps round for ever: BMC never runs out of paths, induction proves the range
  // of y at k = 1, and `x != 5 || y == 1` needs two steps of history.
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..9 = 0;\nvar y : 0..1 = 0;\n"
                              "rule tick @fair : true -> x' = (x + 1) % 10, y' = x == 4;\n"
                              "invariant y_small : y <= 1;\ninvariant y_after_four : x != 5 || y == 1;\n");
  SmtOptions options;
  options.maxDepth = 12;
  SmtResult r = checkSafetySmt(m, options);
  ASSERT_EQ(r.search.properties.size(), 2u);
  EXPECT_EQ(r.search.properties[0].verdict, Verdict::Proven);
  EXPECT_EQ(r.search.properties[1].verdict, Verdict::Proven);
  EXPECT_EQ(r.inductionDepth[0], 1u);
  EXPECT_GE(r.inductionDepth[1], 1u);
  EXPECT_FALSE(r.search.complete) << "the run never ends: only induction proves anything";
}

TEST(SmtSearch, AViolationBeyondTheBoundIsNotProvenAndIc3FindsIt) {
  // The bad state is 8 steps away: BMC to 5 misses it and induction must not prove it; IC3 finds
  // it and BMC rebuilds the path at that depth.
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..9 = 0;\nrule inc @fair : x < 9 -> x' = x + 1;\n"
                              "invariant below_eight : x < 8;\n");
  SmtOptions options;
  options.maxDepth = 5;
  options.ic3 = false;
  SmtResult r = checkSafetySmt(m, options);
  EXPECT_EQ(r.search.properties[0].verdict, Verdict::Unknown);
  options.ic3 = true;
  r = checkSafetySmt(m, options);
  ASSERT_EQ(r.search.properties[0].verdict, Verdict::Violated);
  EXPECT_EQ(r.search.properties[0].counterexample->steps.size(), 8u);
  EXPECT_TRUE(r.deepCounterexample[0]);
  options.maxDepth = 8;
  options.ic3 = false;
  r = checkSafetySmt(m, options);
  ASSERT_EQ(r.search.properties[0].verdict, Verdict::Violated);
  EXPECT_EQ(r.search.properties[0].counterexample->steps.size(), 8u);
  EXPECT_FALSE(r.deepCounterexample[0]);
}

TEST(SmtSearch, Ic3ProvesWhatNeedsAStrengthening) {
  // Two counters in lock step round a cycle of 21: `not (x == 0 and y == 10)` holds, but every
  // state of the cycle x - y = 11 (mod 21) leads to the bad one along a loop-free path of up to 20
  // steps, so k-induction needs k = 21; IC3 learns x == y.
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..20 = 0;\nvar y : 0..20 = 0;\n"
                              "rule tick @fair : true -> x' = x == 20 ? 0 : x + 1, y' = y == 20 ? 0 : y + 1;\n"
                              "invariant apart : !(x == 0 && y == 10);\n");
  SmtOptions options;
  options.maxDepth = 4;
  options.ic3 = false;
  SmtResult r = checkSafetySmt(m, options);
  EXPECT_EQ(r.search.properties[0].verdict, Verdict::Unknown);
  options.ic3 = true;
  r = checkSafetySmt(m, options);
  EXPECT_EQ(r.search.properties[0].verdict, Verdict::Proven);
  EXPECT_EQ(r.proof[0], SmtProof::Ic3);
  EXPECT_GE(r.invariantConjuncts[0], 1u);
  // The explicit engine agrees (the whole cycle of 21 states).
  EXPECT_EQ(checkSafety(m, {}).properties[0].verdict, Verdict::Proven);
}

TEST(SmtSearch, Ic3FindsARangeErrorBeyondTheBound) {
  // x leaves its range 0..5 at the sixth step: BMC to 3 cannot see it, IC3 on the ranges does, and
  // nothing is proven in a model with an error.
  ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..5 = 0;\nrule inc @fair : x < 7 -> x' = x + 1;\n"
                              "invariant small : x < 100;\n");
  SmtOptions options;
  options.maxDepth = 3;
  SmtResult r = checkSafetySmt(m, options);
  ASSERT_TRUE(r.search.rangeError.has_value());
  EXPECT_EQ(r.search.rangeError->steps.size(), 6u);
  EXPECT_NE(r.search.properties[0].verdict, Verdict::Proven);
}

TEST(SmtSearch, BoundedModelCheckingFindsARangeErrorWithinTheBound) {
  // The ranges are not kept by every step (x = 5 steps out), so BMC looks for a range error at each
  // depth and finds the shortest, as the explicit engine does; where every step keeps them (y), it
  // need not look, and a model without an error still proves its invariant.
  ir::Model bad = test::parseIr("semo-ir 1;\nvar x : 0..5 = 3;\nrule inc @fair : x < 7 -> x' = x + 1;\n"
                                "invariant small : x < 100;\n");
  SmtOptions options;
  options.maxDepth = 5;
  SmtResult r = checkSafetySmt(bad, options);
  ASSERT_TRUE(r.search.rangeError.has_value());
  EXPECT_EQ(r.search.rangeError->steps.size(), 3u);
  EXPECT_EQ(r.search.rangeError->steps.size(), checkSafety(bad, {}).rangeError->steps.size());
  ir::Model good = test::parseIr("semo-ir 1;\nvar y : 0..5 = 3;\nrule inc @fair : y < 5 -> y' = y + 1;\n"
                                 "invariant small : y >= 3;\n");
  SmtResult g = checkSafetySmt(good, options);
  EXPECT_FALSE(g.search.rangeError.has_value());
  EXPECT_EQ(g.search.properties[0].verdict, Verdict::Proven);
}

TEST(SmtSearch, RangesKeptByEveryOutcomeNeedNoProofOfTheirOwn) {
  // No induction to carry the ranges along (as when only LTL properties are checked): each rule
  // outcome keeps them (`reset` is never enabled within them), so they are taken as 1-inductive and
  // IC3 is not run on them. A second assignment of one outcome leaving its range is still seen, and
  // found by IC3.
  const std::string kept = "semo-ir 1;\nvar x : 0..5 = 0;\nvar y : 0..3 = 0;\n"
                           "rule inc @fair : x < 5 -> x' = x + 1, y' = y;\n"
                           "rule reset @fair : x > 5 -> x' = 100;\n"
                           "rule wrap @fair : x == 5 -> x' = 0, y' = (y + 1) % 4;\n"
                           "property settles : always eventually {x == 0};\n";
  std::vector<std::string> phases;
  SmtOptions options;
  options.maxDepth = 2;
  options.induction = false;
  options.onPhase = [&phases](const std::string& p) { phases.push_back(p); };
  SmtResult r = checkSafetySmt(test::parseIr(kept), options);
  EXPECT_FALSE(r.search.rangeError.has_value());
  EXPECT_TRUE(r.note.empty()) << r.note;
  for (const std::string& p : phases) EXPECT_EQ(p.find("ranges"), std::string::npos) << p;

  std::string leaves = kept;
  leaves.replace(leaves.find("(y + 1) % 4"), 11, "y + 1");  // y reaches 4 on the fourth wrap
  phases.clear();
  r = checkSafetySmt(test::parseIr(leaves), options);
  ASSERT_TRUE(r.search.rangeError.has_value());
  EXPECT_EQ(r.search.rangeError->steps.size(), 24u);
  EXPECT_EQ(r.search.rangeError->steps.size(), checkSafety(test::parseIr(leaves), {}).rangeError->steps.size());
  bool ic3OnRanges = false;
  for (const std::string& p : phases) ic3OnRanges = ic3OnRanges || p == "smt: IC3 on the variables' ranges";
  EXPECT_TRUE(ic3OnRanges);
}

TEST(SmtSearch, SaysWhenTheRangesHoldSoThatTheLivenessSearchMayStartBesideTheProofs) {
  // verify.cpp starts the LTL properties' search once no range error can exist. Ranges that hold
  // initially and are kept by every step are known before BMC's first depth; ranges an induction
  // proves (together with an invariant), once it has; a model with a range error never says so.
  std::vector<std::string> events;
  SmtOptions options;
  options.maxDepth = 2;
  options.onPhase = [&events](const std::string& p) { events.push_back(p); };
  options.onRangesHold = [&events] { events.emplace_back("ranges hold"); };
  const auto told = [&events] { return std::count(events.begin(), events.end(), "ranges hold"); };

  SmtResult kept = checkSafetySmt(test::parseIr("semo-ir 1;\nvar x : 0..9 = 0;\nrule tick @fair : true -> x' = (x + 1) % 10;\n"
                                                "invariant small : x < 10;\n"),
                                  options);
  EXPECT_EQ(kept.search.properties[0].verdict, Verdict::Proven);
  ASSERT_EQ(told(), 1);
  EXPECT_EQ(events.front(), "ranges hold") << "before any BMC depth";

  // From x == 5 (within 0..5, never reached) `jump` leaves the range: not kept by every step, but
  // inductive together with `low`, at k = 1.
  events.clear();
  SmtResult induced = checkSafetySmt(test::parseIr("semo-ir 1;\nvar x : 0..5 = 0;\nrule inc @fair : x < 3 -> x' = x + 1;\n"
                                                   "rule jump @fair : x == 5 -> x' = x + 1;\ninvariant low : x <= 3;\n"),
                                     options);
  EXPECT_FALSE(induced.search.rangeError.has_value());
  EXPECT_EQ(induced.search.properties[0].verdict, Verdict::Proven);
  ASSERT_EQ(told(), 1);
  const auto said = std::find(events.begin(), events.end(), "ranges hold");
  EXPECT_NE(std::find(events.begin(), said, "smt: k-induction, k = 1 of 3"), said) << "after the induction that proved them";

  events.clear();
  options.maxDepth = 3;
  SmtResult error = checkSafetySmt(test::parseIr("semo-ir 1;\nvar x : 0..5 = 0;\nrule inc @fair : x < 7 -> x' = x + 1;\n"
                                                 "invariant small : x < 100;\n"),
                                   options);
  EXPECT_TRUE(error.search.rangeError.has_value());
  EXPECT_EQ(told(), 0);
}

TEST(SmtSearch, TruncatingDivisionAsTheExplicitEngine) {
  // -7 / 2 = -3 and -7 % 2 = -1 in C (and in the explicit engine); x / 0 = 0.
  ir::Model m = test::parseIr("semo-ir 1;\nvar a : -9..9 = -7;\nvar q : -9..9 = 0;\nvar r : -9..9 = 0;\nvar z : -9..9 = 5;\n"
                              "rule go : q == 0 -> q' = a / 2, r' = a % 2, z' = a / 0;\n"
                              "invariant c_division : q == 0 || (q == -3 && r == -1 && z == 0);\n");
  SmtOptions options;
  options.maxDepth = 3;
  SmtResult r = checkSafetySmt(m, options);
  EXPECT_EQ(r.search.properties[0].verdict, Verdict::Proven);
  SearchResult e = checkSafety(m, {});
  EXPECT_EQ(e.properties[0].verdict, Verdict::Proven);
}

}  // namespace
}  // namespace semo::checker
