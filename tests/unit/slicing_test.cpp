// Property-directed slicing (checker/slicing.hpp, sliced_liveness.cpp), fairness groups and the
// settling world (specs/ir.md): the slice's abstraction, the semantics of groups and of @settled on
// hand-made models, the independent lasso check, and random models on which the sliced search, the
// whole product and the product up to symmetry must give the same verdicts, every lasso passing the
// independent check.
#include <gtest/gtest.h>

#include "ir_support.hpp"
#include "random_model.hpp"
#include "semo/checker/compiled_model.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/slicing.hpp"
#include "semo/checker/stepper.hpp"

#include <algorithm>
#include <set>

namespace semo::checker {
namespace {

LivenessResult run(const ir::Model& m, bool slicing, bool symmetry = false) {
  SearchLimits limits;
  limits.symmetry = symmetry;
  LivenessOptions options;
  options.slicing = slicing;
  return checkLiveness(m, limits, options);
}

Verdict verdict(const std::string& text, bool slicing = true, LivenessResult* out = nullptr) {
  LivenessResult r = run(test::parseIr(text), slicing);
  EXPECT_TRUE(r.complete) << r.limitReached;
  if (out != nullptr) *out = r;
  return r.properties.at(0).verdict;
}

// --- the abstraction ---------------------------------------------------------------------------

TEST(Slicing, GuardsWeakenAndTheirFairnessGoesNewValuesBecomeChoices) {
  ir::Model m = test::parseIr(
      "semo-ir 1;\nvar a : 0..3 = 0;\nvar b : 0..2 = 0;\nvar c : bool = false;\n"
      "rule step @fair : a < 3 && b == 1 -> a' = a + 1;\n"              // guard reads b: weakened, unfair
      "rule copy @fair : a == 0 -> a' = c ? 2 : 1;\n"                   // new value reads c: two outcomes
      "rule other @fair : b < 2 -> b' = b + 1;\n"                       // assigns no kept variable: left out
      "rule exact @fair : a == 3 -> a' = 0;\n"                          // exact: keeps its fairness
      "property p : always eventually {a == 3};\n");
  std::vector<char> keep(m.variables.size(), 0);
  Slice s = sliceModel(m, 0, keep);
  ASSERT_EQ(s.variables.size(), 1u);  // a, the only variable the property reads
  EXPECT_EQ(s.leftOut, 1u);
  ASSERT_EQ(s.model.rules.size(), 3u);
  EXPECT_EQ(s.model.rules[0].name, "step");
  EXPECT_FALSE(s.model.rules[0].weaklyFair);
  EXPECT_FALSE(s.exactGuard[0]);
  EXPECT_EQ(s.model.rules[1].name, "copy");
  EXPECT_TRUE(s.model.rules[1].weaklyFair);  // its guard is exact; only its update is not
  EXPECT_EQ(s.model.rules[1].branches.size(), 2u);
  EXPECT_FALSE(s.exactUpdates[1]);
  EXPECT_TRUE(s.model.rules[2].weaklyFair);
  EXPECT_EQ(s.fairnessDropped, 1u);
}

// The cone of influence keeps exactly what the property depends on, transitively; the hunt then
// drops the crash and environment steps no fairness asks for, the slice's maps kept in step.
TEST(Slicing, TheConeKeepsWhatThePropertyDependsOnAndTheHuntDropsUnfairCrashes) {
  const ir::Model m = test::parseIr(
      "semo-ir 1;\nvar w : 0..2 = 0;\nvar x : 0..2 = 0;\nvar y : 0..2 = 0;\nvar z : bool = false;\n"
      "rule watch @fair : x == 1 -> w' = 2;\n"          // reads x, but nothing in the cone reads w
      "rule crash @kind(crash) : true -> z' = true;\n"  // the cone reads z: kept by the slice
      "rule set @fair : y == 1 -> x' = 1;\n"            // x depends on y
      "rule pick @fair : true -> y' = z ? 1 : 2;\n"     // y depends on z
      "property p : always eventually {x == 1};\n");
  const std::vector<char> cone = coneOfInfluence(m, 0);
  EXPECT_EQ(cone, (std::vector<char>{0, 1, 1, 1}));
  Slice s = sliceModel(m, 0, cone);
  ASSERT_EQ(s.model.rules.size(), 3u);
  EXPECT_EQ(s.leftOut, 1u);
  for (char exact : s.exactGuard) EXPECT_TRUE(exact);
  for (char exact : s.exactUpdates) EXPECT_TRUE(exact);
  EXPECT_EQ(withoutUnfairEnvironment(s), 1u);
  ASSERT_EQ(s.model.rules.size(), 2u);
  EXPECT_EQ(s.model.rules[0].name, "set");
  EXPECT_EQ(s.model.rules[1].name, "pick");
  EXPECT_EQ(s.rules, (std::vector<std::uint32_t>{2, 3}));
  EXPECT_EQ(s.exactGuard.size(), 2u);
}

TEST(Slicing, AGroupKeepsItsFairnessOnlyWhenTheSliceSeesEveryRuleOfIt) {
  ir::Model m = test::parseIr(
      "semo-ir 1;\nvar pc : 0..1 = 0;\nvar x : bool = false;\nvar y : bool = false;\n"
      "rule go @fair(g) : pc == 0 -> pc' = 1;\n"
      "rule look @fair(g) : pc == 0 -> y' = true;\n"  // assigns only y: left out, so g is unfair
      "property p : eventually {pc == 1};\n");
  Slice s = sliceModel(m, 0, std::vector<char>(m.variables.size(), 0));
  ASSERT_EQ(s.model.rules.size(), 1u);
  EXPECT_FALSE(s.model.rules[0].weaklyFair);
  // Kept whole, the group is fair again.
  Slice whole = sliceModel(m, 0, std::vector<char>(m.variables.size(), 1));
  EXPECT_TRUE(whole.model.rules[0].weaklyFair && whole.model.rules[1].weaklyFair);
  // The verdict is the same either way: the robot may take `look` for ever.
  EXPECT_EQ(verdict(ir::toText(m), true), Verdict::Violated);
  EXPECT_EQ(verdict(ir::toText(m), false), Verdict::Violated);
}

// --- fairness groups and the settling world ----------------------------------------------------

// A sensor read again and again at a point the robot does not leave: per rule, fairness forces the
// outcome "it held" in the end; as one group, the robot keeps reading, and may read "no" for ever.
TEST(FairnessGroups, ASensorReadAgainAndAgainIsNotForcedToReportEveryOutcome) {
  auto model = [](const std::string& fair) {
    return "semo-ir 1;\nvar seen : bool = false;\n"
           "rule holds " + fair + " @senses(\"r.dark=1\") : !seen -> seen' = true;\n"
           "rule fails " + fair + " @senses(\"r.dark=0\") : !seen -> skip;\n"
           "property p : eventually {seen};\n";
  };
  for (bool slicing : {false, true}) {
    EXPECT_EQ(verdict(model("@fair"), slicing), Verdict::Proven) << slicing;
    LivenessResult r;
    EXPECT_EQ(verdict(model("@fair(r.look)"), slicing, &r), Verdict::Violated) << slicing;
    const Trace& t = *r.properties[0].counterexample;
    ASSERT_EQ(t.steps.size(), 1u);
    EXPECT_EQ(t.loopStart, 0u);
  }
}

// A robot at a point where its only way on is enabled in every other state: per rule nothing is
// owed (neither rule stays enabled); as a group, the robot must move on.
TEST(FairnessGroups, ARobotWhoseWayOnAlternatesStillMovesOn) {
  const std::string text =
      "semo-ir 1;\nvar tick : bool = false;\nvar pc : 0..1 = 0;\n"
      "rule flip @fair : true -> tick' = !tick;\n"
      "rule on_even GROUP : pc == 0 && !tick -> pc' = 1;\n"
      "rule on_odd GROUP : pc == 0 && tick -> pc' = 1;\n"
      "property p : eventually {pc == 1};\n";
  auto with = [&](const std::string& group) {
    std::string t = text;
    for (std::size_t at = t.find("GROUP"); at != std::string::npos; at = t.find("GROUP")) t.replace(at, 5, group);
    return t;
  };
  EXPECT_EQ(verdict(with("@fair"), false), Verdict::Violated);
  EXPECT_EQ(verdict(with("@fair(r.pc0)"), false), Verdict::Proven);
  EXPECT_EQ(verdict(with("@fair(r.pc0)"), true), Verdict::Proven);
}

// An operator switching a robot in and out of manual control: the two never agree while it keeps
// switching; on a settling world (the command keeps its value) they do.
TEST(SettlingWorld, ALoopThatDecidesAConditionBothWaysIsNotASettledRun) {
  auto model = [](const std::string& settled) {
    return "semo-ir 1;\nvar a : 0..1 = 0;\nvar b : 0..1 = 0;\n"
           "rule a_manual @fair(a.sense) @senses(\"a.manual=1\") : a == 0 -> a' = 1;\n"
           "rule a_auto @fair(a.sense) @senses(\"a.manual=0\") : a == 1 -> a' = 0;\n"
           "rule a_stay @fair(a.sense) @senses(\"a.manual=0\") : a == 0 -> skip;\n"
           "rule b_follow @fair : b != a -> b' = a;\n"
           "property p " + settled + " : always eventually {a == b && a == 0};\n";
  };
  // Unsettled, a goes 1 -> 0 -> 1 ... while b, one step behind, catches up only at 1: a lasso.
  LivenessResult r;
  EXPECT_EQ(verdict(model(""), false, &r), Verdict::Violated);
  // Settled: manual for good cannot last (at a == 1 the robot's only way on decides "auto"), and
  // auto for good leaves a at 0, where b follows: every settled run agrees at 0 again and again.
  EXPECT_EQ(verdict(model("@settled"), false), Verdict::Proven);
  EXPECT_EQ(verdict(model("@settled"), true), Verdict::Proven);
  // The unsettled lasso is a fair run, but not one of a settling world.
  ir::Model settled = test::parseIr(model("@settled"));
  LassoCheck c = checkLasso(settled, *r.properties[0].counterexample, settled.properties[0]);
  EXPECT_TRUE(c.valid);
  EXPECT_TRUE(c.unfairGroups.empty());
  EXPECT_FALSE(c.unsettled.empty());
  EXPECT_FALSE(c.counterexample());
}

// --- the independent lasso check ---------------------------------------------------------------

TEST(LassoCheck, LtlOnUltimatelyPeriodicWords) {
  // Positions 0 1 2 3, then back to 1: x = 0 1 2 1 1 2 1 ...
  const std::vector<int> x{0, 1, 2, 1};
  auto holds = [&](const std::string& formula) {
    ir::Model m = test::parseIr("semo-ir 1;\nvar x : 0..2 = 0;\nproperty p : " + formula + ";\n");
    return ltlOnLasso(m.properties[0].formula, x.size(), 1, [&](const ir::Expr& e, std::size_t i) {
      Program p(e);
      Value v = x[i];
      return p.eval(&v) != 0;
    });
  };
  EXPECT_TRUE(holds("always eventually {x == 2}"));
  EXPECT_FALSE(holds("eventually always {x == 1}"));
  EXPECT_TRUE(holds("{x == 0} until {x == 1}"));
  EXPECT_FALSE(holds("{x == 0} until {x == 2}"));
  EXPECT_TRUE(holds("next {x == 1}"));
  EXPECT_TRUE(holds("{x == 2} release {x >= 0}"));
  EXPECT_FALSE(holds("{false} release {x <= 1}"));
  EXPECT_TRUE(holds("always ({x == 2} => next {x == 1})"));
}

TEST(LassoCheck, RefusesWhatIsNotAFairViolatingLasso) {
  ir::Model m = test::parseIr(
      "semo-ir 1;\nvar c : 0..2 = 0;\nrule inc @fair : c < 2 -> c' = c + 1;\nrule reset : c == 2 -> c' = 0;\n"
      "rule idle : true -> skip;\nproperty p : eventually {c == 2};\n");
  Trace t;
  t.kind = "lasso";
  t.steps.push_back({2, 0, {}});  // idle for ever while inc stays enabled: unfair
  t.loopStart = 0;
  LassoCheck unfair = checkLasso(m, t, m.properties[0]);
  EXPECT_TRUE(unfair.valid);
  EXPECT_EQ(unfair.unfairGroups.size(), 1u);
  EXPECT_FALSE(unfair.counterexample());
  t.steps = {{0, 0, {}}};  // inc once, and call it a loop: it does not come back
  EXPECT_FALSE(checkLasso(m, t, m.properties[0]).valid);
  t.steps = {{0, 0, {}}, {0, 0, {}}, {1, 0, {}}};  // 0 1 2 0 ...: fair, but c reaches 2
  t.loopStart = 0;
  LassoCheck satisfied = checkLasso(m, t, m.properties[0]);
  EXPECT_TRUE(satisfied.valid && satisfied.unfairGroups.empty());
  EXPECT_FALSE(satisfied.violates);
  t.steps = {{1, 0, {}}};  // reset is not enabled in the initial state
  EXPECT_FALSE(checkLasso(m, t, m.properties[0]).valid);
}

// A group whose rules split on a removed variable (the two branches of an `if` on it) is enabled
// exactly where the kept variables say: it keeps its fairness, and the slice without the variable
// proves what needs it. Two rules that do not cover every value of the removed variable do not.
TEST(Slicing, AGroupSplitOnARemovedVariableKeepsItsFairnessWhenItsBranchesCoverIt) {
  const std::string split =
      "semo-ir 1;\nvar pc : 0..1 = 0;\nvar c : bool = false;\nvar slot : 0..2 = 0;\n"
      "rule yes @fair(at0) : pc == 0 && c -> pc' = 1;\n"
      "rule no @fair(at0) : pc == 0 && !c -> pc' = 1;\n"
      "rule flip @fair : true -> c' = !c;\n"
      "rule fill : slot < 2 -> slot' = slot + 1;\n"
      "property p : eventually {pc == 1};\n";
  ir::Model m = test::parseIr(split);
  Slice s = sliceModel(m, 0, std::vector<char>(m.variables.size(), 0));
  ASSERT_EQ(s.variables.size(), 1u);
  ASSERT_EQ(s.model.rules.size(), 2u);
  EXPECT_TRUE(s.model.rules[0].weaklyFair && s.model.rules[1].weaklyFair);
  EXPECT_EQ(s.fairnessDropped, 0u);
  LivenessResult r;
  EXPECT_EQ(verdict(split, true, &r), Verdict::Proven);
  EXPECT_EQ(r.methods[0].keptVariables, 1u);  // proven on the slice of pc alone
  // Branches on slot == 1 and slot == 2 leave slot == 0 out: the group may be disabled where the
  // slice cannot see it, so it loses its fairness.
  ir::Model partial = test::parseIr(
      "semo-ir 1;\nvar pc : 0..1 = 0;\nvar slot : 0..2 = 0;\n"
      "rule one @fair(at0) : pc == 0 && slot == 1 -> pc' = 1;\n"
      "rule two @fair(at0) : pc == 0 && slot == 2 -> pc' = 1;\n"
      "rule fill : slot < 2 -> slot' = slot + 1;\n"
      "property p : eventually {pc == 1};\n");
  Slice t = sliceModel(partial, 0, std::vector<char>(partial.variables.size(), 0));
  ASSERT_EQ(t.model.rules.size(), 2u);
  EXPECT_FALSE(t.model.rules[0].weaklyFair);
  EXPECT_EQ(t.fairnessDropped, 2u);
}

// --- control facts ------------------------------------------------------------------------------

// A `default` transition out of a mode whose plan never finishes there never fires, and a test of a
// plan that does not run in a mode is implied there: the rule is left out of slices and of the cone,
// the conjunct dropped, and the variables only they read leave the cone.
TEST(Slicing, ControlFactsRemoveTransitionsThatNeverFireAndImpliedTests) {
  const std::string text =
      "semo-ir 1;\nrobots r;\n"
      "var r.mode : 0..2 = 0 @robot(r);\nvar r.pc.Loop : 0..2 = 1 @robot(r);\nvar r.pc.Once : 0..1 = 1 @robot(r);\n"
      "var r.count : 0..3 = 0 @robot(r);\n"
      "rule r.loop @robot(r) @fair : r.mode == 0 && r.pc.Loop == 1 -> r.pc.Loop' = 2, r.count' = min(r.count + 1, 3);\n"
      "rule r.back @robot(r) @fair : r.mode == 0 && r.pc.Loop == 2 -> r.pc.Loop' = 1;\n"
      "rule r.once @robot(r) @fair : r.mode == 0 && r.pc.Once == 1 -> r.pc.Once' = 0;\n"
      // mode 0's plans never all finish (Loop never reaches 0): this default never fires
      "rule r.default0 @robot(r) @fair : r.mode == 0 && r.pc.Loop == 0 && r.pc.Once == 0 && r.count == 3 -> r.mode' = 1;\n"
      "rule r.go @robot(r) @fair : r.mode == 0 && r.pc.Once == 0 -> r.mode' = 2, r.pc.Loop' = 0, r.pc.Once' = 0;\n"
      // in mode 2 no plan runs: its test of the plans is implied
      "rule r.default2 @robot(r) @fair : r.mode == 2 && r.pc.Loop == 0 && r.pc.Once == 0 -> r.mode' = 0, r.pc.Loop' = 1, r.pc.Once' = 1;\n"
      "property p : always eventually {r.mode == 2};\n";
  const ir::Model m = test::parseIr(text);
  const ControlFacts facts = controlFacts(m);
  auto rule = [&](const std::string& name) {
    for (std::size_t r = 0; r < m.rules.size(); ++r) {
      if (m.rules[r].name == name) return r;
    }
    return m.rules.size();
  };
  EXPECT_TRUE(facts.neverFires[rule("r.default0")]);
  EXPECT_FALSE(facts.neverFires[rule("r.default2")]);
  EXPECT_FALSE(facts.neverFires[rule("r.go")]);
  // r.default2 keeps only `r.mode == 2`; r.go keeps both its tests (neither implies the other).
  std::vector<char> reads(m.variables.size(), 0);
  markVariablesRead(facts.model.rules[rule("r.default2")].guard, reads);
  EXPECT_EQ(std::count(reads.begin(), reads.end(), 1), 1);
  EXPECT_GE(facts.droppedConjuncts, 2u);
  // Without the facts, the cone takes in r.count through r.default0; with them it does not.
  const std::vector<char> plain = coneOfInfluence(m, 0), withFacts = coneOfInfluence(facts.model, 0, facts.neverFires);
  const ir::VarId count = 3;
  ASSERT_EQ(m.variables[count].name, "r.count");
  EXPECT_TRUE(plain[count]);
  EXPECT_FALSE(withFacts[count]);
  EXPECT_EQ(sliceModel(facts.model, 0, withFacts, facts.neverFires).neverFire, 1u);
  // The verdict is the same either way: mode 2 is reached again and again.
  EXPECT_EQ(verdict(text), Verdict::Proven);
}

// On random models, every fact holds on every reachable state (an exhaustive search of the whole
// model): no rule marked as never firing is enabled, and each simplified guard agrees with the
// original one.
TEST(Slicing, ControlFactsHoldOnEveryReachableStateOfRandomModels) {
  std::size_t dead = 0, dropped = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(400); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    const ControlFacts facts = controlFacts(m);
    ASSERT_EQ(facts.robotsSkipped, 0u);
    dropped += facts.droppedConjuncts;
    dead += static_cast<std::size_t>(std::count(facts.neverFires.begin(), facts.neverFires.end(), 1));
    const Stepper whole(m), simplified(facts.model);
    std::set<Stepper::State> seen{whole.initial()};
    std::vector<Stepper::State> frontier{whole.initial()};
    while (!frontier.empty()) {
      const Stepper::State s = frontier.back();
      frontier.pop_back();
      for (std::size_t r = 0; r < m.rules.size(); ++r) {
        const bool enabled = whole.enabled(s, r);
        ASSERT_FALSE(enabled && facts.neverFires[r]) << m.rules[r].name << " fires in " << whole.describe(s);
        ASSERT_EQ(simplified.enabled(s, r), enabled) << m.rules[r].name << " in " << whole.describe(s);
      }
      for (auto& [choice, next] : whole.successors(s)) {
        if (seen.insert(next).second) frontier.push_back(next);
      }
    }
  }
  // The generator gives the analysis something to find.
  EXPECT_GT(dead, static_cast<std::size_t>(test::atLeast(20)));
  EXPECT_GT(dropped, static_cast<std::size_t>(test::atLeast(20)));
}

// Three robots that look alike each toggle p until they stop (weakly fair), and p is then set for
// good. The first slice keeps p alone, and its lasso toggles p by one robot for ever; rebuilt on
// the model, that robot stops, and the refinement keeps its `go`. The other robots would fail the
// same way one round each: their `go`s are kept with it (sliced_liveness.cpp, twins), so one
// refinement decides. A property that names r0 keeps the twins of the robots it does not name.
TEST(Slicing, ARefinementKeepsTheTwinsOfWhatFailedOnRobotsThatLookAlike) {
  const std::string model = R"(semo-ir 1;
robots r0 r1 r2;
var p : bool = false;
var r0.go : bool = false @robot(r0);
var r1.go : bool = false @robot(r1);
var r2.go : bool = false @robot(r2);
rule r0_toggle @robot(r0) : !r0.go -> p' = !p;
rule r1_toggle @robot(r1) : !r1.go -> p' = !p;
rule r2_toggle @robot(r2) : !r2.go -> p' = !p;
rule r0_stop @robot(r0) @fair : !r0.go -> r0.go' = true;
rule r1_stop @robot(r1) @fair : !r1.go -> r1.go' = true;
rule r2_stop @robot(r2) @fair : !r2.go -> r2.go' = true;
rule fix @fair : !p -> p' = true;
)";
  for (const std::string property : {"eventually always {p}", "(eventually always {p}) || always {r0.go}"}) {
    SCOPED_TRACE(property);
    LivenessResult r;
    EXPECT_EQ(verdict(model + "property settles : " + property + ";\n", true, &r), Verdict::Proven);
    EXPECT_TRUE(r.methods.at(0).sliced);
    EXPECT_EQ(r.methods.at(0).refinements, 1u);
    EXPECT_EQ(r.methods.at(0).keptVariables, 4u);
  }
}

// --- random models: the sliced search, the whole product and its quotient agree ------------------

TEST(Slicing, RandomModelsGetTheSameVerdictsAndCheckedLassos) {
  int proven = 0, violated = 0, refined = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(400); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    ir::Model m = test::parseIr(text);
    LivenessResult whole = run(m, false), sliced = run(m, true), quotient = run(m, false, true);
    ASSERT_TRUE(whole.complete && sliced.complete && quotient.complete);
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      SCOPED_TRACE(m.properties[k].name);
      EXPECT_EQ(sliced.properties[k].verdict, whole.properties[k].verdict);
      EXPECT_EQ(quotient.properties[k].verdict, whole.properties[k].verdict);
      EXPECT_NE(whole.properties[k].verdict, Verdict::Unknown);
      for (const LivenessResult* r : {&whole, &sliced, &quotient}) {
        if (r->properties[k].verdict != Verdict::Violated) continue;
        ASSERT_TRUE(r->properties[k].counterexample.has_value()) << r->notes[k];
        LassoCheck c = checkLasso(m, *r->properties[k].counterexample, m.properties[k]);
        EXPECT_TRUE(c.counterexample()) << c.why << " unfair " << c.unfairGroups.size() << " unsettled " << c.unsettled.size();
      }
      proven += whole.properties[k].verdict == Verdict::Proven ? 1 : 0;
      violated += whole.properties[k].verdict == Verdict::Violated ? 1 : 0;
      refined += sliced.methods[k].refinements > 0 ? 1 : 0;
    }
  }
  // The generator is not degenerate: both verdicts, and slices that had to be refined.
  EXPECT_GT(proven, test::atLeast(100));
  EXPECT_GT(violated, test::atLeast(100));
  EXPECT_GT(refined, test::atLeast(20));
}

}  // namespace
}  // namespace semo::checker
