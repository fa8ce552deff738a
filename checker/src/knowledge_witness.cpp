#include "semo/checker/trace.hpp"

#include <map>

namespace semo::checker {

namespace {

// The knowledge item a count belongs to: its name without the robot's ("ev3_0.knows.papers" ->
// ".knows.papers"), so that the robots' counts of one item are found together.
std::string itemOf(const ir::Model& m, const ir::Variable& v) {
  if (v.robot == ir::kNoRobot) return v.name;
  const std::string& robot = m.robots.at(static_cast<std::size_t>(v.robot));
  return v.name.compare(0, robot.size(), robot) == 0 ? v.name.substr(robot.size()) : v.name;
}

}  // namespace

KnowledgeWitness knowledgeWitness(const ir::Model& m, const Trace& t) {
  KnowledgeWitness out;
  std::map<std::string, std::vector<ir::VarId>> items;  // item -> its counts, one per robot
  std::vector<std::vector<char>> held(m.variables.size());
  for (ir::VarId v = 0; v < m.variables.size(); ++v) {
    const ir::Variable& var = m.variables[v];
    if (var.facts.empty()) continue;
    items[itemOf(m, var)].push_back(v);
    held[v].assign(var.facts.size(), 0);
    const std::int32_t start = v < t.initial.size() ? t.initial[v] : var.init;
    for (std::int32_t f = 0; f < start && static_cast<std::size_t>(f) < var.facts.size(); ++f) held[v][static_cast<std::size_t>(f)] = 1;
  }
  if (items.empty()) return out;
  out.held.resize(t.steps.size());
  for (std::size_t i = 0; i < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    out.held[i].resize(s.changes.size());
    for (std::size_t j = 0; j < s.changes.size(); ++j) {
      const Change& c = s.changes[j];
      if (c.var >= m.variables.size() || held[c.var].empty()) continue;
      const ir::Variable& var = m.variables[c.var];
      std::vector<char>& mine = held[c.var];
      const std::size_t facts = mine.size();
      if (c.after < 0 || static_cast<std::size_t>(c.after) > facts) return {};
      if (c.after < c.before) {  // a crash starts over: keep the first ones
        std::int32_t kept = 0;
        for (char& h : mine) h = h != 0 && kept < c.after ? (++kept, 1) : 0;
      } else if (c.after > c.before) {
        const auto wanted = static_cast<std::size_t>(c.after - c.before);
        const std::vector<ir::VarId>& counts = items[itemOf(m, var)];
        // A gossip step (a delivery) names no teacher: the first other robot that holds at most
        // as many facts as the learner ends with and enough it lacks (a crashed one holds none).
        const std::vector<char>* teacher = nullptr;
        if (s.rule < m.rules.size() && m.rules[s.rule].kind == ir::RuleKind::Delivery) {
          for (ir::VarId other : counts) {
            if (other == c.var || teacher != nullptr) continue;
            std::size_t theirs = 0, lacking = 0;
            for (std::size_t f = 0; f < facts; ++f) {
              theirs += held[other][f] != 0 ? 1 : 0;
              lacking += held[other][f] != 0 && mine[f] == 0 ? 1 : 0;
            }
            if (theirs <= static_cast<std::size_t>(c.after) && lacking >= wanted) teacher = &held[other];
          }
          if (teacher == nullptr) return {};
        }
        std::vector<std::size_t> candidates;
        if (teacher != nullptr) {
          for (std::size_t f = 0; f < facts; ++f) {
            if ((*teacher)[f] != 0 && mine[f] == 0) candidates.push_back(f);
          }
        } else {  // found: first the facts nobody holds, then those this robot lacks
          for (int pass = 0; pass < 2; ++pass) {
            for (std::size_t f = 0; f < facts; ++f) {
              bool anyone = false;
              for (ir::VarId other : counts) anyone = anyone || held[other][f] != 0;
              if (mine[f] == 0 && (pass == 1 ? anyone : !anyone)) candidates.push_back(f);
            }
          }
        }
        if (candidates.size() < wanted) return {};
        for (std::size_t k = 0; k < wanted; ++k) mine[candidates[k]] = 1;
      }
      std::vector<std::string>& names = out.held[i][j];
      for (std::size_t f = 0; f < facts; ++f) {
        if (mine[f] != 0) names.push_back(var.facts[f]);
      }
      out.named = true;
    }
  }
  return out;
}

}  // namespace semo::checker
