#include "semo/checker/group_formation.hpp"

#include <algorithm>

#include <z3++.h>

namespace semo::checker {

using model::Index;

std::vector<FormationVerdict> checkGroupFormation(const model::MissionModel& m) {
  std::vector<FormationVerdict> out;
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
    v.budget = block.team < m.assumptions.crashBudget.size() ? m.assumptions.crashBudget[block.team] : 0;

    z3::context ctx;
    z3::optimize opt(ctx);
    z3::expr_vector crashed(ctx), chosen(ctx);
    for (Index r : robots) crashed.push_back(ctx.bool_const(("crashed_" + m.robots[r].name).c_str()));
    for (std::size_t a = 0; a < arms.size(); ++a) chosen.push_back(ctx.bool_const(("arm_" + std::to_string(a)).c_str()));
    // The chosen arms' live candidates, together, are fewer than the chosen arms (one robot each).
    z3::expr liveCandidates = ctx.int_val(0);
    for (std::size_t i = 0; i < robots.size(); ++i) {
      z3::expr_vector wantedBy(ctx);
      for (std::size_t a = 0; a < arms.size(); ++a) {
        const std::vector<Index>& c = arms[a]->candidates;
        if (std::find(c.begin(), c.end(), robots[i]) != c.end()) wantedBy.push_back(chosen[static_cast<int>(a)]);
      }
      if (wantedBy.empty()) continue;
      liveCandidates = liveCandidates + z3::ite(z3::mk_or(wantedBy) && !crashed[static_cast<int>(i)], ctx.int_val(1), ctx.int_val(0));
    }
    z3::expr arms_needed = ctx.int_val(0);
    for (std::size_t a = 0; a < arms.size(); ++a) arms_needed = arms_needed + z3::ite(chosen[static_cast<int>(a)], ctx.int_val(1), ctx.int_val(0));
    opt.add(liveCandidates < arms_needed);
    z3::expr crashes = ctx.int_val(0);
    for (std::size_t i = 0; i < robots.size(); ++i) crashes = crashes + z3::ite(crashed[static_cast<int>(i)], ctx.int_val(1), ctx.int_val(0));
    opt.minimize(crashes);
    if (opt.check() == z3::sat) {
      z3::model model = opt.get_model();
      for (std::size_t i = 0; i < robots.size(); ++i) {
        if (model.eval(crashed[static_cast<int>(i)], true).is_true()) v.breakingSet.push_back(m.robots[robots[i]].name);
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
