#include "semo/checker/fairness.hpp"

#include <unordered_map>

namespace semo::checker {

Fairness Fairness::of(const ir::Model& model) {
  Fairness f;
  f.groupOf.assign(model.rules.size(), kNone);
  std::unordered_map<std::string, std::uint32_t> named;
  for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
    const ir::Rule& rule = model.rules[r];
    if (!rule.weaklyFair && !rule.stronglyFair) continue;
    std::uint32_t g = static_cast<std::uint32_t>(f.members.size());
    if (!rule.stronglyFair && !rule.fairGroup.empty()) {
      auto [it, added] = named.try_emplace(rule.fairGroup, g);
      g = it->second;
      if (!added) {
        f.groupOf[r] = g;
        f.members[g].push_back(r);
        continue;
      }
    }
    f.groupOf[r] = g;
    f.members.push_back({r});
    f.strong.push_back(rule.stronglyFair ? 1 : 0);
  }
  return f;
}

Sensing Sensing::in(const ir::Model& model) {
  Sensing s;
  std::unordered_map<std::string, std::uint32_t> ids;
  for (const ir::Rule& rule : model.rules) {
    std::vector<Decision> decisions;
    for (const ir::SensedOutcome& o : rule.sensed) {
      auto [it, added] = ids.try_emplace(o.point, static_cast<std::uint32_t>(ids.size()));
      if (added) s.names.push_back(o.point);
      decisions.push_back({it->second, o.holds});
    }
    s.of.push_back(std::move(decisions));
  }
  s.points = ids.size();
  return s;
}

}  // namespace semo::checker
