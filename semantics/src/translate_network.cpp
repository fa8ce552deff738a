// Rules outside the robots' programs: event and message delivery and loss, crashes, leader
// re-election, default mode transitions; then the properties, and the entry point.
#include <algorithm>

#include "translator.hpp"

namespace semo::detail {

Expr Translator::inService(Index robot, const std::string& service) const {
  std::vector<Expr> at;
  auto it = sites_.find({m_.robots[robot].team, service});
  if (it == sites_.end()) return Expr::constant(0);
  for (const ServiceSite& s : it->second) {
    if (vars_[robot].pc[s.plan]) at.push_back(eq(Expr::var(*vars_[robot].pc[s.plan]), static_cast<std::int32_t>(s.instr)));
  }
  return ir::conjunction({alive(robot), ir::disjunction(std::move(at))});
}

// Gossip: a robot working in a group service learns the facts another member holds. With facts
// counted, the merge of q's c_q facts with r's c_r facts holds between max(c_q, c_r) and
// min(|facts|, c_q + c_r) facts: every such count is a possible outcome (one rule each). A lost
// gossip message is a merge that has not happened yet, so loss needs no rule of its own.
void Translator::knowledgeRules() {
  for (const auto& [key, sites] : sites_) {
    const auto& [team, service] = key;
    const strategy::Service& sv = *m_.strategy.service(service);
    for (Index q : m_.teams[team].robots) {
      for (Index r : m_.teams[team].robots) {
        if (q == r) continue;
        for (const strategy::Knowledge& k : sv.knowledge) {
          Expr mine = Expr::var(vars_[q].knows.at(k.name)), theirs = Expr::var(vars_[r].knows.at(k.name));
          for (std::int32_t n = 1; n <= static_cast<std::int32_t>(k.values.size()); ++n) {
            ir::Rule learn;
            learn.name = m_.robots[q].name + ".learns." + k.name + ".from." + m_.robots[r].name + "." + std::to_string(n);
            learn.robot = static_cast<std::int32_t>(q);
            learn.kind = ir::RuleKind::Delivery;
            learn.label = "learns " + k.name + " from " + m_.robots[r].name + " (now holds " + std::to_string(n) + ")";
            learn.guard = ir::conjunction({inService(q, service), inService(r, service),
                                           Expr::binary(Op::Lt, mine, Expr::constant(n)),
                                           Expr::binary(Op::Ge, Expr::constant(n), theirs),
                                           Expr::binary(Op::Le, Expr::constant(n), Expr::binary(Op::Add, mine, theirs))});
            learn.branches.push_back({1.0, {{vars_[q].knows.at(k.name), Expr::constant(n)}}});
            learn.weaklyFair = true;
            addRule(std::move(learn));
          }
        }
      }
    }
  }
}

void Translator::eventRules() {
  for (Index q = 0; q < m_.robots.size(); ++q) {
    Index team = m_.robots[q].team;
    const RobotVars& v = vars_[q];
    for (const auto& [e, var] : v.event) {
      const model::Event& event = m_.teams[team].events[e];
      // Delivery: the mode machine reacts if the current mode catches the event.
      ir::Rule deliver;
      deliver.name = m_.robots[q].name + ".deliver." + event.name;
      deliver.robot = static_cast<std::int32_t>(q);
      deliver.kind = ir::RuleKind::Delivery;
      deliver.label = "receives event " + event.name;
      deliver.origin = event.thrownAt.empty() ? "" : origin(event.thrownAt.front());
      deliver.guard = ir::conjunction({alive(q), Expr::var(var)});
      ir::Branch branch;
      branch.assignments.push_back({var, Expr::constant(0)});
      const std::vector<Index>& modes = m_.teams[team].modes;
      if (v.mode) {
        std::map<ir::VarId, Expr> values;  // the new value of each variable, built as ite over modes
        for (std::size_t k = 0; k < modes.size(); ++k) {
          for (const model::Transition& tr : m_.modes[modes[k]].transitions) {
            if (tr.isDefault || tr.event != e) continue;
            Expr inMode = eq(Expr::var(*v.mode), static_cast<std::int32_t>(k));
            for (ir::Assignment& a : enterMode(q, tr.target)) {
              auto it = values.find(a.var);
              Expr otherwise = it == values.end() ? Expr::var(a.var) : std::move(it->second);
              values[a.var] = Expr::ite(inMode, std::move(a.value), std::move(otherwise));
            }
          }
        }
        for (auto& [target, value] : values) branch.assignments.push_back({target, std::move(value)});
      }
      deliver.branches.push_back(std::move(branch));
      deliver.weaklyFair = true;
      addRule(std::move(deliver));
      if (loseEvents_ && event.delivery.reliable == false) {
        ir::Rule lose;
        lose.name = m_.robots[q].name + ".lose." + event.name;
        lose.robot = static_cast<std::int32_t>(q);
        lose.kind = ir::RuleKind::Loss;
        lose.label = "loses event " + event.name;
        lose.guard = ir::conjunction({alive(q), Expr::var(var)});
        lose.branches.push_back({1.0, {{var, Expr::constant(0)}}});
        addRule(std::move(lose));
      }
    }
  }
}

void Translator::messageRules() {
  for (Index q = 0; q < m_.robots.size(); ++q) {
    for (const auto& [tp, msg] : vars_[q].msg) {
      std::string topic = m_.teams[m_.topics[tp].owner].name + "." + m_.topics[tp].var;
      ir::Rule deliver;
      deliver.name = m_.robots[q].name + ".deliver." + topic;
      deliver.robot = static_cast<std::int32_t>(q);
      deliver.kind = ir::RuleKind::Delivery;
      deliver.label = "receives " + topic;
      deliver.guard = ir::conjunction({alive(q), Expr::binary(Op::Ne, Expr::var(msg), Expr::constant(0))});
      deliver.branches.push_back({1.0, {{vars_[q].view.at(tp), Expr::var(msg)}, {msg, Expr::constant(0)}}});
      deliver.weaklyFair = true;
      addRule(std::move(deliver));
      if (!losePublish_) continue;
      ir::Rule lose;
      lose.name = m_.robots[q].name + ".lose." + topic;
      lose.robot = static_cast<std::int32_t>(q);
      lose.kind = ir::RuleKind::Loss;
      lose.label = "loses " + topic;
      lose.guard = ir::conjunction({alive(q), Expr::binary(Op::Ne, Expr::var(msg), Expr::constant(0))});
      lose.branches.push_back({1.0, {{msg, Expr::constant(0)}}});
      addRule(std::move(lose));
    }
  }
}

void Translator::crashRules() {
  for (Index r = 0; r < m_.robots.size(); ++r) {
    Index team = m_.robots[r].team;
    if (!vars_[r].alive) continue;
    ir::VarId crashed = *crashed_[team];
    ir::Rule crash;
    crash.name = m_.robots[r].name + ".crash";
    crash.robot = static_cast<std::int32_t>(r);
    crash.kind = ir::RuleKind::Crash;
    crash.label = "crashes";
    crash.guard = ir::conjunction({Expr::var(*vars_[r].alive),
                                   Expr::binary(Op::Lt, Expr::var(crashed), Expr::constant(crashBudget(team)))});
    ir::Branch branch{1.0, {{*vars_[r].alive, Expr::constant(0)}, {crashed, Expr::binary(Op::Add, Expr::var(crashed), Expr::constant(1))}}};
    // A crashed robot's other variables are never read again (its rules are off, and properties
    // speak of live robots): clear them, so that where it crashed does not multiply the states.
    for (ir::VarId var = 0; var < out_.variables.size(); ++var) {
      const ir::Variable& v = out_.variables[var];
      if (v.robot == static_cast<std::int32_t>(r) && var != *vars_[r].alive) branch.assignments.push_back({var, Expr::constant(v.init)});
    }
    crash.branches.push_back(std::move(branch));
    addRule(std::move(crash));
  }
}

// The live candidate the block's algorithm prefers, or "none".
Expr Translator::bestCandidate(Index b) const {
  const model::GroupBlock& block = m_.groupBlocks[b];
  std::vector<Index> candidates;
  for (const model::GroupArm& arm : block.arms) {
    if (arm.kind == model::GroupArm::Kind::Leader) candidates = arm.candidates;
  }
  if (block.leader.algorithm == strategy::LeaderSelection::Algorithm::Bully) std::reverse(candidates.begin(), candidates.end());
  Expr best = Expr::constant(static_cast<std::int32_t>(m_.robots.size()));  // none
  for (auto it = candidates.rbegin(); it != candidates.rend(); ++it) {
    best = Expr::ite(alive(*it), Expr::constant(static_cast<std::int32_t>(*it)), std::move(best));
  }
  return best;
}

// The current leader if it is alive, else the best live candidate.
Expr Translator::electedLeader(Index b) const {
  ir::VarId leader = leader_.at(b);
  std::vector<Expr> valid;
  for (const model::GroupArm& arm : m_.groupBlocks[b].arms) {
    if (arm.kind != model::GroupArm::Kind::Leader) continue;
    for (Index c : arm.candidates) valid.push_back(ir::conjunction({eq(Expr::var(leader), static_cast<std::int32_t>(c)), alive(c)}));
  }
  return Expr::ite(ir::disjunction(std::move(valid)), Expr::var(leader), bestCandidate(b));
}

// A failed leader is replaced by the best live candidate still inside the block: it notices (the
// failure detector of the strategy's leader selection) and moves from `others` to the leader's part.
void Translator::leaderRules() {
  for (Index t = 0; t < programs_.size(); ++t) {
    for (std::size_t p = 0; p < programs_[t].size(); ++p) {
      for (const BlockRange& range : programs_[t][p].blocks) {
        const model::GroupBlock& block = m_.groupBlocks[range.block];
        if (!block.isLeaderBlock) continue;
        std::size_t leaderArm = 0, othersArm = SIZE_MAX;
        for (std::size_t a = 0; a < block.arms.size(); ++a) {
          if (block.arms[a].kind == model::GroupArm::Kind::Leader) leaderArm = a;
          if (block.arms[a].kind == model::GroupArm::Kind::Others) othersArm = a;
        }
        if (othersArm == SIZE_MAX) continue;
        ir::VarId leader = leader_.at(range.block);
        std::size_t leaderEntry = programs_[t][p].code[range.last].arms[leaderArm];
        for (Index c : block.arms[leaderArm].candidates) {
          if (!vars_[c].alive && !vars_[c].pc[p]) continue;
          bool anyCrash = false;
          for (Index r : m_.teams[t].robots) anyCrash = anyCrash || vars_[r].alive.has_value();
          if (!anyCrash || !vars_[c].pc[p]) continue;
          Expr pc = Expr::var(*vars_[c].pc[p]);
          ir::Rule take;
          take.name = m_.robots[c].name + ".takes_over." + std::to_string(range.first);
          take.robot = static_cast<std::int32_t>(c);
          take.label = "notices the leader failed and takes over as leader";
          take.origin = origin(block.arms[leaderArm].at);
          take.guard = ir::conjunction({alive(c),
                                        Expr::binary(Op::Ge, pc, Expr::constant(static_cast<std::int32_t>(range.armFirst[othersArm]))),
                                        Expr::binary(Op::Lt, pc, Expr::constant(static_cast<std::int32_t>(range.armEnd(othersArm)))),
                                        eq(electedLeader(range.block), static_cast<std::int32_t>(c)),
                                        Expr::binary(Op::Ne, Expr::var(leader), Expr::constant(static_cast<std::int32_t>(c)))});
          take.branches.push_back({1.0, {{leader, Expr::constant(static_cast<std::int32_t>(c))},
                                         {*vars_[c].pc[p], Expr::constant(static_cast<std::int32_t>(leaderEntry))}}});
          take.weaklyFair = true;
          addRule(std::move(take));
        }
      }
    }
  }
}

void Translator::defaultRules() {
  for (Index r = 0; r < m_.robots.size(); ++r) {
    const RobotVars& v = vars_[r];
    Index team = m_.robots[r].team;
    const std::vector<Index>& modes = m_.teams[team].modes;
    for (std::size_t k = 0; k < modes.size(); ++k) {
      for (const model::Transition& tr : m_.modes[modes[k]].transitions) {
        if (!tr.isDefault) continue;
        ir::Rule rule;
        rule.name = m_.robots[r].name + ".default." + m_.modes[modes[k]].name;
        rule.robot = static_cast<std::int32_t>(r);
        rule.label = "finished mode " + m_.modes[modes[k]].name + ": mode " + m_.modes[tr.target].name;
        rule.origin = origin(tr.at);
        std::vector<Expr> guard{alive(r)};
        if (v.mode) guard.push_back(eq(Expr::var(*v.mode), static_cast<std::int32_t>(k)));
        for (const std::optional<ir::VarId>& pc : v.pc) {
          if (pc) guard.push_back(eq(Expr::var(*pc), 0));
        }
        rule.guard = ir::conjunction(std::move(guard));
        rule.branches.push_back({1.0, enterMode(r, tr.target)});
        rule.weaklyFair = true;
        if (!rule.branches.front().assignments.empty()) addRule(std::move(rule));
      }
    }
  }
}

// A property formula without temporal operators as an expression over the state, or nullopt.
std::optional<Expr> Translator::stateFormula(const model::Ltl& f) const {
  using K = model::Ltl::Kind;
  switch (f.kind) {
    case K::Always: case K::Eventually: case K::Next: case K::Until: return std::nullopt;
    case K::Not: {
      auto a = stateFormula(*f.left);
      return a ? std::optional<Expr>(lnot(std::move(*a))) : std::nullopt;
    }
    case K::And: case K::Or: case K::Implies: {
      auto a = stateFormula(*f.left), b = stateFormula(*f.right);
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
        for (const auto& [b, var] : leader_) leads.push_back(eq(Expr::var(var), static_cast<std::int32_t>(r)));
        atom = ir::disjunction(std::move(leads));
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
        if (f.valueKind != model::ValueKind::Topic || !f.op) return std::nullopt;
        Index tp = m_.findTopic(m_.robots[r].team, f.var);
        if (tp == model::kNone) tp = m_.findTopic(f.subject == model::Ltl::Subject::Team ? f.subjectIndex : m_.robots[r].team, f.var);
        auto view = tp == model::kNone ? v.view.end() : v.view.find(tp);
        if (view == v.view.end()) return std::nullopt;
        std::int32_t symbol = symbolValue(tp, f.rhs);
        if (symbol < 0 || (*f.op != model::RelOp::Eq && *f.op != model::RelOp::Ne)) return std::nullopt;
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
          for (const model::GroupArm& arm : block.arms) {
            if (arm.kind == model::GroupArm::Kind::Others) continue;
            std::vector<Expr> live;
            for (Index c : arm.candidates) live.push_back(alive(c));
            ir::Invariant inv;
            std::string what = arm.kind == model::GroupArm::Kind::Leader ? "leader" : "group";
            inv.name = "group_formation[" + m_.services[block.service].name + " " + what + " (" + arm.names.front() +
                       (arm.names.size() > 1 ? ", ..." : "") + ")]";
            inv.origin = origin(arm.at);
            inv.holds = Expr::binary(Op::Implies, ir::disjunction(inside), ir::disjunction(std::move(live)));
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
      inv.origin = origin(m_.topics[tp].firstUse);
      inv.holds = Expr::binary(Op::Le, Expr::var(ch), Expr::constant(static_cast<std::int32_t>(m_.topics[tp].buffer)));
      out_.invariants.push_back(std::move(inv));
    }
  }
  if (wants("deadlock_freedom")) {
    std::vector<Expr> finished;
    for (Index r = 0; r < m_.robots.size(); ++r) {
      std::vector<Expr> done;
      for (const std::optional<ir::VarId>& pc : vars_[r].pc) {
        if (pc) done.push_back(eq(Expr::var(*pc), 0));
      }
      if (done.empty()) continue;
      finished.push_back(Expr::binary(Op::Or, lnot(alive(r)), ir::conjunction(std::move(done))));
    }
    out_.validEnd = ir::conjunction(std::move(finished));
  }
  for (const model::Property& p : m_.properties) {
    // `always p` with p free of temporal operators is an invariant; the rest needs the LTL engine.
    std::optional<Expr> holds;
    if (p.formula->kind == model::Ltl::Kind::Always) holds = stateFormula(*p.formula->left);
    if (!holds) {
      diags_.warning(p.at, "property '" + p.name + "' is not checked by 'check': only 'always' over modes, alive, "
                           "leaders and topics is a safety invariant; the rest needs the LTL engine");
      continue;
    }
    out_.invariants.push_back({p.name, origin(p.at), std::move(*holds)});
  }
  if (wants("unique_leader") && !leader_.empty()) {
    diags_.warning({}, "unique_leader is not checked yet: the distributed leader election (heartbeats, timeouts, "
                       "per-robot beliefs) is not translated; see specs/semantics.md");
  }
}

std::optional<ir::Model> Translator::run() {
  assumptions();
  variables();
  for (Index r = 0; r < m_.robots.size(); ++r) {
    for (std::size_t p = 0; p < vars_[r].pc.size(); ++p) {
      rulesPerPoint_ = 0;
      if (vars_[r].pc[p]) programRules(r, p);
    }
  }
  knowledgeRules();
  eventRules();
  messageRules();
  crashRules();
  leaderRules();
  defaultRules();
  invariants();
  return std::move(out_);
}

}  // namespace semo::detail

namespace semo {

std::optional<ir::Model> translate(const model::MissionModel& mission, const TranslationOptions& options,
                                   const SourceManager& sources, DiagnosticEngine& diags) {
  return detail::Translator(mission, options, sources, diags).run();
}

}  // namespace semo
