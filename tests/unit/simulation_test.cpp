// The projection (codegen::project) and the simulator with the conformance monitor, on the shipped
// missions: every IR rule of a robot's program is one row; failure detection and election keep the
// strategy's timing; a projection that differs from the IR in one row is caught at run time.
#include <gtest/gtest.h>

#include "mission_fixture.hpp"

#include <algorithm>
#include <fstream>
#include <set>
#include <iterator>

#include "semo/checker/conformance.hpp"
#include "semo/codegen/project.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

using Loaded = test::LoadedMission;

std::unique_ptr<Loaded> load(const std::string& dir, const std::string& stem, const std::string& strategy = "strategy.xml") {
  return test::loadExample(dir, stem, strategy);
}

TEST(Projection, EveryProgramRuleIsOneRowAndEveryVariableIsAbstracted) {
  for (auto [dir, stem] : {std::pair{"scouting", "scouting"}, std::pair{"swarm", "swarm3"}, std::pair{"chase", "chase"},
                           std::pair{"deployment", "deployment"}, std::pair{"patrol", "patrol"}}) {
    auto l = load(dir, stem);
    ASSERT_TRUE(l) << dir;
    const ir::Model& ir = l->translation->model;
    std::vector<int> seen(ir.rules.size(), 0);
    for (const runtime::RobotTable& robot : l->tables.robots) {
      for (const runtime::PlanTable& plan : robot.plans) {
        ASSERT_EQ(plan.firstRow.size(), plan.points.size() + 1);
        for (std::size_t pc = 0; pc < plan.points.size(); ++pc) {
          for (runtime::Id k = plan.firstRow[pc]; k < plan.firstRow[pc + 1]; ++k) EXPECT_EQ(plan.rows[k].from, pc);
        }
        for (const runtime::Row& row : plan.rows) {
          if (row.irRule != runtime::kNone) ++seen[row.irRule];
        }
      }
    }
    for (std::size_t r = 0; r < ir.rules.size(); ++r) {
      const bool program = l->translation->lowering.rules[r].kind == lowering::RuleMeaning::Kind::ProgramStep;
      EXPECT_EQ(seen[r], program ? 1 : 0) << dir << ": " << ir.rules[r].name;
    }
    ASSERT_EQ(l->tables.abstraction.size(), ir.variables.size());
    for (std::size_t v = 0; v < ir.variables.size(); ++v) {
      EXPECT_EQ(l->tables.abstraction[v].name, ir.variables[v].name);
      EXPECT_EQ(l->tables.abstraction[v].init, ir.variables[v].init);
    }
  }
}

TEST(Simulation, TheInitialStateIsTheModels) {
  auto l = load("scouting", "scouting");
  ASSERT_TRUE(l);
  checker::Stepper stepper(l->translation->model);
  EXPECT_EQ(runtime::initialAbstractState(l->tables), stepper.initial());
}

TEST(Simulation, ANewLeaderWithinTheTimeoutPlusOnePeriod) {
  auto l = load("scouting", "scouting");
  ASSERT_TRUE(l && l->world);
  const runtime::LeaderBlockTable& block = l->tables.leaderBlocks.front();
  const double timeout = block.timeoutPeriods * block.heartbeat;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    runtime::SimulationOptions options;
    options.seed = seed;
    options.crashes.push_back({"leader", 5.0});
    checker::ConformanceMonitor monitor(l->translation->model, l->tables);
    runtime::SimTrace trace = runtime::simulate(l->tables, *l->world, runtime::TaskLibrary::standard(), options, &monitor);
    EXPECT_EQ(trace.summary.mismatches, 0u) << monitor.why();
    EXPECT_TRUE(trace.summary.outsideAssumptions.empty());
    const auto takeover = std::find_if(trace.summary.leaderChanges.begin(), trace.summary.leaderChanges.end(),
                                       [](const runtime::LeaderChange& c) { return c.sinceCrash >= 0; });
    ASSERT_NE(takeover, trace.summary.leaderChanges.end()) << "seed " << seed;
    // Silence is counted in whole heartbeat periods: at least timeout - one period, at most timeout + one.
    EXPECT_GE(takeover->sinceCrash, timeout - block.heartbeat);
    EXPECT_LE(takeover->sinceCrash, timeout + block.heartbeat);
    // Bully: the leader elected first is the most preferred of those forming the block.
    EXPECT_NE(takeover->from, takeover->to);
  }
}

TEST(Simulation, ARowThatDiffersFromTheModelIsCaught) {
  auto l = load("scouting", "scouting");
  ASSERT_TRUE(l && l->world);
  // Send one of ev3_0's steps to the wrong place: the running robot now does something the verified
  // model does not allow, and the monitor must say so when it happens.
  runtime::RobotTable& ev3 = *std::find_if(l->tables.robots.begin(), l->tables.robots.end(), [](const auto& r) { return r.name == "ev3_0"; });
  bool mutated = false;
  for (runtime::PlanTable& plan : ev3.plans) {
    for (runtime::Row& row : plan.rows) {
      // The first step of CommOperator: no operator command, on to the loop's back edge.
      const bool noCommand = std::any_of(row.actions.begin(), row.actions.end(), [](const runtime::ActionRow& a) {
        return a.kind == runtime::ActionRow::Kind::Sense && !a.expect;
      });
      if (!mutated && plan.name == "Listen" && row.irRule != runtime::kNone && noCommand && row.to != row.from && row.to != 0) {
        row.to = 0;
        mutated = true;
      }
    }
  }
  ASSERT_TRUE(mutated);
  checker::ConformanceMonitor monitor(l->translation->model, l->tables);
  runtime::SimTrace trace = runtime::simulate(l->tables, *l->world, runtime::TaskLibrary::standard(), {}, &monitor);
  EXPECT_EQ(trace.summary.mismatches, 1u);
  ASSERT_FALSE(trace.summary.violations.empty());
  EXPECT_NE(trace.summary.violations.front().find("conformance: at "), std::string::npos) << trace.summary.violations.front();
  EXPECT_NE(trace.summary.violations.front().find("ev3_0.pc.Listen"), std::string::npos) << trace.summary.violations.front();
  EXPECT_EQ(trace.events.back().kind, runtime::TraceEvent::Kind::Violation);
}

TEST(Simulation, CrashesBeyondTheAssumptionLeaveTheModel) {
  auto l = load("scouting", "scouting");
  ASSERT_TRUE(l && l->world);
  runtime::SimulationOptions options;
  options.crashes = {{"ev3_0", 4.0}, {"burger_1", 6.0}};  // the verify block assumes at most one crash
  checker::ConformanceMonitor monitor(l->translation->model, l->tables);
  runtime::SimTrace trace = runtime::simulate(l->tables, *l->world, runtime::TaskLibrary::standard(), options, &monitor);
  EXPECT_EQ(trace.summary.mismatches, 0u) << monitor.why();
  EXPECT_NE(trace.summary.outsideAssumptions.find("burger_1 crashed, beyond the model's assumption of at most 1"), std::string::npos)
      << trace.summary.outsideAssumptions;
}

TEST(Simulation, KnowledgeSpreadsOnlyWhenShared) {
  auto shared = load("swarm", "swarm3");
  auto none = load("swarm", "swarm3", "strategy_no_sharing.xml");
  ASSERT_TRUE(shared && none && shared->world && none->world);
  for (Loaded* l : {shared.get(), none.get()}) {
    checker::ConformanceMonitor monitor(l->translation->model, l->tables);
    runtime::SimTrace trace = runtime::simulate(l->tables, *l->world, runtime::TaskLibrary::standard(), {}, &monitor);
    EXPECT_EQ(trace.summary.mismatches, 0u) << monitor.why();
    const bool sharing = l == shared.get();
    EXPECT_EQ(trace.summary.completed, sharing);
    EXPECT_EQ(trace.summary.convergedAt.front().second >= 0, sharing);
  }
  EXPECT_TRUE(none->tables.knowledge.front().shared == false);
}


// ---------------------------------------------------------------- election and failure detection
// specs/defects/leader_timeout.semo: two scouts elect a relay leader; heartbeats may be lost, at most
// one in a row. leader_timeout_ok.xml: bully, 500 ms heartbeat, 2 s timeout (four periods);
// leader_timeout_short.xml: 600 ms (one period), too short for one lost heartbeat.

// The file `file` of specs/defects with `from` replaced by `to`, written elsewhere with the robots'
// URDF paths made absolute (so that they still resolve), for a variant no shipped file has.
std::string variant(const std::string& file, const std::string& from, const std::string& to) {
  const std::string dir = std::string(SEMO_SOURCE_DIR) + "/specs/defects/";
  std::ifstream in(dir + file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto replaceAll = [&text](const std::string& a, const std::string& b) {
    for (std::size_t at = text.find(a); at != std::string::npos; at = text.find(a, at + b.size())) text.replace(at, a.size(), b);
  };
  replaceAll(from, to);
  replaceAll("urdf=\"../robots/", "urdf=\"" + std::string(SEMO_SOURCE_DIR) + "/specs/robots/");
  const std::string path = ::testing::TempDir() + "semo_variant_" + file;
  std::ofstream(path) << text;
  return path;
}

std::string robotName(const runtime::MissionTables& t, std::uint32_t r) { return r == runtime::kNoRobot ? "-" : t.robots[r].name; }

TEST(Election, BullyElectsTheHighestIndexLowestIdTheLowest) {
  const std::string lowestId = variant("leader_timeout_ok.xml", "algorithm=\"bully\"", "algorithm=\"lowest-id\"");
  for (const auto& [strategy, expected] : {std::pair<std::string, std::string>{"defects/leader_timeout_ok.xml", "scout_1"},
                                           {lowestId, "scout_0"}}) {
    SCOPED_TRACE(strategy);
    auto l = test::loadSpec("defects/leader_timeout.semo", strategy);
    ASSERT_TRUE(l);
    runtime::SimulationOptions options;
    options.duration = 10;
    checker::ConformanceMonitor monitor(l->translation->model, l->tables);
    const runtime::SimTrace trace = runtime::simulate(l->tables, runtime::World{}, runtime::TaskLibrary::standard(), options, &monitor);
    EXPECT_EQ(trace.summary.mismatches, 0u) << monitor.why();
    ASSERT_EQ(trace.summary.leaderChanges.size(), 1u) << "one election, no loss, no crash: the leader stays";
    EXPECT_EQ(robotName(l->tables, trace.summary.leaderChanges.front().to), expected);
    EXPECT_EQ(trace.summary.leaderChanges.front().from, runtime::kNoRobot);
  }
}

// Four silent periods, and heartbeats lost at most one in a row: the follower never suspects a live
// leader, however many heartbeats are lost; when the leader crashes it takes over after the timeout.
TEST(FailureDetector, NeverSuspectsALiveLeaderWithinTheAssumedLossAndCatchesACrash) {
  auto l = test::loadSpec("defects/leader_timeout.semo", "defects/leader_timeout_ok.xml");
  ASSERT_TRUE(l);
  const runtime::LeaderBlockTable& block = l->tables.leaderBlocks.front();
  ASSERT_EQ(block.timeoutPeriods, 4);
  ASSERT_TRUE(block.lossyHeartbeats);
  int lossyRunsWithin = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    runtime::SimulationOptions options;
    options.seed = seed;
    options.duration = 25;
    options.loss = 0.1;
    options.crashes.push_back({"scout_1", 12.0});  // the bully leader
    checker::ConformanceMonitor monitor(l->translation->model, l->tables);
    const runtime::SimTrace trace = runtime::simulate(l->tables, runtime::World{}, runtime::TaskLibrary::standard(), options, &monitor);
    EXPECT_EQ(trace.summary.mismatches, 0u) << monitor.why();
    if (!trace.summary.outsideAssumptions.empty()) continue;  // two lost in a row: the model promises nothing
    if (trace.summary.messagesLost > 0) ++lossyRunsWithin;
    ASSERT_EQ(trace.summary.leaderChanges.size(), 2u) << "elected, then replaced after the crash only";
    const runtime::LeaderChange& takeover = trace.summary.leaderChanges.back();
    EXPECT_EQ(robotName(l->tables, takeover.to), "scout_0");
    EXPECT_GE(takeover.t, 12.0);
    // k silent periods, of which the last lossBurst may have been lost heartbeats before the crash;
    // the first period after the crash comes at once or up to one period later.
    EXPECT_GE(takeover.sinceCrash, (block.timeoutPeriods - block.lossBurst - 1) * block.heartbeat - 1e-9);
    EXPECT_LE(takeover.sinceCrash, block.timeoutPeriods * block.heartbeat + 1e-9);
  }
  EXPECT_GE(lossyRunsWithin, 5) << "enough runs lost heartbeats and stayed within the assumption";
}

// One silent period is too short: a lost heartbeat makes a follower take over while the leader lives
// (the defect check finds two leaders). At the next heartbeat period the less preferred leader hears
// the more preferred one and steps down. Three scouts: the model's heartbeat period runs while some
// candidate waits in `others`, so with two scouts both leading there is no period and no step-down.
TEST(Election, TheLessPreferredOfTwoLeadersStepsDown) {
  auto l = test::loadSpec(variant("leader_timeout.semo", "scout[2]", "scout[3]"), "defects/leader_timeout_short.xml");
  ASSERT_TRUE(l);
  runtime::World world;
  for (std::size_t r = 0; r < l->tables.robots.size(); ++r) world.starts.push_back({l->tables.robots[r].name, {static_cast<double>(r), 0}, 0, {}});
  world.places.push_back({"south", {2, -2}, {}});
  int stepDowns = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    runtime::SimulationOptions options;
    options.seed = seed;
    options.duration = 20;
    options.loss = 0.3;
    // No conformance monitor: it would stop the run at the violation of unique_leader.
    const runtime::SimTrace trace = runtime::simulate(l->tables, world, runtime::TaskLibrary::standard(), options);
    std::set<std::string> leaders;
    for (const runtime::TraceEvent& e : trace.events) {
      if (e.kind != runtime::TraceEvent::Kind::Role || e.robot == runtime::kNoRobot) continue;
      const std::string who = robotName(l->tables, e.robot);
      if (e.label.rfind("leader of", 0) == 0) leaders.insert(who);
      if (e.label.find("steps down") == std::string::npos) continue;
      ++stepDowns;
      // Bully: scout_2 is preferred to scout_1, scout_1 to scout_0. The one stepping down hears a
      // more preferred live leader.
      EXPECT_NE(who, "scout_2") << "seed " << seed << " at " << e.t << " s";
      EXPECT_TRUE(leaders.count("scout_2") != 0 || (who == "scout_0" && leaders.count("scout_1") != 0)) << "seed " << seed;
      leaders.erase(who);
    }
  }
  EXPECT_GE(stepDowns, 3) << "a loss of 30% makes false takeovers, and step-downs, happen";
}

}  // namespace
}  // namespace semo
