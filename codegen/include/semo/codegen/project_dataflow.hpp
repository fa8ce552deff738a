#pragma once
// The dataflow half of the projection (specs/runtime.md, "Dataflow"): each robot's task graph
// (sdf::generateTaskGraphs) and its analysis (sdf::analyseTaskGraph: per scenario the static
// schedule, the period and the proven capacities) written into RobotTable::dataflow, plain data the
// runtime runs without any analysis of its own. Apart from codegen::project because it is slow
// where the rest is instant (Z3 proves each schedule safe within its capacities: a few tenths of a
// second for a mission), so only those who run the dataflow pay for it.
#include <cstddef>
#include <optional>

#include "semo/frontend/diagnostics.hpp"
#include "semo/runtime/tables.hpp"
#include "semo/sdf/task_graph_analysis.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo::codegen {

struct DataflowProjection {
  std::size_t robots = 0;
  std::size_t scenarios = 0;  // over every robot
  std::size_t notProven = 0;  // of those, schedule not proven safe (the runtime will not run them)
  std::size_t analysed = 0;   // scenario graphs analysed; the rest came from the cache (identical robots)
};

// The analysis' options for what runs: safety proofs, no minimality proofs.
inline sdf::BoundsOptions runningBounds() {
  sdf::BoundsOptions o;
  o.proveMinimality = false;
  return o;
}

// One robot's dataflow table from its task graph and that graph's analysis. `team` gives the modes
// and plans a scenario's mode and services are resolved against.
runtime::DataflowTable dataflowTable(const sdf::TaskGraph& graph, const sdf::TaskGraphAnalysis& analysis, const runtime::TeamTable& team);

// Every robot's RobotTable::dataflow (`tables` projected from `mission` by codegen::project).
// Scenario graphs already in `cache` are not analysed again; without one a cache local to the call
// still analyses identical robots once. nullopt when the task graphs cannot be generated (the
// errors are in `diags`); the tables are then left as they were.
// The analysis proves by default only what running needs, the schedules' safety
// (sdf::BoundsOptions::proveMinimality false): a tenth of the time of the full analysis.
std::optional<DataflowProjection> projectDataflow(const model::MissionModel& mission, runtime::MissionTables& tables,
                                                  DiagnosticEngine& diags, const sdf::BoundsOptions& options = runningBounds(),
                                                  sdf::ScenarioCache* cache = nullptr);

}  // namespace semo::codegen
