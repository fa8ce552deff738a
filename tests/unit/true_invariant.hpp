#pragma once
// True invariants of a small model, for tests of what may assume the proven ones: "not both of
// two values" for a pair of variables neither of one robot nor of one family, a pair no reachable
// state holds (found by enumerating the reachable states with the Stepper) but that each variable
// alone takes. Each as a line of IR text (`invariant "unreached_pair" : ...;`), at most `most`.
#include <set>
#include <string>
#include <vector>

#include "semo/checker/stepper.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::test {

inline std::vector<std::string> trueInvariants(const ir::Model& model, std::size_t most) {
  std::vector<std::string> out;
  const checker::Stepper stepper(model);
  std::set<checker::Stepper::State> seen{stepper.initial()};
  std::vector<checker::Stepper::State> frontier{stepper.initial()};
  while (!frontier.empty()) {
    const checker::Stepper::State s = frontier.back();
    frontier.pop_back();
    for (auto& [choice, next] : stepper.successors(s)) {
      if (seen.insert(next).second) frontier.push_back(next);
    }
  }
  const auto& vars = model.variables;
  const auto family = [&](ir::VarId v) { return vars[v].name.substr(vars[v].name.find('.') + 1); };
  const auto equals = [&](ir::VarId v, std::int32_t x) {
    return vars[v].isBool ? (x != 0 ? vars[v].name : "!" + vars[v].name) : vars[v].name + " == " + std::to_string(x);
  };
  for (ir::VarId a = 0; a < vars.size(); ++a) {
    for (ir::VarId b = a + 1; b < vars.size(); ++b) {
      // Not of one robot, nor of one family (`r0.pc` and `r1.pc`): a superset projected on those
      // parts already holds such pairs as the reachable states do.
      if (vars[a].robot != ir::kNoRobot && vars[a].robot == vars[b].robot) continue;
      if (vars[a].robot != ir::kNoRobot && vars[b].robot != ir::kNoRobot && family(a) == family(b)) continue;
      std::set<std::int32_t> takenA, takenB;
      std::set<std::pair<std::int32_t, std::int32_t>> pairs;
      for (const auto& s : seen) takenA.insert(s[a]), takenB.insert(s[b]), pairs.emplace(s[a], s[b]);
      for (std::int32_t x : takenA) {
        for (std::int32_t y : takenB) {
          if (pairs.count({x, y}) != 0) continue;
          out.push_back("invariant \"unreached_pair\" : !(" + equals(a, x) + " && " + equals(b, y) + ");\n");
          if (out.size() == most) return out;
        }
      }
    }
  }
  return out;
}

}  // namespace semo::test
