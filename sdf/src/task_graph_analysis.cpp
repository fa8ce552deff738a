// Per-scenario analysis of a task graph (task_graph_analysis.hpp).
#include "semo/sdf/task_graph_analysis.hpp"

#include <algorithm>

namespace semo::sdf {

namespace {

bool boundsProven(const ChosenBounds& b) { return b.safety == ProofStatus::Proven && b.minimality == ProofStatus::Proven; }
bool boundsUnknown(const ChosenBounds& b) { return b.safety == ProofStatus::Unknown || b.minimality == ProofStatus::Unknown; }

void analyseScenario(ScenarioAnalysis& a, const BoundsOptions& options) {
  a.repetition = repetitionVector(a.graph);
  if (a.repetition.consistent()) a.iteration = runIteration(a.graph, a.repetition.firings);
  if (a.iteration.deadlockFree) a.unbounded = throughput(a.graph, a.repetition.firings);
  if (a.iteration.deadlockFree && a.unbounded.error.empty()) a.bounds = chooseAndProveBounds(a.graph, a.repetition.firings, options);
}

}  // namespace

bool ScenarioAnalysis::sound() const {
  return repetition.consistent() && iteration.deadlockFree && unbounded.error.empty() && bounds.haveBounds &&
         boundsProven(bounds.deadlockFree) && boundsProven(bounds.maxThroughput);
}

bool ScenarioAnalysis::runnable() const {
  return repetition.consistent() && iteration.deadlockFree && unbounded.error.empty() && bounds.haveBounds &&
         bounds.maxThroughput.safety == ProofStatus::Proven;
}

bool ScenarioAnalysis::decided() const {
  if (!repetition.consistent()) return repetition.conflictChannel.has_value();
  if (!iteration.error.empty()) return false;
  if (!iteration.deadlockFree) return true;
  if (!unbounded.error.empty() || !bounds.haveBounds) return false;
  return !boundsUnknown(bounds.deadlockFree) && !boundsUnknown(bounds.maxThroughput);
}

std::string ScenarioCache::key(const Graph& g) {
  std::string k;
  for (const Actor& a : g.actors) k += a.name + ' ' + std::to_string(a.executionTime) + ';';
  for (const Channel& c : g.channels) {
    k += c.name + ' ' + std::to_string(c.source) + ' ' + std::to_string(c.target) + ' ' + std::to_string(c.production) + ' ' +
         std::to_string(c.consumption) + ' ' + std::to_string(c.initialTokens) + ';';
  }
  return k;
}

const ScenarioAnalysis* ScenarioCache::find(const Graph& g) const {
  auto it = entries_.find(key(g));
  if (it == entries_.end()) return nullptr;
  ++hits_;
  return &it->second;
}

void ScenarioCache::store(const Graph& g, const ScenarioAnalysis& a) { entries_.emplace(key(g), a); }

TaskGraphAnalysis analyseTaskGraph(const TaskGraph& tg, const BoundsOptions& options, ScenarioCache* cache) {
  TaskGraphAnalysis out;
  out.capacities.assign(tg.channels.size(), 0);
  for (const Scenario& s : tg.scenarios) {
    ScenarioAnalysis a;
    a.graph = scenarioGraph(tg, s);
    if (const ScenarioAnalysis* known = cache != nullptr ? cache->find(a.graph) : nullptr) {
      a = *known;
    } else {
      analyseScenario(a, options);
      if (cache != nullptr) cache->store(a.graph, a);
    }
    a.scenario = s.name;
    if (a.bounds.haveBounds) {
      for (std::size_t c = 0; c < s.channels.size(); ++c) {  // scenarioGraph keeps the scenario's channel order
        std::int64_t& cap = out.capacities[s.channels[c].channel];
        cap = std::max(cap, a.bounds.maxThroughput.capacities[c]);
      }
    }
    out.scenarios.push_back(std::move(a));
  }
  return out;
}

}  // namespace semo::sdf
