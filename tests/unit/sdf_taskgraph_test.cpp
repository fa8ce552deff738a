// Task-graph generation from small missions whose graphs, rates and buffer bounds can be worked out
// by hand; the Z3 bound proofs on hand graphs; the JSON form read back.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "semo/sdf/bounds.hpp"
#include "semo/sdf/task_graph.hpp"
#include "semo/sdf/task_graph_analysis.hpp"
#include "semo/sdf/task_graph_io.hpp"
#include "semo/semantics/load.hpp"

namespace semo::sdf {
namespace {

// drive: planner (goal in, cmd out 2 per firing, 5 ms) -> motor (cmd in 1, tacho out 1, 1 ms);
// beep: tone (freq in) -> motor.cmd as well; sense T.dist: ranger (dist out, 1 ms).
const char* kStrategy = R"(<?xml version="1.0"?>
<strategy version="1">
  <robot urdf="ROBOTS/ev3_robot.urdf" type="Ev3Robot"/>
  <service name="drive" kind="primitive">
    <implementation robot="Ev3Robot">
      <task name="planner" exec="5 MSEC">
        <port name="goal" dir="in" rate="1"/>
        <port name="cmd" dir="out" rate="2"/>
      </task>
      <task name="motor" exec="1 MSEC">
        <port name="cmd" dir="in" rate="1"/>
        <port name="tacho" dir="out" rate="1"/>
      </task>
      <channel from="planner.cmd" to="motor.cmd"/>
    </implementation>
  </service>
  <service name="beep" kind="primitive">
    <implementation robot="Ev3Robot">
      <task name="tone" exec="2 MSEC">
        <port name="freq" dir="in" rate="1"/>
        <port name="cmd" dir="out" rate="1"/>
      </task>
      <task name="motor" exec="1 MSEC">
        <port name="cmd" dir="in" rate="1"/>
        <port name="tacho" dir="out" rate="1"/>
      </task>
      <channel from="tone.cmd" to="motor.cmd"/>
    </implementation>
  </service>
  <service name="log" kind="primitive">
    <implementation robot="Ev3Robot">
      <task name="motor" exec="1 MSEC">
        <port name="cmd" dir="in" rate="1"/>
        <port name="tacho" dir="out" rate="1"/>
      </task>
      <task name="logger" exec="1 MSEC"><port name="tacho" dir="in" rate="1"/></task>
      <channel from="motor.tacho" to="logger.tacho"/>
    </implementation>
  </service>
  <value name="T.dist">
    <domain kind="threshold" thresholds="10"/>
    <implementation robot="Ev3Robot">
      <task name="ranger" exec="1 MSEC"><port name="dist" dir="out" rate="1"/></task>
    </implementation>
  </value>
</strategy>
)";

struct Generated {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<std::vector<TaskGraph>> graphs;
};

std::unique_ptr<Generated> generate(const std::string& mission, const std::string& name) {
  auto out = std::make_unique<Generated>();
  const std::string dir = testing::TempDir();
  std::string strategy = kStrategy;
  strategy.replace(strategy.find("ROBOTS"), 6, SEMO_SOURCE_DIR "/specs/robots");
  std::ofstream(dir + "/" + name + ".xml") << strategy;
  std::ofstream(dir + "/" + name + ".semo") << mission;
  auto m = loadMission({dir + "/" + name + ".semo", dir + "/" + name + ".xml", std::nullopt}, out->sources, out->diags);
  if (m) out->graphs = generateTaskGraphs(*m, out->diags);
  return out;
}

std::vector<std::string> names(const TaskGraph& g, const std::vector<std::uint32_t>& tasks) {
  std::vector<std::string> out;
  for (std::uint32_t t : tasks) out.push_back(g.tasks[t].name);
  return out;
}

const ScenarioChannel& channelNamed(const TaskGraph& g, const Scenario& s, const std::string& name) {
  for (const ScenarioChannel& c : s.channels) {
    if (g.channels[c.channel].name == name) return c;
  }
  throw std::runtime_error("no channel " + name);
}

TEST(SdfTaskGraph, OneGraphPerRobotWithServiceSensingControlAndEventTasks) {
  auto g = generate(R"(
T: Ev3Robot e[2]
T.Act.Go { drive("there") beep() }
T.Watch.Look { loop(1 SEC) if (T.dist < 10) throw near }
T.Act.Stay { beep() }
T.M1 { set(Act, Go) set(Watch, Look) }
T.M2 { set(Act, Stay) }
T.main {
  case (M1): catch(near): mode = M2
  case (M2): default: mode = M1 }
)", "structure");
  ASSERT_TRUE(g->graphs) << (g->diags.diagnostics().empty() ? "" : g->diags.format(g->diags.diagnostics().front()));
  ASSERT_EQ(g->graphs->size(), 2u);
  const TaskGraph& tg = g->graphs->front();
  EXPECT_EQ(tg.robot, "e_0");
  std::vector<std::string> all;
  for (const Task& t : tg.tasks) all.push_back(t.name + ":" + taskKindName(t.kind));
  EXPECT_EQ(all, (std::vector<std::string>{"control:control", "ranger:sensing", "event_out:communication", "event_in:communication",
                                           "planner:service", "motor:service", "tone:service"}));
  // motor serves both services: one task, two origins.
  EXPECT_EQ(tg.tasks[5].origins, (std::vector<std::string>{"drive", "beep"}));
  // Go calls drive then beep in one plan: two scenarios of M1, never both at once (both feed motor.cmd).
  ASSERT_EQ(tg.scenarios.size(), 3u);
  EXPECT_EQ(tg.scenarios[0].name, "M1[drive]");
  EXPECT_EQ(tg.scenarios[1].name, "M1[beep]");
  EXPECT_EQ(tg.scenarios[2].name, "M2");
  EXPECT_EQ(names(tg, tg.scenarios[0].tasks), (std::vector<std::string>{"control", "ranger", "event_out", "event_in", "planner", "motor"}));
  EXPECT_EQ(names(tg, tg.scenarios[2].tasks), (std::vector<std::string>{"control", "motor", "tone"}));  // M2 throws and catches nothing
  // The control task's rates: one iteration's worth per firing (motor fires twice per planner firing).
  const Scenario& drive = tg.scenarios[0];
  const ScenarioChannel& tacho = channelNamed(tg, drive, "motor.tacho->control.motor.tacho");
  EXPECT_EQ(tacho.production, 1);
  EXPECT_EQ(tacho.consumption, 2);
  const ScenarioChannel& goal = channelNamed(tg, drive, "control.planner.goal->planner.goal");
  EXPECT_EQ(goal.production, 1);
  EXPECT_EQ(goal.initialTokens, 1);  // the first command is there when the scenario starts
  EXPECT_EQ(channelNamed(tg, drive, "planner.cmd->motor.cmd").production, 2);
  // Events are multicast to the other robot of the team.
  ASSERT_EQ(tg.remotePorts.size(), 2u);
  EXPECT_EQ(tg.remotePorts[0].id, "events:T");
  EXPECT_EQ(tg.remotePorts[0].peers, (std::vector<std::string>{"e_1"}));
}

TEST(SdfTaskGraph, TwoPlansFeedingOnePortAtOnceAreAnError) {
  auto g = generate(R"(
T: Ev3Robot e[1]
T.Act.Go { drive("there") }
T.Noise.Buzz { beep() }
T.M1 { set(Act, Go) set(Noise, Buzz) }
T.main { case (M1): default: mode = M1 }
)", "conflict");
  EXPECT_FALSE(g->graphs.has_value());
  ASSERT_EQ(g->diags.errorCount(), 1u);
  const Diagnostic& d = g->diags.diagnostics().front();
  EXPECT_NE(d.message.find("would feed input port 'motor.cmd' from two tasks at once ('planner' and 'tone')"), std::string::npos) << d.message;
  EXPECT_EQ(d.range.begin.line, 5u);  // the mode
}

// drive leaves motor.tacho to the control task and takes motor.cmd from its planner; log connects
// motor.tacho to its logger and leaves motor.cmd to the control task. Together: the planner alone
// feeds motor.cmd, and motor.tacho fans out to the control task and the logger.
TEST(SdfTaskGraph, ConnectedInputsWinAndOutputsFanOut) {
  auto g = generate(R"(
T: Ev3Robot e[1]
T.Act.Go { drive("there") }
T.Rec.Log { log() }
T.M1 { set(Act, Go) set(Rec, Log) }
T.main { case (M1): default: mode = M1 }
)", "fanout");
  ASSERT_TRUE(g->graphs);
  const TaskGraph& tg = g->graphs->front();
  ASSERT_EQ(tg.scenarios.size(), 1u);
  std::vector<std::string> active;
  for (const ScenarioChannel& c : tg.scenarios[0].channels) active.push_back(tg.channels[c.channel].name);
  std::sort(active.begin(), active.end());
  EXPECT_EQ(active, (std::vector<std::string>{"control.planner.goal->planner.goal", "motor.tacho->control.motor.tacho",
                                              "motor.tacho->logger.tacho", "planner.cmd->motor.cmd"}));
  EXPECT_TRUE(analyseTaskGraph(tg).scenarios[0].sound());
}

// One Ev3 in one mode running drive (the next two tests).
constexpr const char* kOneDrive = R"(
T: Ev3Robot e[1]
T.Act.Go { drive("there") }
T.M1 { set(Act, Go) }
T.main { case (M1): default: mode = M1 }
)";

// One mode running drive: control -> planner (5 ms) -> 2x motor (1 ms) -> control (1 ms), a single
// cycle with one command token: period 5 + 1 + 1 + 1 = 8 ms. Smallest capacities: goal 1 (its one
// token), cmd 2 (p + c - gcd), tacho 2; with them nothing waits longer, so total 5 is both the
// deadlock-free and the maximal-throughput choice, and one token less on any channel deadlocks.
TEST(SdfTaskGraph, HandComputedRepetitionPeriodAndProvenBounds) {
  auto g = generate(kOneDrive, "bounds");
  ASSERT_TRUE(g->graphs);
  const TaskGraph& tg = g->graphs->front();
  ASSERT_EQ(tg.scenarios.size(), 1u);
  const TaskGraphAnalysis a = analyseTaskGraph(tg);
  ASSERT_EQ(a.scenarios.size(), 1u);
  const ScenarioAnalysis& s = a.scenarios[0];
  ASSERT_TRUE(s.repetition.consistent());
  EXPECT_EQ(s.repetition.firings, (std::vector<std::int64_t>{1, 1, 2}));  // control, planner, motor
  EXPECT_TRUE(s.iteration.deadlockFree);
  EXPECT_EQ(s.unbounded.period, (Period{8000, 1}));
  ASSERT_TRUE(s.bounds.haveBounds);
  EXPECT_EQ(s.bounds.deadlockFree.total, 5);
  EXPECT_EQ(s.bounds.maxThroughput.total, 5);
  EXPECT_EQ(s.bounds.maxThroughput.period, (Period{8000, 1}));
  EXPECT_EQ(s.bounds.maxThroughput.safety, ProofStatus::Proven);
  EXPECT_EQ(s.bounds.maxThroughput.minimality, ProofStatus::Proven);
  for (const ChannelMinimality& m : s.bounds.maxThroughput.channels) EXPECT_EQ(m.outcome, ChannelMinimality::Outcome::Deadlocks);
  EXPECT_TRUE(s.sound());
  std::vector<std::int64_t> caps;
  for (std::size_t c = 0; c < tg.channels.size(); ++c) caps.push_back(a.capacities[c]);
  EXPECT_EQ(caps, (std::vector<std::int64_t>{2, 1, 2}));  // cmd, goal, tacho in the graph's order
}

// Safety only (what the simulator asks for): the same capacities, schedule and period, the safety
// proven, the minimality left Unknown with a note; runnable() but not sound().
TEST(SdfTaskGraph, SafetyOnlyKeepsTheBoundsAndLeavesMinimalityOut) {
  auto g = generate(kOneDrive, "bounds");
  ASSERT_TRUE(g->graphs);
  const TaskGraph& tg = g->graphs->front();
  BoundsOptions safetyOnly;
  safetyOnly.proveMinimality = false;
  const TaskGraphAnalysis full = analyseTaskGraph(tg);
  const TaskGraphAnalysis quick = analyseTaskGraph(tg, safetyOnly);
  ASSERT_EQ(quick.scenarios.size(), 1u);
  const ChosenBounds& f = full.scenarios[0].bounds.maxThroughput;
  const ChosenBounds& q = quick.scenarios[0].bounds.maxThroughput;
  EXPECT_EQ(quick.capacities, full.capacities);
  EXPECT_EQ(q.capacities, f.capacities);
  EXPECT_EQ(q.period, f.period);
  ASSERT_EQ(q.schedule.size(), f.schedule.size());
  for (std::size_t i = 0; i < q.schedule.size(); ++i) {
    EXPECT_EQ(q.schedule[i].actor, f.schedule[i].actor);
    EXPECT_EQ(q.schedule[i].times, f.schedule[i].times);
  }
  EXPECT_EQ(q.safety, ProofStatus::Proven);
  EXPECT_EQ(q.minimality, ProofStatus::Unknown);
  EXPECT_TRUE(q.channels.empty());
  EXPECT_NE(q.minimalityNote.find("not asked for"), std::string::npos);
  EXPECT_TRUE(quick.scenarios[0].runnable());
  EXPECT_FALSE(quick.scenarios[0].sound());
  EXPECT_TRUE(full.scenarios[0].runnable());
  EXPECT_TRUE(full.scenarios[0].sound());
}

// a -> b, 2 produced and 3 consumed per firing: q = (3, 2); a channel of 4 (2 + 3 - 1) runs an
// iteration (a a b a b), one of 3 cannot (after a a it holds 4 > 3, after a 2 < 3).
Graph chain() {
  Graph g;
  g.actors = {{"a", 1, {}}, {"b", 1, {}}};
  g.channels = {{"ab", 0, 1, 2, 3, 0, {}}};
  return g;
}

TEST(SdfBoundsProof, Z3DecidesWhetherAnIterationFitsTheCapacities) {
  const Graph g = chain();
  EXPECT_EQ(proveIterationImpossible(g, {3, 2}, {4}, 10'000), ProofStatus::Refuted);
  EXPECT_EQ(proveIterationImpossible(g, {3, 2}, {3}, 10'000), ProofStatus::Proven);
  EXPECT_EQ(proveIterationImpossible(g, {3, 2}, {1}, 10'000), ProofStatus::Proven);
}

TEST(SdfBoundsProof, Z3ChecksAScheduleForAnyNumberOfIterations) {
  const Graph g = chain();
  const std::vector<FiringRun> good{{0, 2}, {1, 1}, {0, 1}, {1, 1}};
  EXPECT_EQ(proveScheduleSafe(g, {4}, good, 10'000), ProofStatus::Proven);
  EXPECT_EQ(proveScheduleSafe(g, {3}, good, 10'000), ProofStatus::Refuted);  // a a: 4 tokens
  const std::vector<FiringRun> starving{{0, 1}, {1, 1}, {0, 2}, {1, 1}};
  EXPECT_EQ(proveScheduleSafe(g, {10}, starving, 10'000), ProofStatus::Refuted);  // b takes 3 of 2
  // Unbalanced: one extra a per iteration fills any capacity after enough iterations.
  const std::vector<FiringRun> unbalanced{{0, 2}, {1, 1}, {0, 2}, {1, 1}};
  std::string note;
  EXPECT_EQ(proveScheduleSafe(g, {100}, unbalanced, 10'000, &note), ProofStatus::Refuted);
  EXPECT_NE(note.find("iterations"), std::string::npos);
}

TEST(SdfBoundsProof, CapacitiesAsReverseChannels) {
  const Graph bounded = withCapacities(chain(), {5});
  ASSERT_EQ(bounded.channels.size(), 2u);
  EXPECT_EQ(bounded.channels[1].source, 1u);
  EXPECT_EQ(bounded.channels[1].production, 3);   // b frees what it consumed
  EXPECT_EQ(bounded.channels[1].consumption, 2);  // a claims what it produces
  EXPECT_EQ(bounded.channels[1].initialTokens, 5);
}

TEST(SdfTaskGraph, TheJsonFormReadsBackToTheSameGraph) {
  auto g = generate(R"(
T: Ev3Robot e[2]
T.Act.Go { drive("there") beep() }
T.Watch.Look { loop(1 SEC) if (T.dist < 10) throw near }
T.M1 { set(Act, Go) set(Watch, Look) }
T.main { case (M1): catch(near): mode = M1 }
)", "json");
  ASSERT_TRUE(g->graphs);
  const TaskGraph& tg = g->graphs->front();
  const std::string text = taskGraphToJson(tg);
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const FileId file = sources.add("g.json", text);
  std::optional<TaskGraph> back = readTaskGraphJson(sources, file, diags);
  ASSERT_TRUE(back) << (diags.diagnostics().empty() ? "" : diags.format(diags.diagnostics().front()));
  EXPECT_EQ(taskGraphToJson(*back), text);
  ASSERT_EQ(back->scenarios.size(), tg.scenarios.size());
  for (std::size_t s = 0; s < tg.scenarios.size(); ++s) {
    const Graph a = scenarioGraph(tg, tg.scenarios[s]), b = scenarioGraph(*back, back->scenarios[s]);
    EXPECT_EQ(repetitionVector(a).firings, repetitionVector(b).firings);
    ASSERT_EQ(a.channels.size(), b.channels.size());
    for (std::size_t c = 0; c < a.channels.size(); ++c) {
      EXPECT_EQ(a.channels[c].name, b.channels[c].name);
      EXPECT_EQ(a.channels[c].production, b.channels[c].production);
      EXPECT_EQ(a.channels[c].initialTokens, b.channels[c].initialTokens);
    }
  }
}

}  // namespace
}  // namespace semo::sdf
