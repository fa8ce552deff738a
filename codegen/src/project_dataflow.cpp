// The dataflow half of the projection (project_dataflow.hpp): task graphs and their analyses
// written into each robot's DataflowTable. Nothing is derived here: tasks, channels and scenarios
// are the task graph's, schedules, periods and capacities the analysis', indices translated from
// the per-scenario SDF graph (actors = the scenario's active tasks, in order) back to the robot's
// task graph.
#include "semo/codegen/project_dataflow.hpp"

#include <algorithm>

namespace semo::codegen {

namespace {

using runtime::DataflowTask;

DataflowTask::Kind taskKind(sdf::TaskKind k) {
  switch (k) {
    case sdf::TaskKind::Service: return DataflowTask::Kind::Service;
    case sdf::TaskKind::Sensing: return DataflowTask::Kind::Sensing;
    case sdf::TaskKind::Control: return DataflowTask::Kind::Control;
    case sdf::TaskKind::Communication: return DataflowTask::Kind::Communication;
    case sdf::TaskKind::Knowledge: return DataflowTask::Kind::Knowledge;
    case sdf::TaskKind::LeaderElection: return DataflowTask::Kind::LeaderElection;
  }
  return DataflowTask::Kind::Service;
}

// Why a scenario cannot run, in the words `semo-verify sdf` uses (empty when it can).
std::string notProvenReason(const sdf::ScenarioAnalysis& a) {
  if (a.runnable()) return {};
  if (!a.repetition.consistent()) return "inconsistent: " + a.repetition.error;
  if (!a.iteration.error.empty()) return "deadlock freedom unknown: " + a.iteration.error;
  if (!a.iteration.deadlockFree) return "an iteration deadlocks";
  if (!a.unbounded.error.empty()) return "period not computed: " + a.unbounded.error;
  if (!a.bounds.haveBounds) return "no buffer bounds: " + a.bounds.error;
  const sdf::ChosenBounds& b = a.bounds.maxThroughput;
  std::string out = std::string("max-throughput bounds: no overflow/underflow ") + sdf::proofStatusName(b.safety);
  return b.safetyNote.empty() ? out : out + " (" + b.safetyNote + ")";
}

}  // namespace

runtime::DataflowTable dataflowTable(const sdf::TaskGraph& graph, const sdf::TaskGraphAnalysis& analysis, const runtime::TeamTable& team) {
  runtime::DataflowTable out;
  for (const sdf::Task& t : graph.tasks) out.tasks.push_back({t.name, taskKind(t.kind), t.origins, t.execMicros});
  for (std::size_t c = 0; c < graph.channels.size(); ++c) {
    const sdf::TaskChannel& ch = graph.channels[c];
    out.channels.push_back({ch.name, ch.fromTask, ch.toTask, ch.control, c < analysis.capacities.size() ? analysis.capacities[c] : 0});
  }
  for (std::size_t i = 0; i < graph.scenarios.size() && i < analysis.scenarios.size(); ++i) {
    const sdf::Scenario& s = graph.scenarios[i];
    const sdf::ScenarioAnalysis& a = analysis.scenarios[i];
    runtime::ScenarioTable st;
    st.name = s.name;
    st.mode = s.mode;
    for (std::size_t m = 0; m < team.modes.size(); ++m) {
      if (team.modes[m].name == s.mode) st.modeIndex = static_cast<runtime::Id>(m);
    }
    st.services = s.services;
    st.planServices.assign(team.plans.size(), std::string());
    for (std::size_t k = 0; k < s.services.size() && k < s.plans.size(); ++k) {
      if (s.plans[k] < st.planServices.size()) st.planServices[s.plans[k]] = s.services[k];
    }
    for (const sdf::ScenarioChannel& sc : s.channels) {
      const sdf::TaskChannel& ch = graph.channels[sc.channel];
      st.channels.push_back(
          {sc.channel, ch.fromTask, ch.toTask, sc.production, sc.consumption, sc.initialTokens, out.channels[sc.channel].capacity});
    }
    // The schedule and period proven within the max-throughput bounds: the robot's capacities are
    // at least those bounds on every channel of the scenario, so the same schedule stays within them
    // (and an SDF graph never runs slower with more room). The iteration found with unbounded
    // channels (ScenarioAnalysis::iteration) may need more room than that and is not used.
    if (a.bounds.haveBounds) {
      const sdf::ChosenBounds& b = a.bounds.maxThroughput;
      for (const sdf::FiringRun& run : b.schedule) {
        if (run.actor < s.tasks.size()) st.schedule.push_back({s.tasks[run.actor], run.times});
      }
      st.periodNum = b.period.num;
      st.periodDen = b.period.den;
      st.period = b.period.value() / 1e6;
    }
    st.proven = a.runnable();
    st.notProven = notProvenReason(a);
    out.scenarios.push_back(std::move(st));
  }
  for (const sdf::RemotePort& r : graph.remotePorts) {
    out.remotePorts.push_back({static_cast<std::uint32_t>(r.task), r.port, r.output, r.kind == sdf::RemotePort::Kind::Multicast, r.id, r.buffer, r.peers});
  }
  return out;
}

std::optional<DataflowProjection> projectDataflow(const model::MissionModel& mission, runtime::MissionTables& tables, DiagnosticEngine& diags,
                                                  const sdf::BoundsOptions& options, sdf::ScenarioCache* cache) {
  std::optional<std::vector<sdf::TaskGraph>> graphs = sdf::generateTaskGraphs(mission, diags);
  if (!graphs) return std::nullopt;
  sdf::ScenarioCache local;
  sdf::ScenarioCache& shared = cache != nullptr ? *cache : local;
  const std::size_t hitsBefore = shared.hits();
  DataflowProjection out;
  for (const sdf::TaskGraph& g : *graphs) {
    auto robot =
        std::find_if(tables.robots.begin(), tables.robots.end(), [&](const runtime::RobotTable& r) { return r.name == g.robot; });
    if (robot == tables.robots.end()) continue;  // not a robot of these tables: nothing to run it on
    const sdf::TaskGraphAnalysis analysis = sdf::analyseTaskGraph(g, options, &shared);
    robot->dataflow = dataflowTable(g, analysis, tables.teams[robot->team]);
    ++out.robots;
    out.scenarios += analysis.scenarios.size();
    out.notProven += static_cast<std::size_t>(std::count_if(analysis.scenarios.begin(), analysis.scenarios.end(),
                                                            [](const sdf::ScenarioAnalysis& a) { return !a.runnable(); }));
  }
  out.analysed = out.scenarios - (shared.hits() - hitsBefore);
  return out;
}

}  // namespace semo::codegen
