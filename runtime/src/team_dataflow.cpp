// The robots' dataflow in the simulator (specs/runtime.md, "Dataflow"). At every control period,
// for each live robot: the scenario its plans are in (its mode, and the services of the calls under
// way) is selected, and the iterations of that scenario's static schedule that start within the
// period run over channels of the proven capacities. Per control period rather than per scenario
// period: the calls a scenario stands for are themselves stepped once per control period, so that
// is as finely as the simulator knows which scenario runs; the number of iterations still follows
// the scenario's own period exactly (DataflowRunner::advance).
#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "team.hpp"

namespace semo::runtime::detail {

TeamDataflow::TeamDataflow(const MissionTables& tables, TraceSummary& summary) {
  for (const RobotTable& r : tables.robots) any = any || !r.dataflow.tasks.empty();
  if (!any) return;
  std::map<std::string, Id, std::less<>> serviceIds;
  const auto serviceId = [&](const std::string& name) {
    return serviceIds.try_emplace(name, static_cast<Id>(serviceIds.size())).first->second;
  };
  for (const CallTable& call : tables.calls) callService.push_back(serviceId(call.service));
  runners.reserve(tables.robots.size());
  summary.dataflow.resize(tables.robots.size());
  for (Id robot = 0; robot < tables.robots.size(); ++robot) {
    const RobotTable& r = tables.robots[robot];
    const DataflowTable& df = r.dataflow;
    runners.emplace_back(df);
    const std::size_t plans = r.plans.size();
    byMode.emplace_back(tables.teams[r.team].modes.size());
    planService.emplace_back(df.scenarios.size() * plans, kNone);
    DataflowRunSummary& sum = summary.dataflow[robot];
    for (Id s = 0; s < df.scenarios.size(); ++s) {
      const ScenarioTable& sc = df.scenarios[s];
      if (sc.modeIndex < byMode.back().size()) byMode.back()[sc.modeIndex].push_back(s);
      for (std::size_t p = 0; p < plans && p < sc.planServices.size(); ++p) {
        if (!sc.planServices[p].empty()) planService.back()[s * plans + p] = serviceId(sc.planServices[p]);
      }
      sum.scenarios.push_back(sc.name);
      if (!runners.back().runnable(s)) sum.notRun.push_back(sc.name + ": " + (sc.notProven.empty() ? "no schedule or period" : sc.notProven));
    }
    sum.iterations.assign(df.scenarios.size(), 0);
    for (const DataflowChannel& c : df.channels) {
      sum.channels.push_back(c.name);
      sum.capacity.push_back(c.capacity);
    }
    sum.maxFill.assign(df.channels.size(), 0);
  }
}

namespace {

// The robot's scenario now: the first of its mode whose services agree with every call under way
// (a plan between two calls agrees with any). With no call under way only a scenario that names no
// service runs (a mode whose plans call nothing still senses and communicates).
Id scenarioNow(const TeamDataflow& df, Id robot, const RobotRun& r) {
  if (robot >= df.byMode.size() || r.mode >= df.byMode[robot].size()) return kNone;
  const std::size_t plans = r.plans.size();
  const std::vector<Id>& services = df.planService[robot];
  for (Id s : df.byMode[robot][r.mode]) {
    bool agrees = true, calling = false, namesAny = false;
    for (std::size_t p = 0; p < plans && agrees; ++p) {
      const PlanRun& plan = r.plans[p];
      const Id expected = services[s * plans + p];
      namesAny = namesAny || expected != kNone;
      if (!plan.behaviour || plan.behaviourCall == kNone) continue;
      calling = true;
      agrees = df.callService[plan.behaviourCall] == expected;
    }
    if (agrees && (calling || !namesAny)) return s;
  }
  return kNone;
}

}  // namespace

void Team::stepDataflow() {
  if (!dataflow_.any) return;
  const Micros period = toMicros(options_.controlPeriod);
  for (Id robot = 0; robot < robots_.size(); ++robot) {
    if (!local(robot)) continue;  // a networked robot runs its own task graph only
    DataflowRunner& runner = dataflow_.runners[robot];
    const Id s = robots_[robot].alive ? scenarioNow(dataflow_, robot, robots_[robot]) : kNone;
    runner.select(s);
    if (s == kNone) continue;
    const DataflowRunner::Advance done = runner.advance(period);
    DataflowRunSummary& sum = trace_.summary.dataflow[robot];
    const ScenarioTable& scenario = t_.robots[robot].dataflow.scenarios[s];
    sum.iterations[s] = runner.iterations(s);
    for (Id k = 0; k < scenario.channels.size(); ++k) {
      std::int64_t& fill = sum.maxFill[scenario.channels[k].channel];
      fill = std::max(fill, runner.schedule(s).maxTokens(k));
    }
    if (done.stall == StaticSchedule::Stall::None) continue;
    // Impossible by the capacity proof: a bug of the analysis or of the runtime, or tables changed
    // after the projection. The scenario stops; the rest of the team goes on.
    const bool overflow = done.stall == StaticSchedule::Stall::Overflow;
    ++(overflow ? sum.overflows : sum.stalls);
    const DataflowTable& df = t_.robots[robot].dataflow;
    const std::string task = done.task < df.tasks.size() ? df.tasks[done.task].name : "?";
    const std::string channel = done.channel < df.channels.size() ? df.channels[done.channel].name : "?";
    const std::int64_t capacity = done.channel < df.channels.size() ? df.channels[done.channel].capacity : 0;
    const std::string why = overflow ? fmt::format("task {} found no room on channel {} (capacity {})", task, channel, capacity)
                                     : fmt::format("task {} found too few tokens on channel {}", task, channel);
    const std::string what = fmt::format("dataflow {} of {} in scenario {} after {} iterations: {} (impossible by the capacity proof)",
                                         overflow ? "overflow" : "stall", t_.robots[robot].name, scenario.name, runner.iterations(s), why);
    note(robot, TraceEvent::Kind::Violation, what);
    trace_.summary.violations.push_back(what);
  }
}

}  // namespace semo::runtime::detail
