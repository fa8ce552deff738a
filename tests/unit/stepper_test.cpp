// The stepping API (checker/stepper.hpp) against the explicit checker itself: on every shipped
// mission the Stepper's successors are exactly those the search's successor generator produces,
// state for state, and every counterexample the search finds replays through it step by step.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "../../checker/src/state_store.hpp"
#include "../../checker/src/successors.hpp"
#include "../../checker/src/worker_pool.hpp"
#include "ir_support.hpp"
#include "mission_support.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/stepper.hpp"

namespace semo::checker {
namespace {

using State = Stepper::State;

std::string missionName(const testing::TestParamInfo<test::ShippedMission>& info) {
  std::string n = info.param.mission;
  n = n.substr(n.rfind('/') + 1);
  n = n.substr(0, n.find('.'));
  return n;
}

class StepperOnMissions : public testing::TestWithParam<test::ShippedMission> {};

TEST_P(StepperOnMissions, InitialStateIsTheIrInit) {
  std::optional<ir::Model> m = test::translateShipped(GetParam());
  ASSERT_TRUE(m.has_value());
  Stepper stepper(*m);
  State s = stepper.initial();
  ASSERT_EQ(s.size(), m->variables.size());
  for (std::size_t v = 0; v < s.size(); ++v) EXPECT_EQ(s[v], m->variables[v].init) << m->variables[v].name;
}

// Breadth-first over the reachable states (without symmetry, up to a bound), with the search's own
// successor generator; for each state, the Stepper must list the same successors by the same
// (rule, outcome), in the same order, and agree on which rules are enabled.
TEST_P(StepperOnMissions, SuccessorsAgreeWithTheExplicitSearch) {
  std::optional<ir::Model> m = test::translateShipped(GetParam());
  ASSERT_TRUE(m.has_value());
  Stepper stepper(*m);
  CompiledModel cm(*m);
  const StateLayout& layout = cm.layout();
  const std::size_t words = layout.words();
  detail::StateStore store(words);
  detail::WorkerPool pool(1);
  detail::SuccessorGenerator generator(cm, nullptr, 1);
  std::vector<std::uint64_t> packed(words);
  State init = stepper.initial();
  layout.pack(init.data(), packed.data());
  store.insert(packed.data(), detail::kNoParent, 0);
  constexpr std::size_t kStates = 3000;
  std::size_t compared = 0, transitions = 0;
  State values(layout.variables()), next(layout.variables());
  for (std::size_t first = 0; first < store.size() && first < kStates;) {
    generator.expand(store, first, std::min(store.size(), first + 256), pool);
    for (const detail::Expansion& e : generator.parts()) {
      ASSERT_FALSE(e.rangeError.has_value());
      for (std::size_t i = e.firstState; i < e.endState; ++i) {
        const std::size_t local = i - e.firstState;
        layout.unpack(store.state(i), values.data());
        std::vector<std::pair<Stepper::Choice, State>> expected;
        for (std::uint32_t n = e.begin[local]; n < e.begin[local + 1]; ++n) {
          layout.unpack(&e.packed[n * words], next.data());
          expected.emplace_back(Stepper::Choice{e.via[n] >> 8, e.via[n] & 0xffu}, next);
          store.insert(&e.packed[n * words], static_cast<std::uint32_t>(i), e.via[n]);
        }
        std::vector<std::pair<Stepper::Choice, State>> got = stepper.successors(values);
        ASSERT_EQ(got.size(), expected.size()) << stepper.describe(values);
        for (std::size_t k = 0; k < got.size(); ++k) {
          EXPECT_EQ(got[k].first, expected[k].first) << m->rules[got[k].first.rule].name;
          EXPECT_EQ(got[k].second, expected[k].second) << stepper.describeDifference(got[k].second, expected[k].second);
          // The single-outcome form gives the same state (translated rules have one outcome).
          EXPECT_EQ(stepper.successor(values, got[k].first.rule), got[k].second);
          EXPECT_TRUE(stepper.enabled(values, got[k].first.rule));
        }
        EXPECT_EQ(e.enabled[local] != 0, !stepper.enabledRules(values).empty());
        ++compared;
        transitions += got.size();
      }
    }
    first = generator.expandedEnd();
  }
  EXPECT_GT(compared, 0u);
  EXPECT_GT(transitions, 0u);
}

// Every counterexample of the search replays through the Stepper: each step's rule is enabled and
// leads to the trace's next state, findRule finds a rule that does, and the last state violates
// the property (an invariant) or is a deadlock.
TEST_P(StepperOnMissions, CounterexamplesReplayStepByStep) {
  std::optional<ir::Model> m = test::translateShipped(GetParam());
  ASSERT_TRUE(m.has_value());
  Stepper stepper(*m);
  SearchLimits limits;
  limits.maxStates = 200'000;
  SearchResult r = checkSafety(*m, limits);
  ASSERT_FALSE(r.rangeError.has_value());
  for (const PropertyResult& p : r.properties) {
    if (!p.counterexample) continue;
    SCOPED_TRACE(p.name);
    const Trace& t = *p.counterexample;
    State state = stepper.initial();
    EXPECT_EQ(state, t.initial);
    for (const Step& step : t.steps) {
      ASSERT_TRUE(stepper.enabled(state, step.rule)) << m->rules[step.rule].name;
      State recorded = state;
      for (const Change& c : step.changes) {
        EXPECT_EQ(state[c.var], c.before);
        recorded[c.var] = c.after;
      }
      std::string why;
      std::optional<State> next = stepper.successor(state, Stepper::Choice{step.rule, step.branch}, &why);
      ASSERT_TRUE(next.has_value()) << why;
      ASSERT_EQ(*next, recorded) << stepper.describeDifference(*next, recorded);
      std::optional<std::size_t> found = stepper.findRule(state, recorded);
      ASSERT_TRUE(found.has_value());
      EXPECT_LE(*found, step.rule);  // the lowest rule that leads there
      EXPECT_EQ(stepper.successor(state, *found), recorded);
      state = *next;
    }
    if (t.kind == "deadlock") {
      EXPECT_TRUE(stepper.deadlocked(state)) << stepper.describe(state);
      EXPECT_FALSE(stepper.validEnd(state));
      EXPECT_TRUE(stepper.enabledRules(state).empty());
    } else {
      ASSERT_EQ(t.kind, "invariant");
      auto inv = std::find_if(m->invariants.begin(), m->invariants.end(), [&](const ir::Invariant& i) { return i.name == p.name; });
      ASSERT_NE(inv, m->invariants.end());
      EXPECT_FALSE(stepper.invariantHolds(state, static_cast<std::size_t>(inv - m->invariants.begin()))) << stepper.describe(state);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, StepperOnMissions, testing::ValuesIn(test::shippedMissions()), missionName);

TEST(Stepper, EveryDefectHasACounterexampleThatReplays) {
  // The parametrised replay above is only worth something if the defects are violated.
  std::size_t violated = 0;
  for (const test::ShippedMission& s : test::shippedMissions()) {
    if (std::string(s.mission).find("defects/") == std::string::npos || std::string(s.mission).find("_fixed") != std::string::npos) continue;
    std::optional<ir::Model> m = test::translateShipped(s);
    ASSERT_TRUE(m.has_value());
    SearchResult r = checkSafety(*m, {});
    bool any = std::any_of(r.properties.begin(), r.properties.end(), [](const PropertyResult& p) { return p.counterexample.has_value(); });
    EXPECT_TRUE(any) << s.mission;
    violated += any ? 1 : 0;
  }
  EXPECT_GE(violated, 8u);
}

// A hand-written model: rule order, outcomes, ranges, invariants, valid end, descriptions.
const char* kModel = R"(semo-ir 1;
var c : 0..3 = 0;
var b : bool = false;
var mode : 0..2 = 0 @values("idle busy done");
rule reset : c == 3 -> c' = 0;
rule inc : c < 3 && mode == 0 -> c' = c + 1;
rule coin : mode == 0 -> 0.5: b' = true, mode' = 1 + 0.5: b' = false, mode' = 1;
rule overflow : mode == 1 && c == 2 -> c' = c + 2;
rule finish : mode == 1 -> mode' = 2;
invariant small : c < 3;
valid_end : mode == 2 || c == 3;
)";

TEST(Stepper, RuleIndicesAreTheIrsAndOutcomesAreChosen) {
  ir::Model m = test::parseIr(kModel);
  ASSERT_EQ(m.rules.size(), 5u);
  Stepper s(m);
  State init = s.initial();
  EXPECT_EQ(init, (State{0, 0, 0}));
  EXPECT_EQ(s.enabledRules(init), (std::vector<std::size_t>{1, 2}));
  EXPECT_FALSE(s.enabled(init, 0));
  EXPECT_EQ(s.successor(init, 1), (State{1, 0, 0}));
  EXPECT_EQ(s.branches(2), 2u);

  std::string why;
  EXPECT_FALSE(s.successor(init, 2, &why).has_value()) << "a rule with two outcomes needs one chosen";
  EXPECT_NE(why.find("2 outcomes"), std::string::npos) << why;
  EXPECT_EQ(s.successor(init, Stepper::Choice{2, 0}), (State{0, 1, 1}));
  EXPECT_EQ(s.successor(init, Stepper::Choice{2, 1}), (State{0, 0, 1}));
  EXPECT_THROW((void)s.successor(init, Stepper::Choice{2, 2}), std::out_of_range);
  EXPECT_THROW((void)s.enabled(init, 5), std::out_of_range);
  EXPECT_THROW((void)s.enabled(State{0, 0}, 0), std::invalid_argument);

  EXPECT_FALSE(s.successor(init, 0, &why).has_value());
  EXPECT_NE(why.find("'reset' is not enabled"), std::string::npos) << why;

  auto all = s.successors(init);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].first, (Stepper::Choice{1, 0}));
  EXPECT_EQ(all[2].first, (Stepper::Choice{2, 1}));
  EXPECT_EQ(s.findRule(init, State{0, 0, 1}), 2u);
  EXPECT_EQ(s.findChoice(init, State{0, 0, 1}), (Stepper::Choice{2, 1}));
  EXPECT_FALSE(s.findRule(init, State{2, 0, 0}).has_value());
}

TEST(Stepper, AnUpdateOutOfRangeSaysWhich) {
  ir::Model m = test::parseIr(kModel);
  Stepper s(m);
  State st{2, 1, 1};
  std::string why;
  EXPECT_TRUE(s.enabled(st, 3));
  EXPECT_FALSE(s.successor(st, 3, &why).has_value());
  EXPECT_EQ(why, "rule 'overflow' sets c to 4, outside its range 0..3");
  Stepper::Outcome o = s.apply(st, {3, 0});
  EXPECT_TRUE(o.enabled);
  EXPECT_EQ(o.outOfRange, (std::vector<ir::VarId>{0}));
  EXPECT_EQ(o.state, (State{4, 1, 1}));
  // The out-of-range successor is not among the successors (the search reports it as an error).
  for (const auto& [choice, next] : s.successors(st)) EXPECT_NE(choice.rule, 3u);
  EXPECT_EQ(s.describe(o.state), "c=4 (outside 0..3), b=true, mode=busy");
}

TEST(Stepper, InvariantsValidEndAndDeadlockAsTheCheckerHasThem) {
  ir::Model m = test::parseIr(kModel);
  Stepper s(m);
  EXPECT_TRUE(s.invariantHolds(State{2, 0, 0}, 0));
  EXPECT_FALSE(s.invariantHolds(State{3, 0, 0}, 0));
  EXPECT_THROW((void)s.invariantHolds(State{3, 0, 0}, 1), std::out_of_range);
  EXPECT_TRUE(s.validEnd(State{0, 0, 2}));
  EXPECT_FALSE(s.deadlocked(State{0, 0, 2}));  // no rule enabled, but a valid end
  EXPECT_FALSE(s.deadlocked(State{1, 0, 1}));  // finish is enabled
  ir::Model stuck = test::parseIr("semo-ir 1;\nvar x : 0..1 = 0;\nrule go : x == 0 -> x' = 1;\nvalid_end : false;\n");
  Stepper t(stuck);
  EXPECT_FALSE(t.deadlocked(State{0}));
  EXPECT_TRUE(t.deadlocked(State{1}));
  ir::Model noEnd = test::parseIr("semo-ir 1;\nvar x : 0..1 = 1;\nrule go : x == 0 -> x' = 1;\n");
  Stepper u(noEnd);
  EXPECT_TRUE(u.validEnd(State{1}));
  EXPECT_FALSE(u.deadlocked(State{1})) << "without valid_end deadlock freedom is not checked";
}

TEST(Stepper, DescribesStatesAndDifferences) {
  ir::Model m = test::parseIr(kModel);
  Stepper s(m);
  EXPECT_EQ(s.describe(State{1, 0, 2}), "c=1, b=false, mode=done");
  EXPECT_EQ(s.describeDifference(State{1, 0, 0}, State{1, 1, 1}), "b: false -> true, mode: idle -> busy");
  EXPECT_EQ(s.describeDifference(State{1, 0, 0}, State{1, 0, 0}), "");
}

TEST(Stepper, KeepsItsOwnCopyOfTheModelAndMoves) {
  std::optional<Stepper> s;
  {
    ir::Model m = test::parseIr(kModel);
    s.emplace(m);
  }
  Stepper moved = std::move(*s);
  EXPECT_EQ(moved.model().rules.size(), 5u);
  EXPECT_EQ(moved.successor(moved.initial(), 1), (State{1, 0, 0}));
}

}  // namespace
}  // namespace semo::checker
