// Rules outside the robots' programs: event and message delivery and loss, crashes, leader
// re-election, default mode transitions; and the entry point (the properties:
// translate_properties.cpp).
#include <algorithm>

#include "translator.hpp"

namespace semo::detail {

Expr Translator::inService(Index robot, const std::string& service) const {
  std::vector<Expr> at;
  auto it = sites_.find({m_.robots[robot].team, service});
  if (it == sites_.end()) return Expr::constant(0);
  for (const ServiceSite& s : it->second.at) {
    if (vars_[robot].pc[s.plan]) at.push_back(eq(Expr::var(*vars_[robot].pc[s.plan]), static_cast<std::int32_t>(s.instr)));
  }
  return ir::conjunction({alive(robot), ir::disjunction(std::move(at))});
}

// Gossip: a robot working in a group service learns the facts another live robot of its team holds. With facts
// counted, the merge of q's c_q facts with r's c_r facts holds between max(c_q, c_r) and
// min(|facts|, c_q + c_r) facts: every such count is a possible outcome. One rule per learner and
// count reached, enabled when some live teammate can teach it that (a large team reads the counts
// of robots holding each number of facts, translate_counts.cpp). Weak fairness per rule means the
// same as per teacher: counts never decrease but by a crash, so within a cycle of states every
// teacher's merge is enabled exactly when the learner works in the service. A lost gossip
// message is a merge that has not happened yet, so loss needs no rule of its own.
void Translator::knowledgeRules() {
  for (const auto& [key, sites] : sites_) {
    const auto& [team, service] = key;
    const strategy::Service& sv = m_.strategy.services[sites.service];
    if (sv.dissemination && sv.dissemination->via == "none") continue;  // nothing is shared: nothing is learnt
    for (Index q : m_.teams[team].robots) {
      for (const strategy::Knowledge& k : sv.knowledge) {
        Expr mine = Expr::var(vars_[q].knows.at(k.name));
        for (std::int32_t n = 1; n <= static_cast<std::int32_t>(k.values.size()); ++n) {
          std::vector<Expr> teachers;
          if (counted(team)) {  // some other live robot holds c facts, with c <= n <= mine + c
            for (std::int32_t c = 1; c <= n; ++c) {
              Expr others = othersCounted(teamCount(team, VariableRole::Kind::Holding, 0, k.name, {c}), q, mine);
              Expr some = Expr::binary(Op::Gt, std::move(others), Expr::constant(0));
              teachers.push_back(c == n ? std::move(some)
                                        : ir::conjunction({Expr::binary(Op::Ge, Expr::binary(Op::Add, mine, Expr::constant(c)), Expr::constant(n)),
                                                           std::move(some)}));
            }
          } else {
            for (Index r : m_.teams[team].robots) {
              if (r == q) continue;
              Expr theirs = Expr::var(vars_[r].knows.at(k.name));
              teachers.push_back(ir::conjunction({alive(r), Expr::binary(Op::Ge, Expr::constant(n), theirs),
                                                  Expr::binary(Op::Le, Expr::constant(n), Expr::binary(Op::Add, mine, theirs))}));
            }
          }
          ir::Rule learn;
          learn.name = m_.robots[q].name + ".learns." + k.name + "." + std::to_string(n);
          learn.robot = static_cast<std::int32_t>(q);
          learn.kind = ir::RuleKind::Delivery;
          learn.label = "learns " + k.name + " from a teammate (now holds " + std::to_string(n) + ")";
          // The teacher need not be working in the service any more: a robot keeps answering
          // gossip about what it knows after its own part of the service is over.
          learn.guard = ir::conjunction({inService(q, service), Expr::binary(Op::Lt, mine, Expr::constant(n)),
                                         ir::disjunction(std::move(teachers))});
          learn.branches.push_back({1.0, {{vars_[q].knows.at(k.name), Expr::constant(n)}}});
          // Under unfair loss every broadcast gossip message may be lost: a merge may never
          // happen. Reliable dissemination resends until acknowledged.
          bool reliable = sv.dissemination && sv.dissemination->via == "reliable";
          learn.weaklyFair = !loseKnowledge_ || fairLoss_ || reliable;
          learn.origin = origin(sv.dissemination ? sv.dissemination->at : sv.at, "dissemination");
          RuleMeaning meaning;
          meaning.kind = RuleMeaning::Kind::Learn;
          meaning.robot = q;
          meaning.service = sv.name;
          meaning.knowledge = k.name;
          meaning.count = n;
          addRule(std::move(learn), std::move(meaning));
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
      deliver.origin = origin(event.thrownAt.empty() ? SourceRange{} : event.thrownAt.front(), "event");
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
      // Fair loss: a loss rule competes with delivery, so only strong fairness makes delivery win
      // in the end.
      deliver.stronglyFair = loseEvents_ && !event.delivery.reliable && fairLoss_;
      RuleMeaning meaning;
      meaning.kind = RuleMeaning::Kind::EventDelivery;
      meaning.robot = q;
      meaning.index = e;
      addRule(std::move(deliver), meaning);
      if (loseEvents_ && !event.delivery.reliable) {
        ir::Rule lose = robotRule("lose." + event.name, q, ir::RuleKind::Loss, "loses event " + event.name,
                                  ir::conjunction({alive(q), Expr::var(var)}), {{var, Expr::constant(0)}});
        lose.origin = origin(event.thrownAt.empty() ? SourceRange{} : event.thrownAt.front(), "event");
        meaning.kind = RuleMeaning::Kind::EventLoss;
        addRule(std::move(lose), meaning);
      }
    }
  }
}

ir::Rule Translator::robotRule(const std::string& what, Index robot, ir::RuleKind kind, std::string label, Expr guard,
                               std::vector<ir::Assignment> updates) const {
  ir::Rule rule;
  rule.name = m_.robots[robot].name + "." + what;
  rule.robot = static_cast<std::int32_t>(robot);
  rule.kind = kind;
  rule.label = std::move(label);
  rule.guard = std::move(guard);
  rule.branches.push_back({1.0, std::move(updates)});
  return rule;
}

void Translator::messageRules() {
  for (Index q = 0; q < m_.robots.size(); ++q) {
    for (const auto& [tp, msg] : vars_[q].msg) {
      std::string topic = m_.teams[m_.topics[tp].owner].name + "." + m_.topics[tp].var;
      Expr pending = ir::conjunction({alive(q), Expr::binary(Op::Ne, Expr::var(msg), Expr::constant(0))});
      ir::Rule deliver = robotRule("deliver." + topic, q, ir::RuleKind::Delivery, "receives " + topic, pending,
                                   {{vars_[q].view.at(tp), Expr::var(msg)}, {msg, Expr::constant(0)}});
      deliver.weaklyFair = true;
      deliver.stronglyFair = losePublish_ && fairLoss_;
      deliver.origin.construct = "topic";  // no position: the value may come from any publish
      RuleMeaning meaning;
      meaning.kind = RuleMeaning::Kind::MessageDelivery;
      meaning.robot = q;
      meaning.index = tp;
      addRule(std::move(deliver), meaning);
      if (losePublish_) {
        ir::Rule lose = robotRule("lose." + topic, q, ir::RuleKind::Loss, "loses " + topic, std::move(pending), {{msg, Expr::constant(0)}});
        lose.origin.construct = "topic";
        meaning.kind = RuleMeaning::Kind::MessageLoss;
        addRule(std::move(lose), meaning);
      }
    }
  }
}

void Translator::crashRules() {
  std::vector<std::vector<ir::VarId>> own(m_.robots.size());  // each robot's variables
  for (ir::VarId var = 0; var < out_.variables.size(); ++var) {
    if (out_.variables[var].robot != ir::kNoRobot) own[static_cast<std::size_t>(out_.variables[var].robot)].push_back(var);
  }
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
    for (ir::VarId var : own[r]) {
      if (var != *vars_[r].alive) branch.assignments.push_back({var, Expr::constant(out_.variables[var].init)});
    }
    crash.branches.push_back(std::move(branch));
    crash.origin.construct = "crash";  // no position: a crash can happen anywhere
    RuleMeaning meaning;
    meaning.kind = RuleMeaning::Kind::Crash;
    meaning.robot = r;
    addRule(std::move(crash), std::move(meaning));
  }
}

const std::vector<Index>& Translator::candidates(Index b) const {
  for (const model::GroupArm& arm : m_.groupBlocks[b].arms) {
    if (arm.kind == model::GroupArm::Kind::Leader) return arm.candidates;
  }
  static const std::vector<Index> none;
  return none;
}

// How many heartbeat periods a robot waits before it suspects the leader (at least one).
std::int32_t Translator::timeoutPeriods(Index b) const {
  const model::LeaderConfig& c = m_.groupBlocks[b].leader;
  return static_cast<std::int32_t>(std::max<std::int64_t>(1, c.timeoutMillis / std::max<std::int64_t>(1, c.heartbeatMillis)));
}

// The candidates of block b, most preferred first (bully: highest index; lowest-id: lowest).
std::vector<Index> Translator::preferenceOrder(Index b) const {
  std::vector<Index> order = candidates(b);
  if (m_.groupBlocks[b].leader.algorithm == strategy::LeaderSelection::Algorithm::Bully) std::reverse(order.begin(), order.end());
  return order;
}

// The live candidate the block's algorithm prefers among those forming the block now (resting at
// its formation point `formPoint` of plan `planIndex`), or "none" (the number of robots). A robot
// still elsewhere is no member yet: electing it would make a leader that is not there.
Expr Translator::bestFormingCandidate(Index b, std::size_t planIndex, std::size_t formPoint) const {
  std::vector<Index> order = preferenceOrder(b);
  Expr best = Expr::constant(static_cast<std::int32_t>(m_.robots.size()));
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const std::optional<ir::VarId>& pc = vars_[*it].pc[planIndex];
    if (!pc) continue;
    Expr forming = ir::conjunction({alive(*it), eq(Expr::var(*pc), static_cast<std::int32_t>(formPoint))});
    best = Expr::ite(std::move(forming), Expr::constant(static_cast<std::int32_t>(*it)), std::move(best));
  }
  return best;
}

Expr Translator::noLeader(Index b) const {
  std::vector<Expr> leading;
  for (Index c : candidates(b)) leading.push_back(ir::conjunction({alive(c), Expr::var(vars_[c].leads.at(b))}));
  return lnot(ir::disjunction(std::move(leading)));
}

// A live candidate in the `others` part of the block, where it listens for the leader's heartbeats.
Expr Translator::waitingForHeartbeats(Index robot, Index b) const {
  Index team = m_.robots[robot].team;
  std::vector<Expr> inOthers;
  for (std::size_t p = 0; p < programs_[team].size(); ++p) {
    if (!vars_[robot].pc[p]) continue;
    for (const BlockRange& range : programs_[team][p].blocks) {
      if (range.block != b) continue;
      const model::GroupBlock& block = m_.groupBlocks[b];
      for (std::size_t a = 0; a < block.arms.size(); ++a) {
        if (block.arms[a].kind != model::GroupArm::Kind::Others) continue;
        Expr pc = Expr::var(*vars_[robot].pc[p]);
        inOthers.push_back(ir::conjunction({Expr::binary(Op::Ge, pc, Expr::constant(static_cast<std::int32_t>(range.armFirst[a]))),
                                            Expr::binary(Op::Lt, pc, Expr::constant(static_cast<std::int32_t>(range.armEnd(a))))}));
      }
    }
  }
  return ir::conjunction({alive(robot), lnot(Expr::var(vars_[robot].leads.at(b))), ir::disjunction(std::move(inOthers))});
}

// A candidate that heard no heartbeat for the failure timeout.
Expr Translator::suspects(Index robot, Index b) const {
  return Expr::binary(Op::Ge, Expr::var(vars_[robot].silence.at(b)), Expr::constant(timeoutPeriods(b)));
}

// One heartbeat period of a leader block (specs/semantics.md, "Leaders"): every live leader sends a
// heartbeat; each waiting candidate hears one unless it is lost (at most `burst` in a row); one that
// hears nothing counts a silent period. A leader that hears a better leader steps down. One rule per
// set of candidates whose heartbeat is lost.
void Translator::roundRules(Index b) {
  const std::vector<Index>& cands = candidates(b);
  if (cands.empty() || !vars_[cands.front()].silence.count(b)) return;
  std::int32_t k = timeoutPeriods(b);
  auto burst = static_cast<std::int32_t>(m_.assumptions.lossBurst);
  std::vector<Index> order = preferenceOrder(b);
  std::size_t subsets = loseHeartbeats_ ? (std::size_t{1} << cands.size()) : 1;
  std::vector<Expr> anyWaiting;
  for (Index c : cands) anyWaiting.push_back(waitingForHeartbeats(c, b));
  for (std::size_t lost = 0; lost < subsets; ++lost) {
    ir::Rule round;
    round.name = "heartbeat." + std::to_string(b) + "." + std::to_string(lost);
    round.kind = ir::RuleKind::Timer;
    round.origin = origin(m_.groupBlocks[b].at, "leader block");
    RuleMeaning meaning;
    meaning.kind = RuleMeaning::Kind::HeartbeatPeriod;
    meaning.index = b;
    std::vector<Expr> guard{ir::disjunction(anyWaiting)};
    std::vector<ir::Assignment> updates;
    std::string lostNames;
    for (std::size_t i = 0; i < cands.size(); ++i) {
      Index c = cands[i];
      const RobotVars& v = vars_[c];
      Expr silence = Expr::var(v.silence.at(b));
      Expr waiting = waitingForHeartbeats(c, b);
      Expr louder = Expr::binary(Op::Min, Expr::binary(Op::Add, silence, Expr::constant(1)), Expr::constant(k));
      std::vector<Expr> others;
      for (Index d : cands) {
        if (d != c) others.push_back(ir::conjunction({alive(d), Expr::var(vars_[d].leads.at(b))}));
      }
      Expr heard = ir::disjunction(std::move(others));
      bool isLost = (lost >> i) & 1u;
      if (isLost) {
        lostNames += (lostNames.empty() ? "" : ", ") + m_.robots[c].name;
        meaning.lostTo.push_back(c);
        guard.push_back(waiting);
        guard.push_back(heard);  // a heartbeat that was never sent cannot be lost
        guard.push_back(Expr::binary(Op::Lt, Expr::var(v.lossRun.at(b)), Expr::constant(burst)));
        updates.push_back({v.silence.at(b), louder});
        updates.push_back({v.lossRun.at(b), Expr::binary(Op::Add, Expr::var(v.lossRun.at(b)), Expr::constant(1))});
        continue;
      }
      updates.push_back({v.silence.at(b), Expr::ite(waiting, Expr::ite(heard, Expr::constant(0), louder), Expr::constant(0))});
      if (v.lossRun.count(b)) updates.push_back({v.lossRun.at(b), Expr::ite(heard, Expr::constant(0), Expr::var(v.lossRun.at(b)))});
      // Bully: a leader that hears a more preferred leader steps down.
      std::vector<Expr> better;
      for (Index d : order) {
        if (d == c) break;
        better.push_back(ir::conjunction({alive(d), Expr::var(vars_[d].leads.at(b))}));
      }
      if (!better.empty()) {
        ir::VarId leads = v.leads.at(b);
        updates.push_back({leads, ir::conjunction({Expr::var(leads), lnot(ir::disjunction(std::move(better)))})});
      }
    }
    round.label = lostNames.empty() ? "a heartbeat period passes" : "a heartbeat period passes; lost on the way to " + lostNames;
    round.guard = ir::conjunction(std::move(guard));
    round.branches.push_back({1.0, std::move(updates)});
    round.weaklyFair = lostNames.empty();
    round.stronglyFair = lostNames.empty() && loseHeartbeats_ && fairLoss_;
    addRule(std::move(round), std::move(meaning));
  }
}

// A candidate that heard no heartbeat for the failure timeout suspects the leader and takes over
// (moving from `others` to the leader's part of the block).
void Translator::leaderRules() {
  for (Index b : leaderBlocks_) {
    roundRules(b);
    const model::GroupBlock& block = m_.groupBlocks[b];
    Index t = block.team;
    std::size_t leaderArm = 0, othersArm = SIZE_MAX;
    for (std::size_t a = 0; a < block.arms.size(); ++a) {
      if (block.arms[a].kind == model::GroupArm::Kind::Leader) leaderArm = a;
      if (block.arms[a].kind == model::GroupArm::Kind::Others) othersArm = a;
    }
    if (othersArm == SIZE_MAX) continue;
    for (std::size_t p = 0; p < programs_[t].size(); ++p) {
      for (const BlockRange& range : programs_[t][p].blocks) {
        if (range.block != b) continue;
        std::size_t leaderEntry = programs_[t][p].code[range.last].arms[leaderArm];
        for (Index c : candidates(b)) {
          const RobotVars& v = vars_[c];
          if (!v.pc[p] || !v.silence.count(b)) continue;
          Expr pc = Expr::var(*v.pc[p]);
          ir::Rule take;
          take.name = m_.robots[c].name + ".takes_over." + std::to_string(range.first);
          take.robot = static_cast<std::int32_t>(c);
          take.label = "suspects the leader (no heartbeat for the failure timeout) and takes over";
          take.origin = origin(block.arms[leaderArm].at, "leader block");
          take.guard = ir::conjunction({alive(c), lnot(Expr::var(v.leads.at(b))),
                                        Expr::binary(Op::Ge, pc, Expr::constant(static_cast<std::int32_t>(range.armFirst[othersArm]))),
                                        Expr::binary(Op::Lt, pc, Expr::constant(static_cast<std::int32_t>(range.armEnd(othersArm)))),
                                        suspects(c, b)});
          std::vector<ir::Assignment> updates{{v.leads.at(b), Expr::constant(1)},
                                              {v.silence.at(b), Expr::constant(0)},
                                              {*v.pc[p], Expr::constant(static_cast<std::int32_t>(leaderEntry))}};
          if (v.lossRun.count(b)) updates.push_back({v.lossRun.at(b), Expr::constant(0)});
          if (!loseHeartbeats_) {  // the new leader's announcement, as when the block forms
            for (Index d : candidates(b)) {
              if (d != c && vars_[d].silence.count(b) != 0) updates.push_back({vars_[d].silence.at(b), Expr::constant(0)});
            }
          }
          take.branches.push_back({1.0, std::move(updates)});
          take.weaklyFair = true;
          RuleMeaning meaning;
          meaning.kind = RuleMeaning::Kind::Takeover;
          meaning.robot = c;
          meaning.index = b;
          meaning.plan = p;
          meaning.from = range.armFirst[othersArm];
          meaning.to = leaderEntry;
          addRule(std::move(take), std::move(meaning));
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
        rule.origin = origin(tr.at, "default");
        std::vector<Expr> guard{alive(r)};
        if (v.mode) guard.push_back(eq(Expr::var(*v.mode), static_cast<std::int32_t>(k)));
        for (const std::optional<ir::VarId>& pc : v.pc) {
          if (pc) guard.push_back(eq(Expr::var(*pc), 0));
        }
        rule.guard = ir::conjunction(std::move(guard));
        rule.branches.push_back({1.0, enterMode(r, tr.target)});
        rule.weaklyFair = true;
        RuleMeaning meaning;
        meaning.kind = RuleMeaning::Kind::ModeDefault;
        meaning.robot = r;
        meaning.mode = modes[k];
        meaning.target = tr.target;
        if (!rule.branches.front().assignments.empty()) addRule(std::move(rule), std::move(meaning));
      }
    }
  }
}

std::optional<Translation> Translator::run() {
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
  maintainCounts();
  lowering_.countDefinitions = countDefinitions();
  invariants();
  livenessProperties();
  lowering_.programs = programs_;
  return Translation{std::move(out_), std::move(lowering_)};
}

}  // namespace semo::detail

namespace semo {

std::optional<Translation> translateMission(const model::MissionModel& mission, const TranslationOptions& options,
                                            const SourceManager& sources, DiagnosticEngine& diags) {
  return detail::Translator(mission, options, sources, diags).run();
}

std::optional<ir::Model> translate(const model::MissionModel& mission, const TranslationOptions& options,
                                   const SourceManager& sources, DiagnosticEngine& diags) {
  std::optional<Translation> t = translateMission(mission, options, sources, diags);
  if (!t) return std::nullopt;
  return std::move(t->model);
}

}  // namespace semo
