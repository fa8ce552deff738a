// The projection (codegen::project) and the simulator with the conformance monitor, on the shipped
// missions: every IR rule of a robot's program is one row; failure detection and election keep the
// strategy's timing; a projection that differs from the IR in one row is caught at run time.
#include <gtest/gtest.h>

#include "mission_fixture.hpp"

#include <algorithm>

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

}  // namespace
}  // namespace semo
