// Which rules a run can take infinitely often (checker/src/recurring_rules.hpp), and the searches
// that narrow their loops with it: on a model written for it, an event thrown once is delivered
// finitely often, and a world that never senses the other way starts no new cycle; on random
// models, the symbolic search of every world with its loops narrowed, and the search of the exact
// cone that uses it, give the explicit search's verdicts with lassos that pass the independent check.
#include <gtest/gtest.h>

#include <numeric>

#include "../../checker/src/recurring_rules.hpp"
#include "../../checker/src/sliced_liveness.hpp"
#include "../../checker/src/symbolic_liveness.hpp"
#include "ir_support.hpp"
#include "random_model.hpp"
#include "semo/checker/compiled_model.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/slicing.hpp"

namespace semo::checker {
namespace {

using detail::LoopNarrowing;
using detail::RecurringRules;
using detail::SymbolicOutcome;

// A robot that throws an event once and then ticks for ever; its teammate catches the event and
// changes mode. A sensor read on each tick throws an alarm when it reads dark.
constexpr const char* kThrowOnce = R"(semo-ir 1;
robots a b;
var a.pc : 0..2 = 0 @robot(a);
var b.ev : bool = false @robot(b);
var b.mode : 0..1 = 0 @robot(b);
var b.alarm : bool = false @robot(b);
rule a.throw @robot(a) @fair : a.pc == 0 -> a.pc' = 1, b.ev' = true;
rule a.tick @robot(a) @fair(a.loop) @senses("dark=0") : a.pc == 1 -> a.pc' = 2;
rule a.alarm @robot(a) @fair(a.loop) @senses("dark=1") : a.pc == 1 -> a.pc' = 2, b.alarm' = true;
rule a.tock @robot(a) @fair : a.pc == 2 -> a.pc' = 1;
rule b.deliver @robot(b) @kind(delivery) @strongly_fair : b.ev -> b.ev' = false, b.mode' = 1;
rule b.hears_alarm @robot(b) @kind(delivery) @strongly_fair : b.alarm -> b.alarm' = false, b.mode' = 1 - b.mode;
property agree @settled : always eventually {b.mode == 0};
)";

LivenessResult explicitSearch(const ir::Model& m) {
  LivenessOptions whole;
  whole.slicing = false;
  return checkLiveness(m, SearchLimits{}, whole);
}

std::vector<std::string> names(const ir::Model& m, const std::vector<char>& marks) {
  std::vector<std::string> out;
  for (std::size_t r = 0; r < marks.size(); ++r) {
    if (marks[r] != 0) out.push_back(m.rules[r].name);
  }
  return out;
}

// The search of every world with its loops narrowed to the rules that can recur, as the exact
// cone runs it (on the whole model here: every rule is the cut model's).
struct NarrowedSearch {
  explicit NarrowedSearch(const ir::Model& m) : recurring(m), narrowing(recurring, m, everyRule(m)) {
    limits.narrowing = &narrowing;
    limits.everyWorld = true;
  }
  NarrowedSearch(const NarrowedSearch&) = delete;
  NarrowedSearch& operator=(const NarrowedSearch&) = delete;
  static std::vector<std::uint32_t> everyRule(const ir::Model& m) {
    std::vector<std::uint32_t> identity(m.rules.size());
    std::iota(identity.begin(), identity.end(), 0u);
    return identity;
  }
  RecurringRules recurring;
  LoopNarrowing narrowing;
  detail::SymbolicLimits limits;
};

TEST(RecurringRules, AStepOnNoCycleAndWhatOnlyItEnablesCannotRecur) {
  const ir::Model m = test::parseIr(kThrowOnce);
  const RecurringRules recurring(m);
  // Every rule allowed: the throw leaves a.pc = 0 for good, so the event's flag, set only by it,
  // has no cycle either, and its delivery happens at most once.
  EXPECT_EQ(names(m, recurring.narrow(std::vector<char>(m.rules.size(), 1))),
            (std::vector<std::string>{"a.tick", "a.alarm", "a.tock", "b.hears_alarm"}));
  // A world that never reads dark again: no new alarm, so no alarm is heard for ever.
  std::vector<char> bright(m.rules.size(), 1);
  bright[2] = 0;  // a.alarm
  EXPECT_EQ(names(m, recurring.narrow(bright)), (std::vector<std::string>{"a.tick", "a.tock"}));
}

TEST(RecurringRules, TheSearchOfEveryWorldProvesWhatOnlyANarrowedLoopCouldBreak) {
  const ir::Model m = test::parseIr(kThrowOnce);
  const NarrowedSearch narrowed(m);
  const detail::SymbolicLimits& limits = narrowed.limits;
  // In a dark world b's mode flips for ever (it is 0 again and again); in a bright one it settles
  // at 1 after the one delivery: a violation either way, found with the loops narrowed too.
  const SymbolicOutcome s = detail::decideSymbolically(m, 0, limits);
  ASSERT_EQ(s.kind, SymbolicOutcome::Kind::Violation) << s.why;
  ASSERT_TRUE(s.lasso.has_value());
  EXPECT_TRUE(checkLasso(m, *s.lasso, m.properties[0]).counterexample());
  EXPECT_EQ(s.worlds, 1u);  // the first world searched (dark=0) has it
}

// The same robot glancing left or right between ticks: which way it looks narrows nothing but the
// two glances, so the search of every world leaves that condition open (its two worlds searched as
// one) and decides only whether it reads dark.
TEST(RecurringRules, AConditionWhoseDecidingNarrowsNothingElseIsSearchedBothWaysAtOnce) {
  std::string text = kThrowOnce;
  const std::string tock = "rule a.tock @robot(a) @fair : a.pc == 2 -> a.pc' = 1;";
  text.replace(text.find(tock), tock.size(),
               "rule a.glance_left @robot(a) @fair(a.glance) @senses(\"left=1\") : a.pc == 2 -> a.pc' = 1;\n"
               "rule a.glance_right @robot(a) @fair(a.glance) @senses(\"left=0\") : a.pc == 2 -> a.pc' = 1;");
  text += "property ticks @settled : always eventually {a.pc == 1};\n";
  const ir::Model m = test::parseIr(text);
  const LivenessResult reference = explicitSearch(m);
  const NarrowedSearch narrowed(m);
  for (std::size_t k = 0; k < m.properties.size(); ++k) {
    SCOPED_TRACE(m.properties[k].name);
    const SymbolicOutcome s = detail::decideSymbolically(m, k, narrowed.limits);
    EXPECT_EQ(s.openPoints, 1u);  // left, not dark
    EXPECT_EQ(s.kind == SymbolicOutcome::Kind::Violation, reference.properties[k].verdict == Verdict::Violated);
    if (s.kind == SymbolicOutcome::Kind::Violation) {
      ASSERT_TRUE(s.lasso.has_value());
      EXPECT_TRUE(checkLasso(m, *s.lasso, m.properties[k]).counterexample());
      EXPECT_EQ(s.worlds, 1u);  // dark=0, either glance
    } else {
      EXPECT_EQ(s.kind, SymbolicOutcome::Kind::NoViolation) << s.why;
      EXPECT_EQ(s.worlds, 2u);  // dark=0 and dark=1, each with either glance
    }
  }
  EXPECT_EQ(reference.properties[0].verdict, Verdict::Violated);
  EXPECT_EQ(reference.properties[1].verdict, Verdict::Proven);
}

// The soundness claim, tested where the explicit search is the reference: on random models, every
// world searched with its loops narrowed gives the same verdict, and each lasso passes the check.
TEST(RecurringRules, RandomModelsWithNarrowedLoopsGetTheExplicitVerdicts) {
  int narrowedRules = 0, violated = 0, proven = 0, manyWorlds = 0, leftOpen = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(300); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    const LivenessResult reference = explicitSearch(m);
    ASSERT_TRUE(reference.complete);
    const NarrowedSearch narrowed(m);
    const std::vector<char> recur = narrowed.recurring.narrow(std::vector<char>(m.rules.size(), 1));
    narrowedRules += static_cast<int>(std::count(recur.begin(), recur.end(), 0));
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      SCOPED_TRACE(m.properties[k].name);
      detail::SymbolicLimits limits = narrowed.limits;
      const SymbolicOutcome s = detail::decideSymbolically(m, k, limits);
      ASSERT_NE(s.kind, SymbolicOutcome::Kind::GaveUp) << s.why;
      EXPECT_EQ(s.kind == SymbolicOutcome::Kind::Violation, reference.properties[k].verdict == Verdict::Violated);
      // The worlds shared with a forked helper (shared_worlds.hpp): the same outcome, the same
      // world, the same lasso, whichever process searched which world.
      limits.worldsHelper = true;
      const SymbolicOutcome shared = detail::decideSymbolically(m, k, limits);
      EXPECT_EQ(shared.kind, s.kind);
      EXPECT_EQ(shared.worlds, s.worlds);
      EXPECT_EQ(shared.lasso.has_value(), s.lasso.has_value());
      if (shared.lasso && s.lasso) {
        EXPECT_EQ(shared.lasso->initial, s.lasso->initial);
        EXPECT_EQ(shared.lasso->loopStart, s.lasso->loopStart);
        ASSERT_EQ(shared.lasso->steps.size(), s.lasso->steps.size());
        for (std::size_t i = 0; i < s.lasso->steps.size(); ++i) EXPECT_EQ(shared.lasso->steps[i].rule, s.lasso->steps[i].rule);
      }
      manyWorlds += s.worlds > 1 ? 1 : 0;
      leftOpen += s.openPoints > 0 ? 1 : 0;
      if (s.kind != SymbolicOutcome::Kind::Violation) {
        ++proven;
        continue;
      }
      ++violated;
      ASSERT_TRUE(s.lasso.has_value());
      EXPECT_TRUE(checkLasso(m, *s.lasso, m.properties[k]).counterexample());
    }
  }
  EXPECT_GT(narrowedRules, test::atLeast(50));  // the narrowing left rules out, and the verdicts held
  EXPECT_GT(proven, test::atLeast(50));
  EXPECT_GT(violated, test::atLeast(50));
  EXPECT_GT(manyWorlds, test::atLeast(20));  // searches that went past the first world
  EXPECT_GT(leftOpen, test::atLeast(100));   // searches with a condition left open
  std::printf("[ stats    ] %d searches with a condition left open\n", leftOpen);
}

// The search of the exact cone, as checkSliced runs it last: a proof or a rebuilt lasso, each the
// explicit search's verdict, or (a lasso that does not rebuild) no verdict.
TEST(RecurringRules, TheExactConeDecidesAsTheExplicitSearchDoes) {
  int decided = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(200); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    const LivenessResult reference = explicitSearch(m);
    const CompiledModel cm(m);
    const ControlFacts facts = controlFacts(m);
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      SCOPED_TRACE(m.properties[k].name);
      detail::SlicedOutcome out;
      detail::proveOnCone(cm, facts, k, SearchLimits{}, out, 60);
      // The cone keeps every variable that matters but not every group's fairness (a group with
      // a rule left out loses it, as in any slice): its proof stands, its lasso may not be one of
      // the model's, and is then not reported.
      if (out.property.verdict == Verdict::Unknown) {
        EXPECT_NE(out.why.find("could not be rebuilt"), std::string::npos) << out.why;
        EXPECT_EQ(reference.properties[k].verdict, Verdict::Violated);
        continue;
      }
      EXPECT_TRUE(out.onCone);
      EXPECT_EQ(out.property.verdict, reference.properties[k].verdict);
      if (out.property.verdict == Verdict::Violated) {
        ASSERT_TRUE(out.property.counterexample.has_value());
        EXPECT_TRUE(checkLasso(m, *out.property.counterexample, m.properties[k]).counterexample());
      }
      ++decided;
    }
  }
  EXPECT_GT(decided, test::atLeast(100));
}

}  // namespace
}  // namespace semo::checker
