// The liveness engine on tiny models whose fair runs are known by hand: fairness kinds, runs that
// end, the temporal operators, and the Büchi construction's acceptance sets.
#include <gtest/gtest.h>

#include <algorithm>

#include "semo/checker/buchi.hpp"
#include "semo/checker/liveness_search.hpp"
#include "ir_support.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo::checker {
namespace {

ir::Model parse(const std::string& text) { return test::parseIr(text); }

Verdict verdictOf(const std::string& model, const std::string& property, LivenessResult* out = nullptr) {
  ir::Model m = parse(model + "property p : " + property + ";\n");
  LivenessResult r = checkLiveness(m, {});
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.properties.size(), 1u);
  if (r.properties.empty()) return Verdict::Unknown;
  Verdict v = r.properties[0].verdict;
  EXPECT_EQ(v == Verdict::Violated, r.properties[0].counterexample.has_value());
  if (out != nullptr) *out = std::move(r);
  return v;
}

// c counts to 3 and stays; `idle` may be taken at any time.
std::string counter(const std::string& incFairness) {
  return "semo-ir 1;\nvar c : 0..3 = 0;\nrule inc " + incFairness + " : c < 3 -> c' = c + 1;\nrule idle : true -> skip;\n";
}

TEST(Liveness, WeakFairnessForcesAStepThatStaysEnabled) {
  EXPECT_EQ(verdictOf(counter("@fair"), "eventually {c == 3}"), Verdict::Proven);
  LivenessResult r;
  EXPECT_EQ(verdictOf(counter(""), "eventually {c == 3}", &r), Verdict::Violated);
  // Unfair: nothing must happen, so staying at c = 0 for ever (idling, or not even that) is a run.
  const Trace& t = *r.properties[0].counterexample;
  EXPECT_EQ(t.kind, "lasso");
  EXPECT_EQ(t.loopStart, 0u);
  for (const Step& step : t.steps) EXPECT_EQ(step.rule, 1u) << "only `idle` in the loop";
}

TEST(Liveness, AFairRuleIsNotForcedWhileItKeepsBeingDisabled) {
  // inc is fair but needs `go`, which an unfair rule keeps turning off: inc need not happen.
  std::string m = "semo-ir 1;\nvar c : 0..1 = 0;\nvar go : bool = false;\n"
                  "rule inc @fair : go && c == 0 -> c' = 1;\nrule on : !go -> go' = true;\nrule off @fair : go -> go' = false;\n";
  EXPECT_EQ(verdictOf(m, "eventually {c == 1}"), Verdict::Violated);
  // With `on` fair too, go keeps coming back, but weak fairness still allows missing it every time.
  std::string both = "semo-ir 1;\nvar c : 0..1 = 0;\nvar go : bool = false;\n"
                     "rule inc @fair : go && c == 0 -> c' = 1;\nrule on @fair : !go -> go' = true;\nrule off @fair : go -> go' = false;\n";
  EXPECT_EQ(verdictOf(both, "eventually {c == 1}"), Verdict::Violated);
  std::string strong = "semo-ir 1;\nvar c : 0..1 = 0;\nvar go : bool = false;\n"
                       "rule inc @strongly_fair : go && c == 0 -> c' = 1;\nrule on @fair : !go -> go' = true;\nrule off @fair : go -> go' = false;\n";
  EXPECT_EQ(verdictOf(strong, "eventually {c == 1}"), Verdict::Proven);
}

TEST(Liveness, SafetyFormulasAndNextAndUntil) {
  std::string m = counter("@fair");
  EXPECT_EQ(verdictOf(m, "always {c <= 3}"), Verdict::Proven);
  EXPECT_EQ(verdictOf(m, "always {c < 3}"), Verdict::Violated);
  // idle may come first, so c is not 1 in the second state of every run.
  EXPECT_EQ(verdictOf(m, "next {c == 1}"), Verdict::Violated);
  EXPECT_EQ(verdictOf(m, "next {c <= 1}"), Verdict::Proven);
  EXPECT_EQ(verdictOf(m, "{c == 0} until {c == 1}"), Verdict::Proven);
  EXPECT_EQ(verdictOf(m, "{c == 0} until {c == 2}"), Verdict::Violated);
  EXPECT_EQ(verdictOf(m, "eventually always {c == 3}"), Verdict::Proven);
  EXPECT_EQ(verdictOf(m, "always ({c == 1} => eventually {c == 2})"), Verdict::Proven);
  EXPECT_EQ(verdictOf(m, "always eventually {c == 0}"), Verdict::Violated);
  EXPECT_EQ(verdictOf(m, "{false} release {c <= 3}"), Verdict::Proven);
}

// A message that may be lost, resent while it is not delivered.
std::string lossy(const std::string& deliverFairness) {
  return "semo-ir 1;\nvar msg : bool = false;\nvar got : bool = false;\n"
         "rule send @fair : !msg && !got -> msg' = true;\n"
         "rule lose @kind(loss) : msg -> msg' = false;\n"
         "rule deliver " + deliverFairness + " : msg -> msg' = false, got' = true;\n";
}

TEST(Liveness, StrongFairnessMakesARetriedDeliveryHappen) {
  // Weakly fair delivery is not enough: loss disables it every time (send, lose, send, lose, ...).
  LivenessResult r;
  EXPECT_EQ(verdictOf(lossy("@fair"), "eventually {got}", &r), Verdict::Violated);
  const Trace& t = *r.properties[0].counterexample;
  ASSERT_EQ(t.steps.size(), 2u);
  EXPECT_EQ(t.loopStart, 0u);
  // Strongly fair: enabled again and again, so taken in the end.
  EXPECT_EQ(verdictOf(lossy("@strongly_fair"), "eventually {got}"), Verdict::Proven);
}

TEST(Liveness, ARunThatEndsStaysInItsLastState) {
  std::string m = "semo-ir 1;\nvar c : 0..2 = 0;\nrule inc @fair : c < 2 -> c' = c + 1;\n";
  EXPECT_EQ(verdictOf(m, "eventually always {c == 2}"), Verdict::Proven);
  LivenessResult r;
  EXPECT_EQ(verdictOf(m, "always eventually {c == 0}", &r), Verdict::Violated);
  const Trace& t = *r.properties[0].counterexample;
  EXPECT_EQ(t.steps.size(), 2u);
  EXPECT_EQ(t.loopStart, 2u) << "no step repeats: the run stays at c = 2";
  EXPECT_NE(traceToText(parse(m), t).find("stays in this state for ever"), std::string::npos);
}

TEST(Liveness, FairLoopTakesEveryFairRuleThatIsAlwaysEnabled) {
  // Two fair togglers: each keeps toggling, but not in step (ta ta tb tb ... never has a && b).
  std::string m = "semo-ir 1;\nvar a : bool = false;\nvar b : bool = false;\n"
                  "rule ta @fair : true -> a' = !a;\nrule tb @fair : true -> b' = !b;\n";
  EXPECT_EQ(verdictOf(m, "always eventually {a}"), Verdict::Proven);
  EXPECT_EQ(verdictOf(m, "always eventually {a && b}"), Verdict::Violated);
  LivenessResult r;
  EXPECT_EQ(verdictOf(m, "eventually always {a}", &r), Verdict::Violated);
  const Trace& t = *r.properties[0].counterexample;
  bool tookA = false, tookB = false;
  for (std::size_t i = t.loopStart; i < t.steps.size(); ++i) {
    tookA = tookA || t.steps[i].rule == 0;
    tookB = tookB || t.steps[i].rule == 1;
  }
  EXPECT_TRUE(tookA && tookB) << "the loop is fair to both rules";
}

TEST(Liveness, AFairCycleAmongTheStatesExploredIsAViolationEvenWhenTheSearchStops) {
  // x may climb to 100000 (unfairly); y flips for ever from the start. The product is far beyond
  // a budget of 1000 states, but the loop flipping y at x = 0 lies in the part explored.
  const std::string m = "semo-ir 1;\nvar x : 0..100000 = 0;\nvar y : bool = false;\n"
                        "rule climb : x < 100000 -> x' = x + 1;\nrule flip @fair : true -> y' = !y;\n";
  SearchLimits small;
  small.maxStates = 1000;
  LivenessOptions whole;
  whole.slicing = false;
  LivenessResult r = checkLiveness(parse(m + "property p : eventually always {y};\n"), small, whole);
  ASSERT_EQ(r.properties.size(), 1u);
  EXPECT_EQ(r.properties[0].verdict, Verdict::Violated);
  ASSERT_TRUE(r.properties[0].counterexample.has_value());
  EXPECT_TRUE(r.complete) << "a violation is final, however much was left unexplored";
  EXPECT_LE(r.states, 1001u);
  // A property that holds cannot be proven on a part: unknown.
  r = checkLiveness(parse(m + "property p : always eventually {y};\n"), small, whole);
  EXPECT_EQ(r.properties[0].verdict, Verdict::Unknown);
  EXPECT_FALSE(r.complete);
}

TEST(Liveness, ARoundRobinHuntFindsAViolationNoSliceAndNoPartialSearchReaches) {
  // Eight counters cycle; z may decide once, by what it senses, to leave m = 0 for good. The
  // property reads every counter, so no slice is smaller than the product (131,072 states), far
  // beyond the budget of 1000; breadth-first, 1000 states hold no loop on which every counter
  // comes back. With the counters taking turns, the world in which z senses p is a short loop.
  std::string m = "semo-ir 1;\nvar m : 0..1 = 0;\n";
  std::string sum;
  for (int k = 1; k <= 8; ++k) {
    const std::string c = "c" + std::to_string(k);
    m += "var " + c + " : 0..3 = 0;\n";
    sum += (sum.empty() ? "" : " + ") + c;
  }
  for (int k = 1; k <= 8; ++k) {
    const std::string c = "c" + std::to_string(k);
    m += "rule tick" + std::to_string(k) + " @fair : true -> " + c + "' = (" + c + " + 1) % 4;\n";
  }
  m += "rule go @fair(z) @senses(\"z.p=1\") : m == 0 -> m' = 1;\n"
       "rule stay @fair(z) @senses(\"z.p=0\") : m == 0 -> skip;\n";
  SearchLimits small;
  small.maxStates = 1000;
  LivenessOptions options;
  options.sliceStates = 1000;
  options.symbolic = false;  // the hunt's own test: the symbolic search would decide it first,
  options.walks = false;     // and so would the random walks
  LivenessResult r = checkLiveness(parse(m + "property p : always eventually {m == 0 || " + sum + " == 99};\n"), small, options);
  ASSERT_EQ(r.properties.size(), 1u);
  EXPECT_EQ(r.properties[0].verdict, Verdict::Violated);
  ASSERT_TRUE(r.properties[0].counterexample.has_value());
  ASSERT_EQ(r.methods.size(), 1u);
  EXPECT_TRUE(r.methods[0].roundRobin);
  EXPECT_TRUE(r.complete);
  const Trace& t = *r.properties[0].counterexample;
  EXPECT_LT(t.loopStart, t.steps.size());
  // The lasso's loop moves every counter (it is fair to them) and z is out of m = 0.
  std::vector<char> ticked(8, 0);
  for (std::size_t i = t.loopStart; i < t.steps.size(); ++i) {
    if (t.steps[i].rule < 8) ticked[t.steps[i].rule] = 1;
  }
  EXPECT_EQ(std::count(ticked.begin(), ticked.end(), 1), 8);
  // Without the world in which z leaves, the same hunt finds nothing: unknown, never proven.
  std::string quiet = m;
  quiet.replace(quiet.find("m == 0 -> m' = 1"), 16, "m == 2 -> m' = 1");
  r = checkLiveness(parse(quiet + "property p : always eventually {m == 0 || " + sum + " == 99};\n"), small, options);
  EXPECT_NE(r.properties[0].verdict, Verdict::Violated);
}

TEST(Liveness, TheRoundRobinHuntAllowsLossesWhenNoLosslessRunViolates) {
  // A message sent once is delivered unless it is lost; the counters keep every slice as large as
  // the product, and come back only all together (reset), too deep for 1000 states breadth-first.
  // Without losses every run delivers the message; the violation needs the loss.
  std::string m = "semo-ir 1;\nvar sent : bool = false;\nvar inbox : bool = false;\nvar got : bool = false;\n";
  const test::ResettingCounters counters = test::resettingCounters();
  const std::string& sum = counters.sum;
  m += counters.declarations;
  m += "rule send @fair : !sent -> sent' = true, inbox' = true;\n"
       "rule lose @kind(loss) : inbox -> inbox' = false;\n"
       "rule deliver @fair : inbox -> inbox' = false, got' = true;\n"
       + counters.resetRule;
  SearchLimits small;
  small.maxStates = 1000;
  LivenessOptions options;
  options.sliceStates = 1000;
  options.symbolic = false;  // the hunt's own test: the symbolic search would decide it first,
  options.walks = false;     // and so would the random walks
  LivenessResult r = checkLiveness(parse(m + "property p : eventually {got || " + sum + " == 99};\n"), small, options);
  ASSERT_EQ(r.properties.size(), 1u);
  EXPECT_EQ(r.properties[0].verdict, Verdict::Violated);
  ASSERT_TRUE(r.properties[0].counterexample.has_value());
  EXPECT_TRUE(r.methods[0].roundRobin);
  const Trace& t = *r.properties[0].counterexample;
  EXPECT_TRUE(std::any_of(t.steps.begin(), t.steps.end(), [](const Step& s) { return s.rule == 9; })) << "the lasso loses the message";
}

TEST(Liveness, TheRoundRobinHuntTriesCrashesLast) {
  // The worker finishes unless it crashes first; the counters, as above, keep the slices and a
  // breadth-first search from any loop. Only the stage that allows crashes finds the violation.
  std::string m = "semo-ir 1;\nvar alive : bool = true;\nvar done : bool = false;\n";
  const test::ResettingCounters counters = test::resettingCounters();
  const std::string& sum = counters.sum;
  m += counters.declarations;
  m += "rule crash @kind(crash) : alive -> alive' = false;\n"
       "rule work @fair : alive && !done -> done' = true;\n"
       + counters.resetRule;
  SearchLimits small;
  small.maxStates = 1000;
  LivenessOptions options;
  options.sliceStates = 1000;
  options.symbolic = false;  // the hunt's own test: the symbolic search would decide it first,
  options.walks = false;     // and so would the random walks
  LivenessResult r = checkLiveness(parse(m + "property p : eventually {done || " + sum + " == 99};\n"), small, options);
  ASSERT_EQ(r.properties.size(), 1u);
  EXPECT_EQ(r.properties[0].verdict, Verdict::Violated);
  ASSERT_TRUE(r.properties[0].counterexample.has_value());
  EXPECT_TRUE(r.methods[0].roundRobin);
  const Trace& t = *r.properties[0].counterexample;
  EXPECT_TRUE(std::any_of(t.steps.begin(), t.steps.end(), [](const Step& s) { return s.rule == 8; })) << "the worker crashes";
}

TEST(Buchi, AcceptanceSetsOnePerUntil) {
  ir::Model m = parse("semo-ir 1;\nvar x : bool;\nproperty p : always eventually {x} && eventually {!x};\n");
  Buchi b = buildBuchi(m.properties[0].formula);
  EXPECT_EQ(b.acceptanceSets, 2u);
  EXPECT_FALSE(b.states.empty());
  Buchi safety = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Always, ir::Ltl::of(ir::Expr::var(0))));
  EXPECT_EQ(safety.acceptanceSets, 1u) << "no until: every state accepts";
  for (const BuchiState& s : safety.states) EXPECT_EQ(s.acceptance, 1u);
}

TEST(Buchi, AcceptedLoopStatesAreTheComponentsWithEverySet) {
  Buchi b;
  b.acceptanceSets = 2;
  auto add = [&](std::vector<std::uint32_t> successors, std::uint64_t acceptance) {
    BuchiState s;
    s.successors = std::move(successors);
    s.acceptance = acceptance;
    b.states.push_back(s);
  };
  add({0, 1}, 0);  // 0: loops on itself, no set, and leads to 1
  add({1}, 3);     // 1: a self-loop in both sets
  add({0}, 3);     // 2: in both sets but on no cycle
  add({4}, 1);     // 3, 4: one component, each in one of the sets
  add({3}, 2);
  add({5}, 1);     // 5: a self-loop in one set only
  EXPECT_EQ(acceptedLoopStates(b), (std::vector<char>{0, 1, 0, 1, 1, 0}));
  // Of `eventually always !x` (the negation of `always eventually x`), the state still waiting to
  // settle loops without accepting: it is left out, the settled one kept.
  ir::Model m = parse("semo-ir 1;\nvar x : bool;\nproperty p : always eventually {x};\n");
  const Buchi negated = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, m.properties[0].formula));
  const std::vector<char> loops = acceptedLoopStates(negated);
  EXPECT_NE(std::count(loops.begin(), loops.end(), 1), 0);
  EXPECT_NE(std::count(loops.begin(), loops.end(), 0), 0);
}

TEST(IrText, PropertiesReadBackTheSame) {
  std::string text = "semo-ir 1;\nvar c : 0..3 = 0;\nrule inc @strongly_fair : c < 3 -> c' = c + 1;\n"
                     "property p1 : always ({c == 1} => eventually {c == 3});\n"
                     "property \"p 2\" @origin(\"x:1:2\") : ({c > 0} until {c > 1} || next !{c == 0}) && {true} release always {c < 3};\n";
  ir::Model m = parse(text);
  ASSERT_EQ(m.properties.size(), 2u);
  EXPECT_TRUE(m.rules[0].stronglyFair && m.rules[0].weaklyFair);
  EXPECT_EQ(m.properties[1].origin, "x:1:2");
  EXPECT_EQ(m.properties[1].formula.kind, ir::Ltl::Kind::Release);
  std::string once = ir::toText(m);
  EXPECT_EQ(ir::toText(parse(once)), once);
  EXPECT_NE(once.find("rule inc @strongly_fair"), std::string::npos) << once;
}

}  // namespace
}  // namespace semo::checker
