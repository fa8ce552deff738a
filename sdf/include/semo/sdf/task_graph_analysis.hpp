#pragma once
// Every analysis of a task graph, scenario by scenario: consistency and repetition vector,
// deadlock freedom with a static schedule, the period with unbounded channels, the throughput-
// buffer front and the chosen, proven buffer bounds (bounds.hpp). The capacities the robot's code
// gets are, per channel, the largest maximal-throughput bound over the scenarios that use it:
// enlarging a channel never deadlocks an SDF graph nor lowers its throughput, so every scenario's
// proofs still hold with them.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "semo/sdf/bounds.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/task_graph.hpp"
#include "semo/sdf/throughput.hpp"

namespace semo::sdf {

struct ScenarioAnalysis {
  std::string scenario;
  Graph graph;  // scenarioGraph(): actor/channel indices below refer to it
  RepetitionVector repetition;
  Iteration iteration;
  ThroughputResult unbounded;
  ScenarioBounds bounds;
  // Sound: consistent, deadlock free, period known and both bounds proven (safety and minimality).
  [[nodiscard]] bool sound() const;
  // Runnable: consistent, deadlock free, a period, and the max-throughput schedule proven safe within
  // its capacities: what running the scenario needs (sound() implies it; minimality is not needed).
  [[nodiscard]] bool runnable() const;
  // Decided: nothing came out "unknown" (a limit or a solver timeout); !sound() && decided() is a
  // real defect of the graph.
  [[nodiscard]] bool decided() const;
};

struct TaskGraphAnalysis {
  std::vector<ScenarioAnalysis> scenarios;
  std::vector<std::int64_t> capacities;  // per TaskGraph channel (0: in no scenario)
};

// Robots of one type in the same role get the same scenario graphs: a cache shared across calls
// analyses each distinct graph (actors, execution times, channels, rates, tokens) once. One cache
// serves one BoundsOptions: its entries hold the proofs those options asked for.
class ScenarioCache {
 public:
  const ScenarioAnalysis* find(const Graph& g) const;
  void store(const Graph& g, const ScenarioAnalysis& a);
  [[nodiscard]] std::size_t hits() const { return hits_; }

 private:
  static std::string key(const Graph& g);
  std::map<std::string, ScenarioAnalysis> entries_;
  mutable std::size_t hits_ = 0;
};

TaskGraphAnalysis analyseTaskGraph(const TaskGraph& tg, const BoundsOptions& options = {}, ScenarioCache* cache = nullptr);

}  // namespace semo::sdf
