#include "projected_reach.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace semo::checker::detail {
namespace {

// Which variables each part holds (one flag per model variable).
std::vector<std::vector<char>> partsOf(const ir::Model& model) {
  const std::size_t n = model.variables.size();
  std::vector<ir::VarId> team;
  for (ir::VarId v = 0; v < n; ++v) {
    if (model.variables[v].robot == ir::kNoRobot) team.push_back(v);
  }
  std::vector<std::vector<char>> parts;
  std::map<std::string, std::size_t> byKey;
  const auto join = [&](const std::string& key, ir::VarId v) {
    auto [it, fresh] = byKey.emplace(key, parts.size());
    if (fresh) {
      parts.emplace_back(n, 0);
      for (ir::VarId t : team) parts.back()[t] = 1;
    }
    parts[it->second][v] = 1;
  };
  for (ir::VarId v = 0; v < n; ++v) {
    const std::int32_t robot = model.variables[v].robot;
    if (robot == ir::kNoRobot) continue;
    const std::string& name = model.robots.at(static_cast<std::size_t>(robot));
    join("robot " + name, v);
    std::string family = model.variables[v].name;
    for (std::size_t at = family.find(name); at != std::string::npos; at = family.find(name, at + 1)) family.replace(at, name.size(), "*");
    join("family " + family, v);
  }
  if (parts.empty()) parts.emplace_back(n, 1);  // no robots: the whole state, exactly
  return parts;
}

}  // namespace

bdd projectedReachable(SymbolicProduct& product, const ir::Model& model) {
  const std::vector<std::vector<char>> parts = partsOf(model);
  const std::size_t n = model.variables.size();
  std::vector<bdd> outside(parts.size(), bddtrue);  // the bits each part's projection quantifies away
  std::vector<std::vector<std::size_t>> partsOfVariable(n);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    for (ir::VarId v = 0; v < n; ++v) {
      if (parts[i][v] != 0) partsOfVariable[v].push_back(i);
      else outside[i] &= product.variableBits(v);
    }
  }
  // The parts each rule can change.
  std::vector<std::vector<std::size_t>> changes(model.rules.size());
  for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
    for (const ir::Branch& b : model.rules[r].branches) {
      for (const ir::Assignment& a : b.assignments) changes[r].insert(changes[r].end(), partsOfVariable[a.var].begin(), partsOfVariable[a.var].end());
    }
    std::sort(changes[r].begin(), changes[r].end());
    changes[r].erase(std::unique(changes[r].begin(), changes[r].end()), changes[r].end());
  }
  bdd assumed = bddtrue;
  for (const ir::Invariant& inv : model.invariants) assumed &= product.holds(inv.holds);
  const bdd initial = product.initialModelState();
  std::vector<bdd> sets;
  for (std::size_t i = 0; i < parts.size(); ++i) sets.push_back(bdd_exist(initial, outside[i]));
  const auto conjunction = [&] {
    bdd all = assumed;
    for (const bdd& s : sets) all &= s;
    return all;
  };
  bdd states = conjunction();
  for (bool grew = true; grew;) {
    grew = false;
    for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
      if (changes[r].empty()) continue;
      const bdd image = product.image(states, r);
      if (image == bddfalse) continue;
      bool more = false;
      for (std::size_t i : changes[r]) {
        const bdd seen = bdd_exist(image, outside[i]);
        if (minus(seen, sets[i]) == bddfalse) continue;
        sets[i] |= seen;
        more = true;
      }
      if (more) states = conjunction(), grew = true;
    }
  }
  return states;
}

}  // namespace semo::checker::detail
