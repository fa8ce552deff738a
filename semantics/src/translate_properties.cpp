// The properties of the model: the built-in invariants (group formation, buffer bounds, unique
// leader) and valid_end, the built-in liveness properties, and the verify block's own properties,
// as invariants when they are `always <state formula>` and as LTL otherwise.
#include <algorithm>

#include "translator.hpp"

namespace semo::detail {

// A property formula without temporal operators as an expression over the state, or nullopt.
std::optional<Expr> Translator::stateFormula(const model::Ltl& f, std::string& why) const {
  using K = model::Ltl::Kind;
  switch (f.kind) {
    case K::Always: case K::Eventually: case K::Next: case K::Until:
      why = "it has nested temporal operators (the LTL engine will check it)";
      return std::nullopt;
    case K::Not: {
      auto a = stateFormula(*f.left, why);
      return a ? std::optional<Expr>(lnot(std::move(*a))) : std::nullopt;
    }
    case K::And: case K::Or: case K::Implies: {
      auto a = stateFormula(*f.left, why), b = stateFormula(*f.right, why);
      if (!a || !b) return std::nullopt;
      Op op = f.kind == K::And ? Op::And : f.kind == K::Or ? Op::Or : Op::Implies;
      return Expr::binary(op, std::move(*a), std::move(*b));
    }
    case K::Atom: break;
  }
  if (f.subjectIndex == model::kNone) return Expr::constant(f.rhs.intValue != 0 ? 1 : 0);  // true / false
  std::vector<Index> robots;
  if (f.subject == model::Ltl::Subject::Robot) {
    robots.push_back(f.subjectIndex);
  } else {
    robots = m_.teams[f.subjectIndex].robots;
  }
  std::vector<Expr> each;
  for (Index r : robots) {
    std::optional<Expr> atom;
    const RobotVars& v = vars_[r];
    switch (f.attribute) {
      case model::Ltl::Attribute::Alive: atom = alive(r); break;
      case model::Ltl::Attribute::Leader: {
        std::vector<Expr> leads;
        for (const auto& [b, var] : v.leads) leads.push_back(Expr::var(var));
        atom = ir::conjunction({alive(r), ir::disjunction(std::move(leads))});
        break;
      }
      case model::Ltl::Attribute::Mode: {
        const std::vector<Index>& modes = m_.teams[m_.robots[r].team].modes;
        auto k = static_cast<std::int32_t>(std::find(modes.begin(), modes.end(), f.mode) - modes.begin());
        atom = v.mode ? eq(Expr::var(*v.mode), k) : Expr::constant(k == 0 ? 1 : 0);
        if (f.op && *f.op == model::RelOp::Ne) atom = lnot(std::move(*atom));
        break;
      }
      case model::Ltl::Attribute::Value: {
        if (f.valueKind != model::ValueKind::Topic || !f.op) {
          why = "'" + f.var + "' is a sensed value or knowledge, which the model does not keep";
          return std::nullopt;
        }
        Index tp = m_.findTopic(m_.robots[r].team, f.var);
        if (tp == model::kNone) tp = m_.findTopic(f.subject == model::Ltl::Subject::Team ? f.subjectIndex : m_.robots[r].team, f.var);
        auto view = tp == model::kNone ? v.view.end() : v.view.find(tp);
        if (view == v.view.end()) {
          why = "robot '" + m_.robots[r].name + "' keeps no value of topic '" + f.var + "' (its team never reads it)";
          return std::nullopt;
        }
        std::int32_t symbol = symbolValue(tp, f.rhs);
        if (symbol < 0 || (*f.op != model::RelOp::Eq && *f.op != model::RelOp::Ne)) {
          why = "topic '" + f.var + "' is compared with a value it never carries, or with an ordering";
          return std::nullopt;
        }
        atom = eq(Expr::var(view->second), symbol);
        if (*f.op == model::RelOp::Ne) atom = lnot(std::move(*atom));
        break;
      }
    }
    // A team atom speaks of its live robots.
    each.push_back(f.subject == model::Ltl::Subject::Team ? Expr::binary(Op::Or, lnot(alive(r)), std::move(*atom)) : std::move(*atom));
  }
  return ir::conjunction(std::move(each));
}

// The live candidates of `arms`, together, are at least the robots they need.
Expr Translator::enoughLive(const std::vector<const model::GroupArm*>& arms) const {
  std::vector<Index> candidates;
  std::int64_t demand = 0;
  for (const model::GroupArm* arm : arms) {
    demand += m_.armDemand(*arm);
    for (Index c : arm->candidates) {
      if (std::find(candidates.begin(), candidates.end(), c) == candidates.end()) candidates.push_back(c);
    }
  }
  if (demand == 1) {  // the common case, kept as the plain disjunction it always was
    std::vector<Expr> live;
    for (Index c : candidates) live.push_back(alive(c));
    return ir::disjunction(std::move(live));
  }
  Expr count = Expr::constant(0);
  for (Index c : candidates) count = Expr::binary(Op::Add, std::move(count), Expr::ite(alive(c), Expr::constant(1), Expr::constant(0)));
  return Expr::binary(Op::Ge, std::move(count), Expr::constant(static_cast<std::int32_t>(demand)));
}

void Translator::invariants() {
  if (wants("group_formation")) {
    for (Index t = 0; t < programs_.size(); ++t) {
      for (std::size_t p = 0; p < programs_[t].size(); ++p) {
        for (const BlockRange& range : programs_[t][p].blocks) {
          const model::GroupBlock& block = m_.groupBlocks[range.block];
          std::vector<Expr> inside;
          for (Index r : m_.teams[t].robots) {
            if (!vars_[r].pc[p]) continue;
            Expr pc = Expr::var(*vars_[r].pc[p]);
            // Forming the block or inside an arm; a robot at the block's exit has finished with it.
            inside.push_back(ir::conjunction({alive(r), Expr::binary(Op::Gt, pc, Expr::constant(static_cast<std::int32_t>(range.first))),
                                              Expr::binary(Op::Le, pc, Expr::constant(static_cast<std::int32_t>(range.last)))}));
          }
          // Each arm, and each set of two or more arms, has at least as many live candidates
          // (together: a robot joins one arm) as its robots need (Hall's condition; the crash-set
          // analysis of checker/group_formation.cpp decides the same, for every crash set).
          std::vector<const model::GroupArm*> arms;
          for (const model::GroupArm& arm : block.arms) {
            if (arm.kind != model::GroupArm::Kind::Others) arms.push_back(&arm);
          }
          const std::size_t subsets = arms.size() <= kHallArms ? (std::size_t{1} << arms.size()) : 0;
          auto armText = [&](const model::GroupArm& arm) {
            return std::string(arm.kind == model::GroupArm::Kind::Leader ? "leader" : "group") + " (" + arm.names.front() +
                   (arm.names.size() > 1 ? ", ..." : "") + ")";
          };
          for (std::size_t a = 0; a < arms.size(); ++a) {
            ir::Invariant inv;
            inv.name = "group_formation[" + m_.services[block.service].name + " " + armText(*arms[a]) + "]";
            inv.origin = origin(arms[a]->at, "").text();
            inv.holds = Expr::binary(Op::Implies, ir::disjunction(inside), enoughLive({arms[a]}));
            out_.invariants.push_back(std::move(inv));
          }
          for (std::size_t set = 1; set < subsets; ++set) {
            if ((set & (set - 1)) == 0) continue;  // one arm: above
            std::vector<const model::GroupArm*> chosen;
            std::string names;
            for (std::size_t a = 0; a < arms.size(); ++a) {
              if ((set >> a & 1) == 0) continue;
              chosen.push_back(arms[a]);
              names += (names.empty() ? "" : " and ") + armText(*arms[a]);
            }
            ir::Invariant inv;
            inv.name = "group_formation[" + m_.services[block.service].name + " " + names + "]";
            inv.origin = origin(block.at, "").text();
            inv.holds = Expr::binary(Op::Implies, ir::disjunction(inside), enoughLive(chosen));
            out_.invariants.push_back(std::move(inv));
          }
        }
      }
    }
  }
  if (wants("buffer_bounds")) {
    for (const auto& [tp, ch] : channel_) {
      ir::Invariant inv;
      inv.name = "buffer_bounds[" + m_.teams[m_.topics[tp].owner].name + "." + m_.topics[tp].var + "]";
      inv.origin = origin(m_.topics[tp].firstUse, "").text();
      inv.holds = Expr::binary(Op::Le, Expr::var(ch), Expr::constant(static_cast<std::int32_t>(m_.topics[tp].buffer)));
      out_.invariants.push_back(std::move(inv));
    }
  }
  if (wants("deadlock_freedom")) {
    std::vector<Expr> finished;
    for (Index r = 0; r < m_.robots.size(); ++r) {
      std::vector<Expr> done;
      Index team = m_.robots[r].team;
      for (std::size_t p = 0; p < vars_[r].pc.size(); ++p) {
        const std::optional<ir::VarId>& pc = vars_[r].pc[p];
        if (!pc) continue;
        // A plan is done, or works in a group service without a goal, which runs until the mode
        // changes: the robot is busy, not stuck, even when no fact is left to find.
        std::vector<Expr> atRest{eq(Expr::var(*pc), 0)};
        for (const auto& [key, sites] : sites_) {
          if (key.first != team || m_.strategy.services[sites.service].goal) continue;
          for (const ServiceSite& site : sites.at) {
            if (site.plan == p) atRest.push_back(eq(Expr::var(*pc), static_cast<std::int32_t>(site.instr)));
          }
        }
        done.push_back(ir::disjunction(std::move(atRest)));
      }
      if (done.empty()) continue;
      finished.push_back(Expr::binary(Op::Or, lnot(alive(r)), ir::conjunction(std::move(done))));
    }
    out_.validEnd = ir::conjunction(std::move(finished));
  }
  for (const model::Property& p : m_.properties) {
    // `always p` with p free of temporal operators is an invariant; the rest needs the LTL engine.
    std::optional<Expr> holds;
    std::string why = "it is not of the form 'always <state formula>' (the LTL engine will check it)";
    if (p.formula->kind == model::Ltl::Kind::Always) holds = stateFormula(*p.formula->left, why);
    if (holds) {
      out_.invariants.push_back({p.name, origin(p.at, "").text(), std::move(*holds)});
      continue;
    }
    why.clear();
    std::optional<ir::Ltl> formula = temporalFormula(*p.formula, why);
    if (!formula) {
      diags_.warning(p.at, "property '" + p.name + "' is not checked: " + why);
      continue;
    }
    out_.properties.push_back({p.name, origin(p.at, "").text(), std::move(*formula)});
  }
  if (wants("unique_leader")) {
    for (Index b : leaderBlocks_) {
      std::vector<Expr> pairs;
      const std::vector<Index>& cands = candidates(b);
      for (std::size_t i = 0; i < cands.size(); ++i) {
        for (std::size_t j = i + 1; j < cands.size(); ++j) {
          pairs.push_back(lnot(ir::conjunction({alive(cands[i]), Expr::var(vars_[cands[i]].leads.at(b)), alive(cands[j]),
                                                Expr::var(vars_[cands[j]].leads.at(b))})));
        }
      }
      ir::Invariant inv;
      inv.name = "unique_leader[" + m_.services[m_.groupBlocks[b].service].name + "]";
      inv.origin = origin(m_.groupBlocks[b].at, "").text();
      inv.holds = ir::conjunction(std::move(pairs));
      out_.invariants.push_back(std::move(inv));
    }
  }
}

std::optional<ir::Ltl> Translator::temporalFormula(const model::Ltl& f, std::string& why) const {
  using K = model::Ltl::Kind;
  auto one = [&](ir::Ltl::Kind kind) -> std::optional<ir::Ltl> {
    auto a = temporalFormula(*f.left, why);
    return a ? std::optional<ir::Ltl>(ir::Ltl::unary(kind, std::move(*a))) : std::nullopt;
  };
  auto two = [&](ir::Ltl::Kind kind) -> std::optional<ir::Ltl> {
    auto a = temporalFormula(*f.left, why), b = temporalFormula(*f.right, why);
    return a && b ? std::optional<ir::Ltl>(ir::Ltl::binary(kind, std::move(*a), std::move(*b))) : std::nullopt;
  };
  switch (f.kind) {
    case K::Always: return one(ir::Ltl::Kind::Always);
    case K::Eventually: return one(ir::Ltl::Kind::Eventually);
    case K::Next: return one(ir::Ltl::Kind::Next);
    case K::Not: return one(ir::Ltl::Kind::Not);
    case K::Until: return two(ir::Ltl::Kind::Until);
    case K::And: return two(ir::Ltl::Kind::And);
    case K::Or: return two(ir::Ltl::Kind::Or);
    case K::Implies: return two(ir::Ltl::Kind::Implies);
    case K::Atom: break;
  }
  std::optional<Expr> atom = stateFormula(f, why);
  return atom ? std::optional<ir::Ltl>(ir::Ltl::of(std::move(*atom))) : std::nullopt;
}

// The built-in liveness checks (specs/semantics.md, "Liveness"), as LTL over the state.
void Translator::livenessProperties() {
  using L = ir::Ltl;
  auto alwaysEventually = [](Expr e) { return L::unary(L::Kind::Always, L::unary(L::Kind::Eventually, L::of(std::move(e)))); };
  if (wants("mode_agreement")) {
    for (Index t = 0; t < m_.teams.size(); ++t) {
      const std::vector<Index>& robots = m_.teams[t].robots;
      if (robots.size() < 2 || m_.teams[t].modes.size() < 2 || !vars_[robots.front()].mode) continue;
      // Again and again, the live robots of the team are all in one mode, once the world they sense
      // settles: an environment that keeps changing its mind (an operator switching remote control
      // on and off for ever) can keep any team of robots that sense for themselves apart, which
      // says nothing of the mission. A split that lasts while the world is quiet (a lost event, say)
      // is what this finds; the lasso shows how.
      std::vector<Expr> someMode;
      for (std::size_t k = 0; k < m_.teams[t].modes.size(); ++k) {
        std::vector<Expr> all;
        for (Index r : robots) all.push_back(Expr::binary(Op::Or, lnot(alive(r)), eq(Expr::var(*vars_[r].mode), static_cast<std::int32_t>(k))));
        someMode.push_back(ir::conjunction(std::move(all)));
      }
      out_.properties.push_back(
          {"mode_agreement[" + m_.teams[t].name + "]", "", alwaysEventually(ir::disjunction(std::move(someMode))), true});
    }
  }
  if (wants("knowledge_convergence")) {
    for (const auto& [key, sites] : sites_) {
      const auto& [team, service] = key;
      const std::vector<Index>& robots = m_.teams[team].robots;
      for (const strategy::Knowledge& k : m_.strategy.services[sites.service].knowledge) {
        // Again and again, the live members working in the service hold the same facts: any two
        // of them hold as many. Equivalently, some count 0..|facts| is held by every one of them;
        // that form grows with the team, the pairs with its square, so a team of more than
        // 2 |facts| + 3 robots gets it (the swarms), a small one the pairs (fewer terms).
        const std::size_t facts = k.values.size();
        std::vector<Expr> same;
        if (robots.size() > 2 * facts + 3) {
          for (std::size_t count = 0; count <= facts; ++count) {
            std::vector<Expr> holds;
            for (Index r : robots) {
              holds.push_back(Expr::binary(Op::Implies, inService(r, service),
                                           Expr::binary(Op::Eq, Expr::var(vars_[r].knows.at(k.name)), Expr::constant(static_cast<std::int32_t>(count)))));
            }
            same.push_back(ir::conjunction(std::move(holds)));
          }
        } else {
          for (std::size_t i = 0; i < robots.size(); ++i) {
            for (std::size_t j = i + 1; j < robots.size(); ++j) {
              same.push_back(Expr::binary(Op::Implies, ir::conjunction({inService(robots[i], service), inService(robots[j], service)}),
                                          Expr::binary(Op::Eq, Expr::var(vars_[robots[i]].knows.at(k.name)),
                                                       Expr::var(vars_[robots[j]].knows.at(k.name)))));
            }
          }
        }
        Expr converged = robots.size() > 2 * facts + 3 ? ir::disjunction(std::move(same)) : ir::conjunction(std::move(same));
        out_.properties.push_back({"knowledge_convergence[" + service + "." + k.name + "]", "", alwaysEventually(std::move(converged))});
      }
    }
  }
  if (wants("leader_reelection")) {
    for (Index b : leaderBlocks_) {
      // Whenever live candidates work in the block (inside an arm) with no live leader, a live
      // leader comes, or no candidate is left inside.
      std::vector<Expr> waiting;
      Index team = m_.groupBlocks[b].team;
      for (Index c : candidates(b)) {
        for (std::size_t p = 0; p < programs_[team].size(); ++p) {
          if (!vars_[c].pc[p]) continue;
          for (const BlockRange& range : programs_[team][p].blocks) {
            if (range.block != b || range.armFirst.empty()) continue;
            Expr pc = Expr::var(*vars_[c].pc[p]);
            waiting.push_back(ir::conjunction({alive(c), Expr::binary(Op::Ge, pc, Expr::constant(static_cast<std::int32_t>(range.armFirst.front()))),
                                               Expr::binary(Op::Lt, pc, Expr::constant(static_cast<std::int32_t>(range.last)))}));
          }
        }
      }
      Expr someoneWaits = ir::disjunction(std::move(waiting));
      L trigger = L::of(ir::conjunction({noLeader(b), someoneWaits}));
      L answer = L::of(Expr::binary(Op::Or, lnot(noLeader(b)), lnot(someoneWaits)));
      out_.properties.push_back({"leader_reelection[" + m_.services[m_.groupBlocks[b].service].name + "]",
                                 origin(m_.groupBlocks[b].at, "").text(),
                                 L::unary(L::Kind::Always, L::binary(L::Kind::Implies, std::move(trigger),
                                                                     L::unary(L::Kind::Eventually, std::move(answer))))});
    }
  }
}

}  // namespace semo::detail
