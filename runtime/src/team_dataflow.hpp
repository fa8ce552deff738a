#pragma once
// The robots' dataflow inside the simulator (specs/runtime.md, "Dataflow"): per robot a
// DataflowRunner over its projected task graph, and what the simulator needs to pick, at each
// control period, the scenario the robot's plans are in. Everything is built with the team, before
// the first event; Team::stepDataflow (team_dataflow.cpp) then allocates nothing but the trace's
// lines for a stall, which the capacity proof rules out.
#include <vector>

#include "semo/runtime/dataflow.hpp"
#include "semo/runtime/sim_trace.hpp"
#include "semo/runtime/tables.hpp"

namespace semo::runtime::detail {

struct TeamDataflow {
  // Sizes `summary.dataflow` (one entry per robot) when any robot has a projected task graph.
  TeamDataflow(const MissionTables& tables, TraceSummary& summary);

  bool any = false;                           // some robot has a projected task graph
  std::vector<DataflowRunner> runners;        // per robot
  std::vector<std::vector<std::vector<Id>>> byMode;  // per robot, per mode of its team: its scenarios, in the table's order
  // Per robot, [scenario * plans + plan]: the service the plan runs in that scenario (an index into
  // the service names seen; kNone: the plan calls none there).
  std::vector<std::vector<Id>> planService;
  std::vector<Id> callService;                // per call (MissionTables::calls): its service, same indices
};

}  // namespace semo::runtime::detail
