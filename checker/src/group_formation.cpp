#include "semo/checker/group_formation.hpp"

#include <algorithm>
#include <map>

#include <z3++.h>

namespace semo::checker {

using model::Index;

std::string formationCoverage(const FormationVerdict& v) {
  std::string out = "every crash set of up to " + std::to_string(v.budget) + " robots leaves it formable; it tolerates " + std::to_string(v.tolerated);
  if (v.vacuousAtBudget()) {
    out += "; with all " + std::to_string(v.teamSize) + " robots of its team crashed nobody is left to form it: that case holds vacuously";
  }
  return out;
}

std::vector<FormationVerdict> checkGroupFormation(const model::MissionModel& m, const std::vector<std::int64_t>* crashBudget) {
  std::vector<FormationVerdict> out;
  const std::vector<std::int64_t>& budgets = crashBudget != nullptr ? *crashBudget : m.assumptions.crashBudget;
  for (Index b = 0; b < m.groupBlocks.size(); ++b) {
    const model::GroupBlock& block = m.groupBlocks[b];
    std::vector<const model::GroupArm*> arms;
    for (const model::GroupArm& arm : block.arms) {
      if (arm.kind != model::GroupArm::Kind::Others) arms.push_back(&arm);
    }
    if (arms.empty()) continue;
    const std::vector<Index>& robots = m.teams[block.team].robots;
    FormationVerdict v;
    v.blockIndex = b;
    v.block = m.services[block.service].name + (block.isLeaderBlock ? " (leader block)" : (arms.size() == 1 ? " (block of 1 group)" : " (block of " + std::to_string(arms.size()) + " groups)"));
    v.budget = block.team < budgets.size() ? budgets[block.team] : 0;
    v.teamSize = static_cast<std::int64_t>(robots.size());

    // Robots wanted by the same arms are interchangeable here: one count per such class (how many
    // of it crash) keeps the problem as small as the number of classes, whatever the team's size.
    std::map<std::vector<std::size_t>, std::vector<Index>> classes;
    for (Index r : robots) {
      std::vector<std::size_t> wantedBy;
      for (std::size_t a = 0; a < arms.size(); ++a) {
        const std::vector<Index>& c = arms[a]->candidates;
        if (std::find(c.begin(), c.end(), r) != c.end()) wantedBy.push_back(a);
      }
      if (!wantedBy.empty()) classes[wantedBy].push_back(r);
    }
    z3::context ctx;
    z3::optimize opt(ctx);
    z3::expr_vector chosen(ctx);
    for (std::size_t a = 0; a < arms.size(); ++a) chosen.push_back(ctx.bool_const(("arm_" + std::to_string(a)).c_str()));
    // The chosen arms' live candidates, together, are fewer than the robots the chosen arms need
    // (Hall's condition with a demand per arm: each needs its minimum size, robots of its own).
    z3::expr liveCandidates = ctx.int_val(0), crashes = ctx.int_val(0), armsChosen = ctx.int_val(0);
    std::vector<z3::expr> crashedOf;
    std::size_t k = 0;
    for (const auto& [wantedBy, members] : classes) {
      z3::expr crashed = ctx.int_const(("crashed_" + std::to_string(k++)).c_str());
      const int size = static_cast<int>(members.size());
      opt.add(crashed >= 0 && crashed <= size);
      z3::expr_vector any(ctx);
      for (std::size_t a : wantedBy) any.push_back(chosen[static_cast<int>(a)]);
      liveCandidates = liveCandidates + z3::ite(z3::mk_or(any), size - crashed, ctx.int_val(0));
      crashes = crashes + crashed;
      crashedOf.push_back(crashed);
    }
    for (std::size_t a = 0; a < arms.size(); ++a) {
      armsChosen = armsChosen + z3::ite(chosen[static_cast<int>(a)], ctx.int_val(static_cast<int>(m.armDemand(*arms[a]))), ctx.int_val(0));
    }
    opt.add(liveCandidates < armsChosen);
    // Some robot of the team is left to run the block: with the whole team crashed, nobody forms
    // it, and the translation's invariant holds (specs/semantics.md), vacuously.
    opt.add(crashes < static_cast<int>(robots.size()));
    opt.minimize(crashes);
    if (opt.check() == z3::sat) {
      z3::model model = opt.get_model();
      k = 0;
      for (const auto& [wantedBy, members] : classes) {
        auto n = static_cast<std::size_t>(model.eval(crashedOf[k++], true).get_numeral_int64());
        for (std::size_t i = 0; i < n && i < members.size(); ++i) v.breakingSet.push_back(m.robots[members[i]].name);
      }
      for (std::size_t a = 0; a < arms.size(); ++a) {
        if (!model.eval(chosen[static_cast<int>(a)], true).is_true()) continue;
        std::string names;
        for (const std::string& n : arms[a]->names) names += (names.empty() ? "" : ", ") + n;
        v.unmetArms.push_back(std::string(arms[a]->kind == model::GroupArm::Kind::Leader ? "leader (" : "group (") +
                              (arms[a]->byCapability ? "capable of " : "instance of ") + names + ")");
      }
      v.tolerated = static_cast<std::int64_t>(v.breakingSet.size()) - 1;
    } else {
      v.tolerated = static_cast<std::int64_t>(robots.size());  // no crash set breaks it
    }
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace semo::checker
