// What each robot's control variables can reach, and the rules and conjuncts that follows for
// (slicing.hpp, controlFacts).
//
// Why: a liveness property about modes reads every rule that changes a mode, and their guards read
// more than they need. A `default` transition out of a mode tests that every plan has finished,
// program counters of plans that never finish there, or do not run there at all; the cone of
// influence then takes in those plans, their leader elections and knowledge, though no reachable
// state lets those tests decide anything. One robot's mode and program counters have a few hundred
// thousand combinations at most on the examples, so the slice keeping them is explored whole.
#include "semo/checker/slicing.hpp"

#include <algorithm>
#include <string>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/stepper.hpp"

namespace semo::checker {

namespace {

std::vector<char> controlVariables(const ir::Model& model, std::int32_t robot) {
  std::vector<char> keep(model.variables.size(), 0);
  for (ir::VarId v = 0; v < model.variables.size(); ++v) keep[v] = model.variables[v].robot == robot && isControlVariable(model.variables[v]);
  return keep;
}

// The states of the slice reachable from its initial state; empty when its variables have more
// than `maxStates` combinations. States are numbered in mixed radix over the variables' ranges.
std::vector<Stepper::State> reachableStates(const Slice& slice, std::uint64_t maxStates) {
  std::uint64_t size = 1;
  std::vector<std::uint64_t> radix;
  for (const ir::Variable& v : slice.model.variables) {
    radix.push_back(size);
    size *= static_cast<std::uint64_t>(static_cast<std::int64_t>(v.max) - v.min + 1);
    if (size > maxStates) return {};
  }
  const Stepper stepper(slice.model);
  auto index = [&](const Stepper::State& st) {
    std::uint64_t i = 0;
    for (std::size_t k = 0; k < st.size(); ++k) i += static_cast<std::uint64_t>(st[k] - slice.model.variables[k].min) * radix[k];
    return i;
  };
  std::vector<char> seen(size, 0);
  std::vector<Stepper::State> frontier{stepper.initial()};
  seen[index(frontier[0])] = 1;
  std::vector<Stepper::State> reached;
  while (!frontier.empty()) {
    Stepper::State st = std::move(frontier.back());
    frontier.pop_back();
    for (auto& step : stepper.successors(st)) {
      const std::uint64_t i = index(step.second);
      if (seen[i] == 0) seen[i] = 1, frontier.push_back(std::move(step.second));
    }
    reached.push_back(std::move(st));
  }
  return reached;
}

void conjuncts(const ir::Expr& e, std::vector<ir::Expr>& out) {
  if (e.op == ir::Op::And) {
    for (const ir::Expr& a : e.args) conjuncts(a, out);
    return;
  }
  out.push_back(e);
}

bool readsOnly(const ir::Expr& e, const std::vector<char>& keep) {
  std::vector<char> reads(keep.size(), 0);
  markVariablesRead(e, reads);
  for (std::size_t v = 0; v < reads.size(); ++v) {
    if (reads[v] != 0 && keep[v] == 0) return false;
  }
  return true;
}

// One robot's slice: marks the rules it shows dead, drops the conjuncts it shows implied. False when
// the slice is too large to explore.
bool learnFromRobot(ControlFacts& facts, std::int32_t robot, std::uint64_t maxStates, bool& learned) {
  const ir::Model& model = facts.model;
  const std::vector<char> keep = controlVariables(model, robot);
  const Slice slice = sliceVariables(model, keep, facts.neverFires);
  if (slice.tooCoarse || slice.variables.empty()) return false;
  const std::vector<Stepper::State> reached = reachableStates(slice, maxStates);
  if (reached.empty()) return false;
  const std::size_t n = model.variables.size();
  for (std::size_t r = 0; r < model.rules.size(); ++r) {
    if (facts.neverFires[r] != 0) continue;
    std::vector<ir::Expr> parts;
    conjuncts(model.rules[r].guard, parts);
    std::vector<Condition> seen;
    for (const ir::Expr& c : parts) seen.emplace_back(seenThrough(c, slice, n));
    std::vector<char> present(parts.size(), 1);
    auto restHolds = [&](const Stepper::State& st, std::size_t except) {
      for (std::size_t j = 0; j < parts.size(); ++j) {
        if (j != except && present[j] != 0 && !seen[j].holds(st.data())) return false;
      }
      return true;
    };
    if (std::none_of(reached.begin(), reached.end(), [&](const Stepper::State& st) { return restHolds(st, parts.size()); })) {
      facts.neverFires[r] = 1;
      learned = true;
      continue;
    }
    bool dropped = false;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (parts.size() == 1 || !readsOnly(parts[i], keep)) continue;
      const bool implied = std::all_of(reached.begin(), reached.end(),
                                       [&](const Stepper::State& st) { return seen[i].holds(st.data()) || !restHolds(st, i); });
      if (implied) present[i] = 0, dropped = true, ++facts.droppedConjuncts;
    }
    if (!dropped) continue;
    learned = true;
    ir::Expr guard = ir::Expr::constant(1);
    bool first = true;
    for (std::size_t j = 0; j < parts.size(); ++j) {
      if (present[j] == 0) continue;
      guard = first ? parts[j] : ir::Expr::binary(ir::Op::And, std::move(guard), parts[j]);
      first = false;
    }
    facts.model.rules[r].guard = std::move(guard);
  }
  return true;
}

}  // namespace

bool isControlVariable(const ir::Variable& v) {
  const std::string& n = v.name;
  auto endsWith = [&](const std::string& suffix) { return n.size() >= suffix.size() && n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0; };
  return v.robot != ir::kNoRobot && (endsWith(".mode") || endsWith(".alive") || endsWith(".pc") || n.find(".pc.") != std::string::npos);
}

ControlFacts controlFacts(const ir::Model& model, std::uint64_t maxStatesPerRobot) {
  ControlFacts facts;
  facts.model = model;
  facts.neverFires.assign(model.rules.size(), 0);
  // What one robot's slice shows makes the others' smaller: another pass while the last one
  // learned something, up to a few.
  for (int pass = 0; pass < 3; ++pass) {
    bool learned = false;
    facts.robotsSkipped = 0;
    for (std::int32_t robot = 0; robot < static_cast<std::int32_t>(model.robots.size()); ++robot) {
      if (!learnFromRobot(facts, robot, maxStatesPerRobot, learned)) ++facts.robotsSkipped;
    }
    if (!learned) break;
  }
  return facts;
}

}  // namespace semo::checker
