// Which rules a run can take infinitely often (recurring_rules.hpp).
#include "recurring_rules.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "semo/checker/slicing.hpp"
#include "semo/checker/stepper.hpp"

namespace semo::checker::detail {

namespace {

// The strongly connected components of a graph (Tarjan's, without recursion): component per node.
std::vector<std::uint32_t> components(std::uint32_t nodes, const std::vector<std::vector<std::uint32_t>>& next) {
  constexpr std::uint32_t kNone = UINT32_MAX;
  std::vector<std::uint32_t> index(nodes, kNone), low(nodes, 0), comp(nodes, kNone), stack;
  std::vector<std::pair<std::uint32_t, std::size_t>> calls;
  std::uint32_t counter = 0, found = 0;
  for (std::uint32_t root = 0; root < nodes; ++root) {
    if (index[root] != kNone) continue;
    calls.push_back({root, 0});
    index[root] = low[root] = counter++;
    stack.push_back(root);
    while (!calls.empty()) {
      auto& [v, k] = calls.back();
      if (k < next[v].size()) {
        const std::uint32_t w = next[v][k++];
        if (index[w] == kNone) {
          index[w] = low[w] = counter++;
          stack.push_back(w);
          calls.push_back({w, 0});
        } else if (comp[w] == kNone) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      const std::uint32_t done = v;
      calls.pop_back();
      if (!calls.empty()) low[calls.back().first] = std::min(low[calls.back().first], low[done]);
      if (low[done] != index[done]) continue;
      while (true) {
        const std::uint32_t w = stack.back();
        stack.pop_back();
        comp[w] = found;
        if (w == done) break;
      }
      ++found;
    }
  }
  return comp;
}

}  // namespace

RecurringRules::RecurringRules(const ir::Model& model, const std::vector<char>& neverFires, std::uint64_t maxStatesPerPart)
    : modelRules_(model.rules.size()) {
  std::vector<std::vector<char>> keeps;
  std::vector<std::int32_t> controlOf(model.robots.size(), -1);
  for (ir::VarId v = 0; v < model.variables.size(); ++v) {
    const ir::Variable& var = model.variables[v];
    // A robot's control variables are one part: a mode change sets every program counter and a
    // plan's steps test the mode (a part of one counter alone would see every value reach every other).
    if (isControlVariable(var)) {
      std::int32_t& k = controlOf.at(static_cast<std::size_t>(var.robot));
      if (k < 0) k = static_cast<std::int32_t>(keeps.size()), keeps.emplace_back(model.variables.size(), 0);
      keeps[static_cast<std::size_t>(k)][v] = 1;
      continue;
    }
    keeps.emplace_back(model.variables.size(), 0);
    keeps.back()[v] = 1;
  }
  for (const std::vector<char>& keep : keeps) {
    const Slice slice = sliceVariables(model, keep, neverFires);
    if (slice.tooCoarse || slice.variables.empty()) continue;
    // States are keyed in mixed radix over the variables' ranges (at most 64 bits of them).
    std::uint64_t size = 1;
    std::vector<std::uint64_t> radix;
    bool fits = true;
    for (const ir::Variable& v : slice.model.variables) {
      radix.push_back(size);
      const auto width = static_cast<std::uint64_t>(static_cast<std::int64_t>(v.max) - v.min + 1);
      if (size > UINT64_MAX / width) fits = false;
      else size *= width;
    }
    if (!fits) continue;
    const Stepper stepper(slice.model);
    auto key = [&](const Stepper::State& st) {
      std::uint64_t i = 0;
      for (std::size_t k = 0; k < st.size(); ++k) i += static_cast<std::uint64_t>(st[k] - slice.model.variables[k].min) * radix[k];
      return i;
    };
    // Every state of the part reachable in its slice (which holds every reachable state of the
    // model seen through it), numbered in the order found, and the steps between them.
    Part part;
    std::unordered_map<std::uint64_t, std::uint32_t> number;
    std::vector<Stepper::State> states{stepper.initial()};
    number.emplace(key(states[0]), 0);
    for (std::size_t s = 0; s < states.size() && states.size() <= maxStatesPerPart; ++s) {
      for (auto& [choice, after] : stepper.successors(states[s])) {
        const auto [it, added] = number.try_emplace(key(after), static_cast<std::uint32_t>(states.size()));
        if (added) states.push_back(std::move(after));
        part.edges.push_back({static_cast<std::uint32_t>(s), it->second, slice.rules[choice.rule]});
      }
    }
    if (states.size() > maxStatesPerPart) continue;
    part.states = static_cast<std::uint32_t>(states.size());
    part.rules = slice.rules;
    parts_.push_back(std::move(part));
  }
}

std::vector<char> RecurringRules::narrow(std::vector<char> allowed) const {
  allowed.resize(modelRules_, 0);
  for (bool changed = true; changed;) {
    changed = false;
    for (const Part& part : parts_) {
      std::vector<std::vector<std::uint32_t>> next(part.states);
      for (const Edge& e : part.edges) {
        if (allowed[e.rule] != 0 && e.from != e.to) next[e.from].push_back(e.to);
      }
      const std::vector<std::uint32_t> comp = components(part.states, next);
      // A rule the part's slice keeps can recur only with a step that leaves the part as it was,
      // or that lies on a cycle of the allowed rules' steps.
      std::vector<char> mayRecur(modelRules_, 0);
      for (const Edge& e : part.edges) {
        if (e.from == e.to || comp[e.from] == comp[e.to]) mayRecur[e.rule] = 1;
      }
      for (std::uint32_t r : part.rules) {
        if (allowed[r] != 0 && mayRecur[r] == 0) allowed[r] = 0, changed = true;
      }
    }
  }
  return allowed;
}

std::vector<char> LoopNarrowing::loopRules(const std::function<bool(const ir::SensedOutcome&)>& senses) const {
  std::vector<char> allowed(model_.rules.size(), 1);
  for (std::size_t r = 0; r < model_.rules.size(); ++r) {
    for (const ir::SensedOutcome& o : model_.rules[r].sensed) {
      if (!senses(o)) allowed[r] = 0;
    }
  }
  const std::vector<char> recur = recurring_.narrow(std::move(allowed));
  std::vector<char> out(fromRules_.size(), 0);
  for (std::size_t j = 0; j < fromRules_.size(); ++j) out[j] = recur[fromRules_[j]];
  return out;
}

}  // namespace semo::checker::detail
