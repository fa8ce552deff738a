// The dataflow half of the projection and its run in the simulator (specs/runtime.md, "Dataflow"):
// the projected capacities, schedules and periods are the SDF analysis' own (scouting); the swarm
// runs its robots' static schedules without a stall or an overflow, never past a proven capacity and
// up to it; one token less on a channel the run fills is caught as an overflow.
#include <gtest/gtest.h>

#include "mission_fixture.hpp"

#include <algorithm>
#include <memory>

#include "semo/checker/conformance.hpp"
#include "semo/codegen/project.hpp"
#include "semo/codegen/project_dataflow.hpp"
#include "semo/runtime/channel.hpp"
#include "semo/sdf/bounds.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

using Loaded = test::LoadedMission;

std::unique_ptr<Loaded> load(const std::string& dir, const std::string& stem) { return test::loadExample(dir, stem); }

TEST(DataflowProjection, CapacitiesSchedulesAndPeriodsAreTheAnalysis) {
  auto l = load("scouting", "scouting");
  ASSERT_TRUE(l);
  DiagnosticEngine diags(l->sources);
  std::optional<std::vector<sdf::TaskGraph>> graphs = sdf::generateTaskGraphs(*l->mission, diags);
  ASSERT_TRUE(graphs);
  sdf::ScenarioCache cache;
  std::vector<sdf::TaskGraphAnalysis> analyses;
  // The analysis the projection asks for by default: safety proofs only.
  const sdf::BoundsOptions options = codegen::runningBounds();
  ASSERT_FALSE(options.proveMinimality);
  for (const sdf::TaskGraph& g : *graphs) analyses.push_back(sdf::analyseTaskGraph(g, options, &cache));
  // The projection analyses nothing again: every scenario graph is in the cache.
  std::optional<codegen::DataflowProjection> projected = codegen::projectDataflow(*l->mission, l->tables, diags, options, &cache);
  ASSERT_TRUE(projected);
  EXPECT_EQ(projected->robots, graphs->size());
  EXPECT_EQ(projected->analysed, 0u);
  EXPECT_EQ(projected->notProven, 0u);

  std::size_t scenarios = 0;
  for (std::size_t r = 0; r < graphs->size(); ++r) {
    const sdf::TaskGraph& g = (*graphs)[r];
    const sdf::TaskGraphAnalysis& analysis = analyses[r];
    const auto robot = std::find_if(l->tables.robots.begin(), l->tables.robots.end(), [&](const auto& t) { return t.name == g.robot; });
    ASSERT_NE(robot, l->tables.robots.end()) << g.robot;
    const runtime::DataflowTable& df = robot->dataflow;
    const runtime::TeamTable& team = l->tables.teams[robot->team];
    ASSERT_EQ(df.tasks.size(), g.tasks.size());
    EXPECT_EQ(df.tasks.front().kind, runtime::DataflowTask::Kind::Control);
    ASSERT_EQ(df.channels.size(), g.channels.size());
    for (std::size_t c = 0; c < g.channels.size(); ++c) {
      EXPECT_EQ(df.channels[c].capacity, analysis.capacities[c]) << g.robot << " " << g.channels[c].name;
      EXPECT_EQ(df.channels[c].from, g.channels[c].fromTask);
      EXPECT_EQ(df.channels[c].to, g.channels[c].toTask);
    }
    ASSERT_EQ(df.scenarios.size(), g.scenarios.size());
    for (std::size_t i = 0; i < g.scenarios.size(); ++i, ++scenarios) {
      const sdf::Scenario& s = g.scenarios[i];
      const sdf::ScenarioAnalysis& a = analysis.scenarios[i];
      const runtime::ScenarioTable& st = df.scenarios[i];
      const std::string where = g.robot + " " + s.name;
      EXPECT_EQ(st.name, s.name);
      ASSERT_TRUE(a.runnable()) << where;  // scouting is proven throughout (semo-verify sdf exits 0)
      // Minimality was not asked for, and says so rather than "refuted".
      EXPECT_EQ(a.bounds.maxThroughput.minimality, sdf::ProofStatus::Unknown) << where;
      EXPECT_TRUE(a.bounds.maxThroughput.channels.empty()) << where;
      EXPECT_FALSE(a.bounds.maxThroughput.minimalityNote.empty()) << where;
      EXPECT_TRUE(st.proven) << where;
      EXPECT_TRUE(st.notProven.empty()) << st.notProven;
      ASSERT_LT(st.modeIndex, team.modes.size()) << where;
      EXPECT_EQ(team.modes[st.modeIndex].name, s.mode);
      EXPECT_EQ(st.services, s.services);
      ASSERT_EQ(s.plans.size(), s.services.size());
      for (std::size_t k = 0; k < s.services.size(); ++k) EXPECT_EQ(st.planServices.at(s.plans[k]), s.services[k]) << where;

      // The schedule is the iteration run within the proven max-throughput capacities, task for actor.
      const sdf::Iteration it = sdf::runIteration(sdf::withCapacities(a.graph, a.bounds.maxThroughput.capacities), a.repetition.firings);
      ASSERT_TRUE(it.deadlockFree) << where;
      ASSERT_EQ(st.schedule.size(), it.schedule.size()) << where;
      std::vector<std::int64_t> fired(g.tasks.size(), 0);
      for (std::size_t k = 0; k < it.schedule.size(); ++k) {
        EXPECT_EQ(st.schedule[k].task, s.tasks[it.schedule[k].actor]) << where << " firing " << k;
        EXPECT_EQ(st.schedule[k].repetitions, it.schedule[k].times) << where << " firing " << k;
        fired[st.schedule[k].task] += st.schedule[k].repetitions;
      }
      for (std::size_t actor = 0; actor < s.tasks.size(); ++actor) EXPECT_EQ(fired[s.tasks[actor]], a.repetition.firings[actor]) << where;
      EXPECT_EQ(st.periodNum, a.bounds.maxThroughput.period.num);
      EXPECT_EQ(st.periodDen, a.bounds.maxThroughput.period.den);
      EXPECT_EQ(a.bounds.maxThroughput.period, a.unbounded.period) << where;  // the max-throughput bounds lose no throughput
      EXPECT_DOUBLE_EQ(st.period, a.bounds.maxThroughput.period.value() / 1e6);

      // Channels: the scenario's rates, the robot's capacity, at least the scenario's own bound.
      ASSERT_EQ(st.channels.size(), s.channels.size());
      for (std::size_t k = 0; k < s.channels.size(); ++k) {
        EXPECT_EQ(st.channels[k].channel, s.channels[k].channel);
        EXPECT_EQ(st.channels[k].production, s.channels[k].production);
        EXPECT_EQ(st.channels[k].consumption, s.channels[k].consumption);
        EXPECT_EQ(st.channels[k].initialTokens, s.channels[k].initialTokens);
        EXPECT_EQ(st.channels[k].capacity, analysis.capacities[s.channels[k].channel]);
        EXPECT_GE(st.channels[k].capacity, a.bounds.maxThroughput.capacities[k]) << where;
      }

      // Round trip: the runtime's schedule built from the table runs iteration after iteration within it.
      runtime::StaticSchedule schedule = runtime::StaticSchedule::forScenario(st);
      for (int n = 0; n < 3; ++n) {
        ASSERT_TRUE(schedule.runIteration([](runtime::Id) {})) << where << ": stalled at channel " << schedule.stalledChannel();
        EXPECT_TRUE(schedule.atInitialTokens()) << where;
      }
      for (runtime::Id k = 0; k < st.channels.size(); ++k) EXPECT_LE(schedule.maxTokens(k), st.channels[k].capacity) << where;
    }
  }
  EXPECT_GT(scenarios, 0u);
}

runtime::SimTrace simulate(Loaded& l, std::string* why = nullptr) {
  checker::ConformanceMonitor monitor(l.translation->model, l.tables);
  runtime::SimTrace trace = runtime::simulate(l.tables, *l.world, runtime::TaskLibrary::standard(), {}, &monitor);
  if (why != nullptr) *why = monitor.why();
  return trace;
}

// Swarm10 with its world and its dataflow projected (run for 60 s with the conformance monitor).
std::unique_ptr<Loaded> swarm10() {
  auto l = load("swarm", "swarm10");
  if (!l || !l->world) return nullptr;
  DiagnosticEngine diags(l->sources);
  std::optional<codegen::DataflowProjection> projected = codegen::projectDataflow(*l->mission, l->tables, diags);
  if (!projected) return nullptr;
  // Ten robots of one type: every scenario graph but the first robot's comes from the cache.
  EXPECT_EQ(projected->robots, 10u);
  EXPECT_EQ(projected->scenarios, 10 * l->tables.robots.front().dataflow.scenarios.size());
  EXPECT_EQ(projected->analysed, l->tables.robots.front().dataflow.scenarios.size());
  EXPECT_EQ(projected->notProven, 0u);
  return l;
}

TEST(DataflowSimulation, SwarmRunsItsSchedulesWithinTheProvenCapacities) {
  auto l = swarm10();
  ASSERT_TRUE(l);
  std::string why;
  const runtime::SimTrace trace = simulate(*l, &why);
  EXPECT_EQ(trace.summary.mismatches, 0u) << why;  // the dataflow changes nothing the model sees
  EXPECT_TRUE(trace.summary.violations.empty()) << trace.summary.violations.front();
  ASSERT_EQ(trace.summary.dataflow.size(), l->tables.robots.size());
  std::uint64_t iterations = 0, atCapacity = 0;
  for (std::size_t r = 0; r < trace.summary.dataflow.size(); ++r) {
    const runtime::DataflowRunSummary& d = trace.summary.dataflow[r];
    const runtime::DataflowTable& df = l->tables.robots[r].dataflow;
    std::uint64_t mine = 0;
    for (std::uint64_t n : d.iterations) mine += n;
    EXPECT_GT(mine, 0u) << l->tables.robots[r].name;
    iterations += mine;
    EXPECT_EQ(d.stalls, 0u);
    EXPECT_EQ(d.overflows, 0u);
    EXPECT_TRUE(d.notRun.empty());
    ASSERT_EQ(d.maxFill.size(), df.channels.size());
    for (std::size_t c = 0; c < df.channels.size(); ++c) {
      EXPECT_EQ(d.capacity[c], df.channels[c].capacity);
      EXPECT_LE(d.maxFill[c], df.channels[c].capacity) << l->tables.robots[r].name << " " << df.channels[c].name;
      atCapacity += df.channels[c].capacity > 0 && d.maxFill[c] == df.channels[c].capacity ? 1 : 0;
    }
  }
  EXPECT_GT(iterations, 0u);
  // The max-throughput capacities are the smallest with the full throughput: a schedule within them
  // fills some channel up to its bound.
  EXPECT_GT(atCapacity, 0u);
}

TEST(DataflowSimulation, OneTokenLessThanProvenIsAnOverflow) {
  auto l = swarm10();
  ASSERT_TRUE(l);
  const runtime::SimTrace proven = simulate(*l);
  // A channel of legged_0 that a scenario it ran filled to its capacity.
  const runtime::DataflowRunSummary& d = proven.summary.dataflow.at(0);
  runtime::DataflowTable& df = l->tables.robots[0].dataflow;
  runtime::Id shrunk = runtime::kNone;
  for (runtime::Id c = 0; c < df.channels.size() && shrunk == runtime::kNone; ++c) {
    if (df.channels[c].capacity > 1 && d.maxFill[c] == df.channels[c].capacity) shrunk = c;
  }
  ASSERT_NE(shrunk, runtime::kNone);
  --df.channels[shrunk].capacity;
  for (runtime::ScenarioTable& s : df.scenarios) {
    for (runtime::ScenarioTable::Channel& c : s.channels) c.capacity = df.channels[c.channel].capacity;
  }
  const runtime::SimTrace trace = simulate(*l);
  const runtime::DataflowRunSummary& after = trace.summary.dataflow.at(0);
  EXPECT_GE(after.overflows, 1u);
  // A scenario stops at its first overflow: one report per scenario at most, not one per period.
  EXPECT_LE(after.overflows + after.stalls, df.scenarios.size());
  ASSERT_FALSE(trace.summary.violations.empty());
  EXPECT_NE(trace.summary.violations.front().find("dataflow overflow of legged_0"), std::string::npos) << trace.summary.violations.front();
  EXPECT_NE(trace.summary.violations.front().find(df.channels[shrunk].name), std::string::npos) << trace.summary.violations.front();
  const bool recorded = std::any_of(trace.events.begin(), trace.events.end(), [](const runtime::TraceEvent& e) {
    return e.kind == runtime::TraceEvent::Kind::Violation && e.robot == 0 && e.label.find("dataflow overflow") != std::string::npos;
  });
  EXPECT_TRUE(recorded);
  // The other robots' capacities were left alone: they still run clean.
  for (std::size_t r = 1; r < trace.summary.dataflow.size(); ++r) EXPECT_EQ(trace.summary.dataflow[r].overflows, 0u);
}

}  // namespace
}  // namespace semo
