#pragma once
// A projected task graph built by hand for the runtime's dataflow tests: a control task feeding a
// producer A that a consumer B drains at another rate, B reporting back to the control task.
//
//   control -2-> A -3-> B -1-> control   (per firing: A consumes 1 command, produces 3; B consumes 2,
//            (c0)   (c1)   (c2)           produces 1 status; the control task takes 3 statuses)
//
// Repetitions per iteration: A 2, B 3, control 1. The schedule A B A B B control needs 2 tokens on
// c0 (its initial commands), 4 on c1 (3, then 1 + 3) and 3 on c2: the capacities a proof would give.
#include "semo/runtime/dataflow_tables.hpp"

namespace semo::runtime::sample {

inline ScenarioTable chainScenario(std::string name, std::int64_t periodNum, std::int64_t periodDen) {
  ScenarioTable s;
  s.name = std::move(name);
  s.mode = "RUN";
  s.modeIndex = 0;
  s.services = {"work"};
  s.planServices = {"work"};
  s.schedule = {{1, 1}, {2, 1}, {1, 1}, {2, 2}, {0, 1}};
  s.channels = {{0, 0, 1, 2, 1, 2, 2}, {1, 1, 2, 3, 2, 0, 4}, {2, 2, 0, 1, 3, 0, 3}};
  s.periodNum = periodNum;
  s.periodDen = periodDen;
  s.period = static_cast<double>(periodNum) / static_cast<double>(periodDen) / 1e6;
  s.proven = true;
  return s;
}

// Scenario 0: period 10/3 ms; 1: period 7 ms; 2: like 0 but not proven (never run).
inline DataflowTable chainTable() {
  DataflowTable t;
  t.tasks = {{"control", DataflowTask::Kind::Control, {"modes of Team"}, 1000},
             {"A", DataflowTask::Kind::Service, {"work"}, 1000},
             {"B", DataflowTask::Kind::Service, {"work"}, 500}};
  t.channels = {{"control.A.in->A.in", 0, 1, true, 2}, {"A.out->B.in", 1, 2, false, 4}, {"B.out->control.B.out", 2, 0, true, 3}};
  t.scenarios = {chainScenario("RUN", 10000, 3), chainScenario("RUN[slow]", 7000, 1), chainScenario("RUN[unproven]", 10000, 3)};
  t.scenarios[2].proven = false;
  t.scenarios[2].notProven = "max-throughput bounds: no overflow/underflow unknown";
  return t;
}

}  // namespace semo::runtime::sample
