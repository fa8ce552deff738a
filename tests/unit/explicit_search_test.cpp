// Explicit-state search on tiny models whose state spaces are counted by hand; and the Promela
// export's naming and arithmetic (its state counts are cross-checked with SPIN in tests/e2e/spin).
#include <gtest/gtest.h>

#include <cstdlib>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/promela_export.hpp"
#include "semo/checker/symmetry.hpp"
#include "semo/checker/trace.hpp"
#include "ir_support.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo::checker {
namespace {

ir::Model parse(const std::string& text) { return test::parseIr(text); }

SearchResult check(const ir::Model& m, std::uint64_t maxStates = 1'000'000) {
  SearchLimits limits;
  limits.maxStates = maxStates;
  return checkSafety(m, limits);
}

const PropertyResult& property(const SearchResult& r, const std::string& name) {
  for (const PropertyResult& p : r.properties) {
    if (p.name == name) return p;
  }
  ADD_FAILURE() << "no property " << name;
  static PropertyResult none;
  return none;
}

// The rules a trace takes, by name, with the outcome of probabilistic ones as "name/branch".
std::vector<std::string> ruleNames(const ir::Model& m, const Trace& t) {
  std::vector<std::string> out;
  for (const Step& s : t.steps) {
    const ir::Rule& r = m.rules.at(s.rule);
    out.push_back(r.branches.size() > 1 ? r.name + "/" + std::to_string(s.branch) : r.name);
  }
  return out;
}

// The values after the last step of a trace.
std::vector<std::int32_t> finalState(const Trace& t) {
  std::vector<std::int32_t> values = t.initial;
  for (const Step& s : t.steps) {
    for (const Change& c : s.changes) {
      EXPECT_EQ(values.at(c.var), c.before);
      values[c.var] = c.after;
    }
  }
  return values;
}

TEST(ExplicitSearch, CounterHasFourStates) {
  ir::Model m = parse(R"(semo-ir 1;
var c : 0..3 = 0;
rule inc : c < 3 -> c' = c + 1;
rule reset : c == 3 -> c' = 0;
invariant bounded : c <= 3;
)");
  SearchResult r = check(m);
  EXPECT_EQ(r.states, 4u);
  EXPECT_EQ(r.transitions, 4u);
  EXPECT_EQ(r.depth, 3u);
  EXPECT_TRUE(r.complete);
  EXPECT_TRUE(r.limitReached.empty()) << r.limitReached;
  ASSERT_EQ(r.properties.size(), 1u) << "no deadlock_freedom without valid_end";
  EXPECT_EQ(r.properties[0].verdict, Verdict::Proven);
  EXPECT_FALSE(r.properties[0].counterexample.has_value());
  EXPECT_FALSE(r.rangeError.has_value());
}

TEST(ExplicitSearch, TwoIndependentBooleansHaveFourStates) {
  ir::Model m = parse(R"(semo-ir 1;
var a : bool;
var b : bool = true;
rule flip_a : true -> a' = !a;
rule flip_b : true -> b' = !b;
)");
  SearchResult r = check(m);
  EXPECT_EQ(r.states, 4u);
  EXPECT_EQ(r.transitions, 8u);  // two rules enabled in each of the 4 states
  EXPECT_EQ(r.depth, 2u);
  EXPECT_TRUE(r.complete);
  EXPECT_TRUE(r.properties.empty());
}

TEST(ExplicitSearch, SimultaneousAssignmentReadsTheOldState) {
  ir::Model m = parse(R"(semo-ir 1;
var a : 0..2 = 0;
var b : 0..2 = 1;
rule swap : true -> a' = b, b' = a;
invariant different : a != b;
)");
  SearchResult r = check(m);
  EXPECT_EQ(r.states, 2u);  // (0,1) and (1,0): a sequential a := b; b := a would give (1,1)
  EXPECT_EQ(property(r, "different").verdict, Verdict::Proven);
}

const char* kMutexWithBug = R"(semo-ir 1;
robots r0 r1;
var pc[2] : 0..2 @values("idle checked inside");
var busy : bool;
rule r0_check @robot(r0) : pc[0] == 0 && !busy -> pc[0]' = 1;
rule r0_enter @robot(r0) : pc[0] == 1 -> busy' = true, pc[0]' = 2;
rule r0_leave @robot(r0) : pc[0] == 2 -> busy' = false, pc[0]' = 0;
rule r1_check @robot(r1) : pc[1] == 0 && !busy -> pc[1]' = 1;
rule r1_enter @robot(r1) : pc[1] == 1 -> busy' = true, pc[1]' = 2;
rule r1_leave @robot(r1) : pc[1] == 2 -> busy' = false, pc[1]' = 0;
invariant mutual_exclusion : !(pc[0] == 2 && pc[1] == 2);
)";

TEST(ExplicitSearch, MutexWithABugHasAShortestCounterexample) {
  ir::Model m = parse(kMutexWithBug);
  SearchResult r = check(m);
  const PropertyResult& p = property(r, "mutual_exclusion");
  EXPECT_EQ(p.verdict, Verdict::Violated);
  ASSERT_TRUE(p.counterexample.has_value());
  const Trace& t = *p.counterexample;
  EXPECT_EQ(t.kind, "invariant");
  EXPECT_EQ(t.property, "mutual_exclusion");
  EXPECT_EQ(t.initial, (std::vector<std::int32_t>{0, 0, 0}));
  // Both check the door before either enters: 4 steps, and no shorter path exists. BFS takes the
  // rules in order, so the first shortest path found is this one.
  ASSERT_EQ(t.steps.size(), 4u);
  EXPECT_EQ(ruleNames(m, t), (std::vector<std::string>{"r0_check", "r1_check", "r0_enter", "r1_enter"}));
  ASSERT_EQ(t.steps[2].changes.size(), 2u);
  EXPECT_EQ(t.steps[2].changes[0].var, 0u);  // pc[0]: 1 -> 2
  EXPECT_EQ(t.steps[2].changes[0].before, 1);
  EXPECT_EQ(t.steps[2].changes[0].after, 2);
  EXPECT_EQ(t.steps[2].changes[1].var, 2u);  // busy: false -> true
  ASSERT_EQ(t.steps[3].changes.size(), 1u) << "busy was already true: only pc[1] changes";
  EXPECT_EQ(finalState(t), (std::vector<std::int32_t>{2, 2, 1}));
  // With its only property violated, the search stops early: not complete, and it says why.
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.limitReached, "every property is violated");
  std::string text = traceToText(m, t);
  EXPECT_NE(text.find("counterexample for mutual_exclusion (invariant): 4 steps"), std::string::npos) << text;
  EXPECT_NE(text.find("pc[1]: checked -> inside"), std::string::npos) << text;
}

TEST(ExplicitSearch, InvariantViolatedInTheInitialState) {
  ir::Model m = parse(R"(semo-ir 1;
var x : 0..3 = 3;
rule down : x > 0 -> x' = x - 1;
invariant small : x < 3;
)");
  SearchResult r = check(m);
  const PropertyResult& p = property(r, "small");
  EXPECT_EQ(p.verdict, Verdict::Violated);
  ASSERT_TRUE(p.counterexample.has_value());
  EXPECT_TRUE(p.counterexample->steps.empty());
  EXPECT_EQ(p.counterexample->initial, (std::vector<std::int32_t>{3}));
}

const char* kDeadlock = R"(semo-ir 1;
robots a b;
var charger : 0..2;
var dock : 0..2;
var done_a : bool;
var done_b : bool;
rule a_charger @robot(a) : charger == 0 && !done_a -> charger' = 1;
rule a_dock @robot(a) : charger == 1 && dock == 0 -> dock' = 1;
rule a_finish @robot(a) : charger == 1 && dock == 1 -> charger' = 0, dock' = 0, done_a' = true;
rule b_dock @robot(b) : dock == 0 && !done_b -> dock' = 2;
rule b_charger @robot(b) : dock == 2 && charger == 0 -> charger' = 2;
rule b_finish @robot(b) : charger == 2 && dock == 2 -> charger' = 0, dock' = 0, done_b' = true;
invariant tidy : done_a => charger != 1;
)";

TEST(ExplicitSearch, DeadlockWithValidEnd) {
  ir::Model m = parse(std::string(kDeadlock) + "valid_end : done_a && done_b;\n");
  SearchResult r = check(m);
  ASSERT_EQ(r.properties.size(), 2u);
  EXPECT_EQ(r.properties[1].name, "deadlock_freedom");
  const PropertyResult& p = r.properties[1];
  EXPECT_EQ(p.verdict, Verdict::Violated);
  ASSERT_TRUE(p.counterexample.has_value());
  EXPECT_EQ(p.counterexample->kind, "deadlock");
  // a takes the charger, b the dock: neither can go on.
  EXPECT_EQ(ruleNames(m, *p.counterexample), (std::vector<std::string>{"a_charger", "b_dock"}));
  EXPECT_EQ(finalState(*p.counterexample), (std::vector<std::int32_t>{1, 2, 0, 0}));
  EXPECT_EQ(property(r, "tidy").verdict, Verdict::Proven);
  // tidy is still open after the deadlock, so the whole state space is searched:
  // (charger, dock, done_a, done_b) reachable = 13 states (hand count in tests/e2e/ir/deadlock.ir).
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.states, 13u);
  EXPECT_NE(traceToText(m, *p.counterexample).find("not a valid end state"), std::string::npos);
}

TEST(ExplicitSearch, DeadlockWithoutValidEndIsNotChecked) {
  ir::Model m = parse(kDeadlock);
  SearchResult r = check(m);
  ASSERT_EQ(r.properties.size(), 1u);
  EXPECT_EQ(r.properties[0].name, "tidy");
  EXPECT_EQ(r.properties[0].verdict, Verdict::Proven);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.states, 13u);
}

TEST(ExplicitSearch, ValidEndAcceptsTheFinalStates) {
  ir::Model m = parse(R"(semo-ir 1;
var c : 0..3;
rule up : c < 3 -> c' = c + 1;
valid_end : c == 3;
)");
  SearchResult r = check(m);
  EXPECT_EQ(property(r, "deadlock_freedom").verdict, Verdict::Proven);
  EXPECT_EQ(r.states, 4u);
  ir::Model stuck = parse("semo-ir 1;\nvar c : 0..3;\nrule up : c < 2 -> c' = c + 1;\nvalid_end : c == 3;\n");
  SearchResult s = check(stuck);
  const PropertyResult& p = property(s, "deadlock_freedom");
  EXPECT_EQ(p.verdict, Verdict::Violated);
  ASSERT_TRUE(p.counterexample.has_value());
  EXPECT_EQ(p.counterexample->steps.size(), 2u);
}

TEST(ExplicitSearch, ProbabilisticBranchesAreAllSuccessors) {
  ir::Model m = parse(R"(semo-ir 1;
var coin : 0..2 @values("unflipped heads tails");
var flips : 0..2;
rule flip : coin == 0 && flips < 2 -> 0.5 : coin' = 1, flips' = flips + 1 + 0.5 : coin' = 2, flips' = flips + 1;
rule again : coin != 0 -> coin' = 0;
invariant never_two_tails : !(coin == 2 && flips == 2);
invariant bounded : flips <= 2;
)");
  SearchResult r = check(m);
  // (coin, flips): (0,0) (1,1) (2,1) (0,1) (1,2) (2,2) (0,2)
  EXPECT_EQ(r.states, 7u);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(property(r, "bounded").verdict, Verdict::Proven);
  const PropertyResult& p = property(r, "never_two_tails");
  EXPECT_EQ(p.verdict, Verdict::Violated);
  ASSERT_TRUE(p.counterexample.has_value());
  // The trace says which outcome was taken: tails (branch 1) at the end.
  std::vector<std::string> rules = ruleNames(m, *p.counterexample);
  ASSERT_EQ(rules.size(), 3u);
  EXPECT_EQ(rules[1], "again");
  EXPECT_EQ(rules[2], "flip/1");
  EXPECT_NE(traceToText(m, *p.counterexample).find("(outcome 2)"), std::string::npos);
  EXPECT_NE(traceToJson(m, *p.counterexample).find("\"branch\": 1"), std::string::npos);
}

TEST(ExplicitSearch, MaxStatesLeavesUnviolatedPropertiesUnknown) {
  ir::Model m = parse(R"(semo-ir 1;
var c : 0..100;
var d : bool;
rule inc : c < 100 -> c' = c + 1;
rule toggle : true -> d' = !d;
invariant fine : c <= 100;
valid_end : true;
)");
  SearchResult full = check(m);
  EXPECT_EQ(full.states, 202u);
  EXPECT_TRUE(full.complete);
  SearchResult r = check(m, 10);
  EXPECT_FALSE(r.complete);
  EXPECT_GE(r.states, 10u);
  EXPECT_LT(r.states, 202u);
  EXPECT_EQ(r.limitReached, "--max-states 10 reached");
  ASSERT_EQ(r.properties.size(), 2u);
  for (const PropertyResult& p : r.properties) {
    EXPECT_EQ(p.verdict, Verdict::Unknown) << p.name;
    EXPECT_FALSE(p.counterexample.has_value());
  }
}

TEST(ExplicitSearch, UpdateOutOfRangeIsAModellingError) {
  ir::Model m = parse(R"(semo-ir 1;
var x : 0..2;
var y : -1..1;
rule inc : true -> x' = x + 1;
invariant ok : x >= 0;
)");
  SearchResult r = check(m);
  ASSERT_TRUE(r.rangeError.has_value());
  const Trace& t = *r.rangeError;
  EXPECT_EQ(t.kind, "range");
  // 0 -> 1 -> 2, and then the third step leaves the range.
  ASSERT_EQ(t.steps.size(), 3u);
  ASSERT_EQ(t.steps[2].changes.size(), 1u);
  EXPECT_EQ(t.steps[2].changes[0].before, 2);
  EXPECT_EQ(t.steps[2].changes[0].after, 3);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.limitReached, "an update left a variable's declared range");
  EXPECT_EQ(property(r, "ok").verdict, Verdict::Unknown);
  EXPECT_NE(traceToText(m, t).find("outside a variable's declared range"), std::string::npos);
}

TEST(ExplicitSearch, DivisionAndRemainderByZeroAreZero) {
  ir::Model m = parse(R"(semo-ir 1;
var a : -7..7 = -7;
var b : -2..2 = 0;
var q : -7..7 = 0;
var r : -7..7 = 5;
rule divide : b == 0 && q == 0 -> q' = a / b, r' = a % b, b' = 2;
rule again : b == 2 && q == 0 && r == 0 -> q' = a / b, r' = a % b;
invariant zero : b == 0 || b == 2 && (q == 0 && r == 0 || q == -3 && r == -1);
)");
  SearchResult r = check(m);
  EXPECT_FALSE(r.rangeError.has_value());
  EXPECT_EQ(r.states, 3u);  // (b, q, r) = (0,0,5) (2,0,0) (2,-3,-1): C's truncating division
  EXPECT_EQ(property(r, "zero").verdict, Verdict::Proven);
}

// ---- the Promela export: names, types and arithmetic as SPIN needs them

// The rules offered in a state come in rule order whether there are few (sorted) or many (read
// back from a bitmap): 600 rules, a third needing pc == 0, a third pc == 1, the rest untriggered,
// interleaved.
TEST(ExplicitSearch, CandidateRulesAscendWhateverTheirNumber) {
  std::string text = "semo-ir 1;\nvar pc : 0..1 = 0;\nvar n : 0..1 = 0;\n";
  for (int r = 0; r < 600; ++r) {
    const std::string guard = r % 3 == 0 ? "pc == 0" : r % 3 == 1 ? "pc == 1" : "n < 2";
    text += "rule r" + std::to_string(r) + " : " + guard + " -> n' = 0;\n";
  }
  ir::Model m = parse(text);
  CompiledModel cm(m);
  for (Value pc : {0, 1}) {
    std::vector<Value> values{pc, 0};
    std::vector<std::uint32_t> offered;
    cm.candidateRules(values.data(), offered);
    std::vector<std::uint32_t> expected;
    for (std::uint32_t r = 0; r < 600; ++r) {
      if (r % 3 == 2 || static_cast<Value>(r % 3) == pc) expected.push_back(r);
    }
    EXPECT_EQ(offered, expected) << "pc == " << pc;
  }
}

TEST(PromelaExport, MangledNamesTypesAndTotalDivision) {
  ir::Model m = parse(R"(semo-ir 1;
var r1.mode : 0..2;
var r1_mode : 0..300;
var do : bool = true;
var t : -1..1 = -1;
var big : 0..70000;
var f[2] : 0..1;
rule r : true -> r1.mode' = r1_mode / t, t' = f[1] % r1.mode, big' = big / 2;
invariant i : !!do;
)");
  std::string pml = toPromela(m);
  EXPECT_NE(pml.find("byte r1_mode = 0;"), std::string::npos) << pml;
  EXPECT_NE(pml.find("short r1_mode_2 = 0;"), std::string::npos) << pml;
  EXPECT_NE(pml.find("bool do_2 = true;"), std::string::npos) << pml;
  EXPECT_NE(pml.find("short t = -1;"), std::string::npos) << pml;
  EXPECT_NE(pml.find("int big = 0;"), std::string::npos) << pml;
  EXPECT_NE(pml.find("bit f_1 = 0;"), std::string::npos) << pml;
  EXPECT_NE(pml.find("/* r1.mode : 0..2 */"), std::string::npos) << pml;
  EXPECT_NE(pml.find("(t == 0 -> 0 : r1_mode_2 / t)"), std::string::npos) << pml;
  EXPECT_NE(pml.find("big = big / 2"), std::string::npos) << pml;
  EXPECT_EQ(pml.find("!!"), std::string::npos) << "!! is a Promela send operator\n" << pml;
  EXPECT_NE(pml.find("hidden byte prop_i;\t/* property 'i' */"), std::string::npos) << pml;
  // r1.mode is read by t's update, so its new value goes through a temporary.
  EXPECT_NE(pml.find("semo_old0 = (t == 0 -> 0 : r1_mode_2 / t)"), std::string::npos) << pml;
  EXPECT_EQ(toPromela(m), pml) << "deterministic";
}

TEST(PromelaExport, DeadlockOptionOnlyWithValidEnd) {
  ir::Model without = parse("semo-ir 1;\nvar c : 0..3;\nrule up : c < 3 -> c' = c + 1;\n");
  std::string a = toPromela(without);
  EXPECT_NE(a.find("end:"), std::string::npos);
  EXPECT_EQ(a.find("timeout"), std::string::npos) << a;
  ir::Model with = parse("semo-ir 1;\nvar c : 0..3;\nrule up : c < 3 -> c' = c + 1;\nvalid_end : c == 3;\n");
  std::string b = toPromela(with);
  EXPECT_NE(b.find(":: atomic { timeout -> prop_deadlock_freedom = c == 3; assert(prop_deadlock_freedom) }"),
            std::string::npos) << b;
}

// A counter 0..3 with a reset: depth d reaches the states 0..d.
constexpr const char* kCounter = R"(semo-ir 1;
var c : 0..3 = 0;
rule inc : c < 3 -> c' = c + 1;
rule reset : c == 3 -> c' = 0;
)";

SearchResult checkToDepth(const ir::Model& m, std::uint32_t depth) {
  SearchLimits limits;
  limits.maxDepth = depth;
  return checkSafety(m, limits);
}

TEST(ExplicitSearch, MaxDepthStoresExactlyTheStatesWithinTheBound) {
  ir::Model m = parse(std::string(kCounter) + "invariant small : c <= 3;\n");
  for (std::uint32_t d = 0; d < 3; ++d) {
    SearchResult r = checkToDepth(m, d);
    EXPECT_EQ(r.states, d + 1) << "depth " << d;
    EXPECT_EQ(r.depth, d);
    EXPECT_FALSE(r.complete);
    EXPECT_TRUE(r.depthBounded);
    EXPECT_EQ(r.properties[0].verdict, Verdict::Unknown) << "a bounded search proves nothing";
  }
  // At depth 3 the only successor of the state at the bound (c = 0) is already stored: complete.
  SearchResult r = checkToDepth(m, 3);
  EXPECT_EQ(r.states, 4u);
  EXPECT_TRUE(r.complete);
  EXPECT_FALSE(r.depthBounded);
  EXPECT_EQ(r.properties[0].verdict, Verdict::Proven);
}

TEST(ExplicitSearch, MaxDepthChecksTheStatesAtTheBound) {
  // The invariant fails at depth 2 and a deadlock waits at depth 3: both count at the bound.
  ir::Model m = parse(R"(semo-ir 1;
var c : 0..3 = 0;
rule inc : c < 3 -> c' = c + 1;
invariant below_two : c < 2;
valid_end : c == 0;
)");
  SearchResult one = checkToDepth(m, 1);
  EXPECT_EQ(property(one, "below_two").verdict, Verdict::Unknown);
  SearchResult two = checkToDepth(m, 2);
  EXPECT_EQ(property(two, "below_two").verdict, Verdict::Violated);
  EXPECT_EQ(property(two, "deadlock_freedom").verdict, Verdict::Unknown);
  SearchResult three = checkToDepth(m, 3);
  const PropertyResult& deadlock = property(three, "deadlock_freedom");
  EXPECT_EQ(deadlock.verdict, Verdict::Violated);
  ASSERT_TRUE(deadlock.counterexample.has_value());
  EXPECT_EQ(deadlock.counterexample->steps.size(), 3u);
}

TEST(PromelaExport, BreadthFirstHasNoHiddenVariablesAndResetsTheScratch) {
  ir::Model m = parse(R"(semo-ir 1;
var a : 0..3 = 0;
var b : 0..3 = 1;
rule swap : true -> a' = b, b' = a;
invariant small : a < 3;
valid_end : a == b;
)");
  std::string dfs = toPromela(m);
  EXPECT_NE(dfs.find("hidden int semo_old0;"), std::string::npos) << dfs;
  std::string bfs = toPromela(m, {.breadthFirst = true});
  EXPECT_EQ(bfs.find("hidden byte"), std::string::npos) << bfs;
  EXPECT_EQ(bfs.find("hidden int"), std::string::npos) << bfs;
  EXPECT_NE(bfs.find("\nbyte prop_small;"), std::string::npos) << bfs;
  EXPECT_NE(bfs.find("assert(prop_small); prop_small = 0"), std::string::npos) << bfs;
  EXPECT_NE(bfs.find("assert(prop_deadlock_freedom); prop_deadlock_freedom = 0"), std::string::npos) << bfs;
  EXPECT_NE(bfs.find("semo_old0 = 0"), std::string::npos) << bfs;
}

// Two robots that each count to 2, and a shared counter of how many are done.
constexpr const char* kTwins = R"(semo-ir 1;
robots a b;
var a.c : 0..2 = 0 @robot(a);
var b.c : 0..2 = 0 @robot(b);
var done : 0..2 = 0;
rule a.up @robot(a) : a.c < 2 -> a.c' = a.c + 1, done' = (a.c == 1 ? done + 1 : done);
rule b.up @robot(b) : b.c < 2 -> b.c' = b.c + 1, done' = (b.c == 1 ? done + 1 : done);
invariant counted : done == (a.c == 2 ? 1 : 0) + (b.c == 2 ? 1 : 0);
invariant not_both_done : done < 2;
)";

TEST(Symmetry, InterchangeableRobotsAreFoundAndCountedOncePerOrbit) {
  ir::Model m = parse(kTwins);
  Symmetry sym = Symmetry::find(m);
  ASSERT_FALSE(sym.empty());
  EXPECT_EQ(sym.describe(m), (std::vector<std::string>{"a b (2! = 2 orderings)"}));
  SearchLimits with, without;
  without.symmetry = false;
  SearchResult full = checkSafety(m, without), reduced = checkSafety(m, with);
  EXPECT_EQ(full.states, 9u) << "(a.c, b.c) in 0..2 x 0..2";
  EXPECT_EQ(reduced.states, 6u) << "unordered pairs: 3 * 4 / 2";
  // The verdicts agree, and the reduced counterexample is a real run of the model.
  ASSERT_EQ(reduced.properties.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) EXPECT_EQ(reduced.properties[p].verdict, full.properties[p].verdict);
  const PropertyResult& both = property(reduced, "not_both_done");
  ASSERT_TRUE(both.counterexample.has_value());
  EXPECT_EQ(both.counterexample->steps.size(), 4u);
  EXPECT_EQ(finalState(*both.counterexample), (std::vector<std::int32_t>{2, 2, 2}));
}

TEST(Symmetry, APropertyNamingOneRobotBreaksItsSymmetry) {
  // The check is syntactic (up to the order of commutative operands), hence conservative:
  ir::Model m = parse(std::string(kTwins) + "invariant either : a.c <= b.c || b.c <= a.c;\n");
  EXPECT_FALSE(Symmetry::find(m).empty()) << "`either` maps to itself";
  ir::Model asymmetric = parse(std::string(kTwins) + "invariant a_small : a.c < 3;\n");
  EXPECT_TRUE(Symmetry::find(asymmetric).empty());
  // A rule that treats the two differently breaks it as well.
  std::string text = kTwins;
  text.replace(text.find("rule b.up @robot(b) : b.c < 2"), 29, "rule b.up @robot(b) : b.c < 1");
  EXPECT_TRUE(Symmetry::find(parse(text)).empty());
}

TEST(Symmetry, CanonicalFormSortsRobotsByTheirValues) {
  ir::Model m = parse(kTwins);
  Symmetry sym = Symmetry::find(m);
  std::vector<Value> x{2, 1, 1}, y{1, 2, 1};
  sym.canonicalize(x.data());
  sym.canonicalize(y.data());
  EXPECT_EQ(x, y);
  EXPECT_EQ(x, (std::vector<Value>{1, 2, 1}));
}

}  // namespace
}  // namespace semo::checker
