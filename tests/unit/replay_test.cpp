// Replay (runtime/replay.hpp, checker/replay_monitor.hpp) on the seeded defects: every IR rule has
// the place where the runtime takes it; a counterexample the checker finds happens step for step in
// the running team; a runtime that differs from the model (a mutated table) is caught, never
// reported as the violation.
#include <gtest/gtest.h>

#include "mission_fixture.hpp"

#include <algorithm>

#include "semo/checker/explicit_search.hpp"
#include "semo/checker/replay_monitor.hpp"
#include "semo/checker/trace.hpp"
#include "semo/codegen/project.hpp"
#include "semo/runtime/replay.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

using Loaded = test::LoadedMission;

// `mission` and `strategy` relative to specs/.
std::unique_ptr<Loaded> load(const std::string& mission, const std::string& strategy) { return test::loadSpec(mission, strategy); }

// The checker's counterexample for `property`, read back as `replay` reads it.
std::optional<checker::ReplayedTrace> counterexample(Loaded& l, const std::string& property) {
  checker::SearchLimits limits;
  limits.symmetry = false;
  const checker::SearchResult result = checker::checkSafety(l.translation->model, limits);
  for (const checker::PropertyResult& p : result.properties) {
    if (p.name != property || !p.counterexample) continue;
    const FileId file = l.sources.add("trace.json", checker::traceToJson(l.translation->model, *p.counterexample));
    DiagnosticEngine diags(l.sources);
    return checker::readTrace(l.sources, file, l.translation->model, diags);
  }
  return std::nullopt;
}

struct Replayed {
  runtime::SimTrace run;
  std::unique_ptr<checker::ReplayMonitor> monitor;
};

Replayed replay(const Loaded& l, const checker::ReplayedTrace& trace) {
  Replayed r;
  r.monitor = std::make_unique<checker::ReplayMonitor>(l.translation->model, l.tables, trace, 3);
  const runtime::World world;  // no world: the robots stand in a row per team
  runtime::SimulationOptions options;
  options.stopAtGoal = false;
  r.run = runtime::replay(l.tables, world, runtime::TaskLibrary::standard(), checker::ReplayMonitor::script(trace, 3), options,
                          runtime::ReplayOptions{0.5, trace.kind == checker::ReplayedTrace::Kind::Deadlock ? 5.0 : 0.0}, r.monitor.get());
  return r;
}

TEST(ReplaySites, EveryRuleIsAStepOfTheRuntime) {
  const std::vector<std::pair<std::string, std::string>> missions = {
      {"examples/scouting/scouting.semo", "examples/scouting/strategy.xml"},
      {"examples/swarm/swarm3.semo", "examples/swarm/strategy.xml"},
      {"examples/chase/chase.semo", "examples/chase/strategy.xml"},
      {"examples/deployment/deployment.semo", "examples/deployment/strategy.xml"},
      {"examples/patrol/patrol.semo", "examples/patrol/strategy.xml"},
      {"defects/leader_timeout.semo", "defects/leader_timeout_short.xml"},
      {"defects/double_receive.semo", "defects/strategy.xml"},
      {"defects/early_clear.semo", "defects/strategy.xml"},
      {"defects/liveness/stuck_gossip.semo", "defects/liveness/strategy.xml"},
      {"defects/liveness/orphaned_relay.semo", "defects/liveness/orphaned_relay_timeout.xml"},
  };
  for (const auto& [mission, strategy] : missions) {
    auto l = load(mission, strategy);
    ASSERT_TRUE(l) << mission;
    const std::vector<runtime::RuleSite> sites = runtime::ruleSites(l->tables);
    ASSERT_EQ(sites.size(), l->translation->model.rules.size()) << mission;
    for (std::size_t r = 0; r < sites.size(); ++r) {
      EXPECT_NE(sites[r].kind, runtime::RuleSite::Kind::None) << mission << ": " << l->translation->model.rules[r].name;
    }
  }
}

TEST(Replay, TheLeaderTimeoutDefectHappensStepForStep) {
  auto l = load("defects/leader_timeout.semo", "defects/leader_timeout_short.xml");
  ASSERT_TRUE(l);
  auto trace = counterexample(*l, "unique_leader[Relay]");
  ASSERT_TRUE(trace);
  ASSERT_EQ(trace->rules.size(), 3U);
  Replayed r = replay(*l, *trace);
  EXPECT_FALSE(r.monitor->failed()) << r.monitor->why();
  EXPECT_EQ(r.monitor->violatedAt(), std::optional<std::size_t>(3));
  // The running team's steps are the counterexample's rules, in order.
  std::vector<std::string> taken;
  for (const runtime::TraceEvent& e : r.run.events) {
    if (e.kind == runtime::TraceEvent::Kind::Step && !e.rule.empty()) taken.push_back(e.rule);
  }
  ASSERT_EQ(taken.size(), 3U);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(taken[k], l->translation->model.rules[trace->rules[k]].name);
  // Two leaders at once, in the runtime's own state: both scouts believe they lead.
  std::size_t leaders = 0;
  for (const runtime::LeaderChange& c : r.run.summary.leaderChanges) leaders += c.to != runtime::kNoRobot ? 1 : 0;
  EXPECT_EQ(leaders, 2U);
}

TEST(Replay, ADeadlockStaysStuckWhenTheTeamRunsOnFreely) {
  auto l = load("defects/double_receive.semo", "defects/strategy.xml");
  ASSERT_TRUE(l);
  auto trace = counterexample(*l, "deadlock_freedom");
  ASSERT_TRUE(trace);
  Replayed r = replay(*l, *trace);
  EXPECT_FALSE(r.monitor->failed()) << r.monitor->why();
  EXPECT_EQ(r.monitor->violatedAt(), std::optional<std::size_t>(trace->rules.size()));
  EXPECT_EQ(r.monitor->freeSteps(), 0U);
  EXPECT_GE(r.run.duration, 0.5 * static_cast<double>(trace->rules.size()) + 5.0 - 1e-9);  // it did run on
}

TEST(Replay, ARuntimeThatTimesOutLaterCannotTakeTheTakeover) {
  auto l = load("defects/leader_timeout.semo", "defects/leader_timeout_short.xml");
  ASSERT_TRUE(l);
  auto trace = counterexample(*l, "unique_leader[Relay]");
  ASSERT_TRUE(trace);
  for (runtime::LeaderBlockTable& block : l->tables.leaderBlocks) block.timeoutPeriods += 3;  // not the verified timeout
  Replayed r = replay(*l, *trace);
  EXPECT_FALSE(r.monitor->violatedAt());
  ASSERT_FALSE(r.run.summary.violations.empty());
  EXPECT_NE(r.run.summary.violations.front().find("step 3 ("), std::string::npos) << r.run.summary.violations.front();
  EXPECT_NE(r.run.summary.violations.front().find("does not suspect the leader"), std::string::npos) << r.run.summary.violations.front();
}

TEST(Replay, ARowWithoutItsEffectIsCaughtByTheMonitor) {
  auto l = load("defects/flood.semo", "defects/strategy.xml");
  ASSERT_TRUE(l);
  auto trace = counterexample(*l, "buffer_bounds[Rover.mapUpdate]");
  ASSERT_TRUE(trace);
  bool mutated = false;
  for (runtime::RobotTable& robot : l->tables.robots) {
    for (runtime::PlanTable& plan : robot.plans) {
      for (runtime::Row& row : plan.rows) {
        auto send = std::find_if(row.effects.begin(), row.effects.end(), [](const runtime::EffectRow& e) { return e.kind == runtime::EffectRow::Kind::Send; });
        if (send != row.effects.end()) row.effects.erase(send), mutated = true;
      }
    }
  }
  ASSERT_TRUE(mutated);
  Replayed r = replay(*l, *trace);
  EXPECT_TRUE(r.monitor->failed());
  EXPECT_FALSE(r.monitor->violatedAt());
  EXPECT_NE(r.monitor->why().find("step 1"), std::string::npos) << r.monitor->why();
}

TEST(Replay, TheScriptTakesALassosLoopAgain) {
  // (The lassos themselves come from the liveness search; the end-to-end tests replay them.)
  checker::ReplayedTrace lasso;
  lasso.kind = checker::ReplayedTrace::Kind::Lasso;
  lasso.rules = {4, 5, 6, 7, 8};
  lasso.loopStart = 3;
  const std::vector<runtime::Id> script = checker::ReplayMonitor::script(lasso, 3);
  EXPECT_EQ(script, (std::vector<runtime::Id>{4, 5, 6, 7, 8, 7, 8, 7, 8}));
  lasso.loopStart = 5;  // the run stays in its last state: nothing to repeat
  EXPECT_EQ(checker::ReplayMonitor::script(lasso, 3).size(), 5U);
}

}  // namespace
}  // namespace semo
