// MissionModel -> IR (specs/semantics.md). Variables first, then one group of rules per concern:
// robots' programs, event delivery, message delivery, crashes, re-election, mode defaults.
#include "semo/semantics/translate.hpp"

#include <algorithm>

#include "translator.hpp"

namespace semo::detail {


ir::Origin Translator::origin(const SourceRange& r, std::string construct) const {
  ir::Origin o;
  o.construct = std::move(construct);
  if (!r.begin.valid() || r.begin.file >= sources_.fileCount()) return o;
  o.file = sources_.path(r.begin.file);
  o.line = r.begin.line;
  o.column = r.begin.column;
  return o;
}

// The mission construct a rule starting at `in` comes from, for its origin.
std::string Translator::constructOf(const Instr& in) {
  using K = model::Stmt::Kind;
  switch (in.kind) {
    case Instr::Kind::Done: return "service end";
    case Instr::Kind::Jump: return in.stmt != nullptr ? "loop" : "repeat";
    case Instr::Kind::Branch: return "if";
    case Instr::Kind::RepeatBranch: return "repeat";
    case Instr::Kind::Throw: return "throw";
    case Instr::Kind::Publish: return "publish";
    case Instr::Kind::Send: return "send";
    case Instr::Kind::Receive: return "receive";
    case Instr::Kind::Groups: return "group block";
    case Instr::Kind::GroupService: return "group service call";
    case Instr::Kind::BlockExit: return "group block end";
    case Instr::Kind::Local: break;
  }
  if (in.stmt == nullptr) return "statement";
  switch (in.stmt->kind) {
    case K::Wait: return "wait";
    case K::Subscribe: return "subscribe";
    default: return "call";
  }
}

std::int32_t Translator::crashBudget(Index team) const {
  if (auto it = options_.crashPerTeam.find(m_.teams[team].name); it != options_.crashPerTeam.end()) {
    return std::min<std::int32_t>(it->second, static_cast<std::int32_t>(m_.teams[team].robots.size()));
  }
  if (options_.crashOverride) {
    return std::min<std::int32_t>(*options_.crashOverride, static_cast<std::int32_t>(m_.teams[team].robots.size()));
  }
  return static_cast<std::int32_t>(m_.assumptions.crashBudget[team]);
}

void Translator::assumptions() {
  for (const auto& [name, budget] : options_.crashPerTeam) {
    if (m_.findTeam(name) != model::kNone) continue;
    std::string teams;
    for (const model::Team& t : m_.teams) teams += (teams.empty() ? "" : ", ") + t.name;
    diags_.error({}, "--crash " + std::to_string(budget) + ":" + name + ": the mission has no team '" + name + "' (its teams: " + teams + ")");
  }
  losePublish_ = m_.assumptions.losePublish;
  loseEvents_ = m_.assumptions.loseEvents;
  // --loss: one kind or a comma-separated list of them (`events,publish`).
  auto overridden = [this](const char* kind) {
    const std::string& list = *options_.lossOverride;
    for (std::size_t start = 0; start <= list.size();) {
      const std::size_t end = std::min(list.find(',', start), list.size());
      const std::string k = list.substr(start, end - start);
      if (k == kind || k == "all") return true;
      start = end + 1;
    }
    return false;
  };
  if (options_.lossOverride) {
    losePublish_ = overridden("publish");
    loseEvents_ = overridden("events");
    loseHeartbeats_ = overridden("heartbeats");
  } else {
    loseHeartbeats_ = m_.assumptions.loseHeartbeats;
  }
  for (Index t = 0; t < m_.teams.size(); ++t) {
    if (crashBudget(t) > 0) out_.assumptions.push_back("crash <= " + std::to_string(crashBudget(t)) + " in " + m_.teams[t].name);
  }
  if (out_.assumptions.empty()) out_.assumptions.push_back("no crash");
  std::string loss;
  if (losePublish_) loss += "publish";
  if (loseHeartbeats_) loss += std::string(loss.empty() ? "" : ", ") + "heartbeats (at most " +
                              std::to_string(m_.assumptions.lossBurst) + " in a row)";
  if (loseEvents_) loss += std::string(loss.empty() ? "" : ", ") + "events";
  // Knowledge gossip is modelled as merges that may happen late or never, so lost gossip is always covered.
  bool loseKnowledge = options_.lossOverride ? overridden("knowledge") : m_.assumptions.loseKnowledge;
  if (loseKnowledge) loss += std::string(loss.empty() ? "" : ", ") + "knowledge";
  loseKnowledge_ = loseKnowledge;
  fairLoss_ = options_.fairLossOverride.value_or(m_.assumptions.fairLoss);
  lowering::LoweredAssumptions& used = lowering_.assumptions;
  for (Index t = 0; t < m_.teams.size(); ++t) used.crashBudget.push_back(crashBudget(t));
  used.losePublish = losePublish_;
  used.loseEvents = loseEvents_;
  used.loseKnowledge = loseKnowledge_;
  used.loseHeartbeats = loseHeartbeats_;
  used.fairLoss = fairLoss_;
  used.lossBurst = m_.assumptions.lossBurst;
  if (!loss.empty()) loss += fairLoss_ ? " (fair: a message sent again and again gets through)" : " (unfair: may be lost for ever)";
  out_.assumptions.push_back("loss: " + (loss.empty() ? std::string("none") : loss));
  out_.assumptions.push_back("timing: any (asynchronous interleaving)");
}

ir::VarId Translator::addVar(std::string name, std::int32_t min, std::int32_t max, std::int32_t init, std::int32_t robot,
                             VariableRole role, std::vector<std::string> valueNames) {
  ir::Variable v;
  v.name = std::move(name);
  v.min = min;
  v.max = max;
  v.init = init;
  v.isBool = min == 0 && max == 1 && valueNames.empty();
  v.robot = robot;
  v.valueNames = std::move(valueNames);
  out_.variables.push_back(std::move(v));
  lowering_.variables.push_back(std::move(role));
  return static_cast<ir::VarId>(out_.variables.size() - 1);
}

Expr Translator::alive(Index robot) const {
  return vars_[robot].alive ? Expr::var(*vars_[robot].alive) : Expr::constant(1);
}

bool Translator::topicRead(Index team, Index topic) const {
  // A robot keeps a view of a topic only if its team's conditions read it (others cannot tell).
  std::vector<const std::vector<model::Stmt>*> bodies;
  for (Index s : m_.teams[team].services) bodies.push_back(&m_.services[s].body);
  std::function<bool(const model::Cond&)> reads = [&](const model::Cond& c) {
    for (const model::Expr* e : {&c.lhs, &c.rhs}) {
      if (e->kind == model::Expr::Kind::Value && e->valueKind == model::ValueKind::Topic && e->topic == topic) return true;
    }
    return (c.left && reads(*c.left)) || (c.right && reads(*c.right));
  };
  for (Index s : m_.teams[team].services) {
    if (m_.services[s].repeat && m_.services[s].repeat->cond && reads(*m_.services[s].repeat->cond)) return true;
  }
  while (!bodies.empty()) {
    const std::vector<model::Stmt>* body = bodies.back();
    bodies.pop_back();
    for (const model::Stmt& s : *body) {
      if (s.cond && reads(*s.cond)) return true;
      bodies.push_back(&s.thenBody);
      bodies.push_back(&s.elseBody);
      if (s.kind == model::Stmt::Kind::Groups) {
        for (const model::GroupArm& arm : m_.groupBlocks[s.groupBlock].arms) bodies.push_back(&arm.body);
      }
    }
  }
  return false;
}

void Translator::variables() {
  out_.robots.reserve(m_.robots.size());
  for (const model::Robot& r : m_.robots) out_.robots.push_back(r.name);
  programs_.resize(m_.teams.size());
  crashed_.resize(m_.teams.size());
  vars_.resize(m_.robots.size());
  for (Index t = 0; t < m_.teams.size(); ++t) {
    const model::Team& team = m_.teams[t];
    for (const std::string& plan : team.plans) programs_[t].push_back(lowering::buildProgram(m_, t, plan));
    if (crashBudget(t) > 0) {
      crashed_[t] = addVar(team.name + ".crashed", 0, crashBudget(t), 0, ir::kNoRobot, {VariableRole::Kind::Crashed, model::kNone, t});
      out_.variables.back().isBool = false;  // a count, even when the budget is 1
    }
    std::vector<std::string> modeNames;
    for (Index md : team.modes) modeNames.push_back(m_.modes[md].name);
    for (Index r : team.robots) {
      auto robot = static_cast<std::int32_t>(r);
      const std::string& name = m_.robots[r].name;
      RobotVars& v = vars_[r];
      if (crashBudget(t) > 0) v.alive = addVar(name + ".alive", 0, 1, 1, robot, {VariableRole::Kind::Alive, r, t});
      Index initial = team.initialMode;
      if (team.modes.size() > 1 && initial != model::kNone) {
        auto initialIndex = static_cast<std::int32_t>(std::find(team.modes.begin(), team.modes.end(), initial) - team.modes.begin());
        v.mode = addVar(name + ".mode", 0, static_cast<std::int32_t>(team.modes.size()) - 1, initialIndex, robot,
                        {VariableRole::Kind::Mode, r, t}, modeNames);
      }
      for (std::size_t p = 0; p < team.plans.size(); ++p) {
        const PlanProgram& prog = programs_[t][p];
        std::size_t entry = 0;
        if (initial != model::kNone) {
          for (const model::PlanSetting& s : m_.modes[initial].settings) {
            if (s.plan == p) entry = prog.entryOf[s.service];
          }
        }
        if (prog.code.size() == 1) {
          v.pc.emplace_back();
          continue;
        }
        std::vector<std::string> labels;
        for (std::size_t i = 0; i < prog.code.size(); ++i) {
          const Instr& in = prog.code[i];
          // One word per value (the IR's @values): service, instruction, and the mission line:col.
          // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "@" + to_string(...).
          std::string label = i == 0 ? std::string("done") : m_.services[in.service].name;
          if (i != 0) {
            label += '#';
            label += std::to_string(i);
          }
          if (i != 0 && in.stmt != nullptr) {
            label += '@';
            label += std::to_string(in.stmt->at.begin.line);
            label += ':';
            label += std::to_string(in.stmt->at.begin.column);
          }
          labels.push_back(std::move(label));
        }
        v.pc.push_back(addVar(name + ".pc." + team.plans[p], 0, static_cast<std::int32_t>(prog.code.size()) - 1,
                              static_cast<std::int32_t>(entry), robot, {VariableRole::Kind::Pc, r, t, static_cast<Index>(p)},
                              std::move(labels)));
      }
      for (std::size_t p = 0; p < team.plans.size(); ++p) {
        const PlanProgram& prog = programs_[t][p];
        for (std::size_t i = 0; i < prog.code.size(); ++i) {
          if (prog.code[i].kind != Instr::Kind::GroupService) continue;
          const std::string& service = prog.code[i].stmt->service;
          if (r == team.robots.front()) {
            ServiceSites& sites = sites_[{t, service}];
            sites.service = prog.code[i].stmt->strategyService;
            sites.at.push_back({p, i});
          }
          const strategy::Service* sv = &m_.serviceOf(*prog.code[i].stmt);
          for (const strategy::Knowledge& k : sv->knowledge) {
            if (v.knows.count(k.name) != 0) continue;
            v.knows[k.name] = addVar(name + ".knows." + k.name, 0, static_cast<std::int32_t>(k.values.size()), 0, robot,
                                     {VariableRole::Kind::Knows, r, t, model::kNone, k.name});
            out_.variables.back().isBool = false;
            out_.variables.back().facts = k.values;
          }
        }
      }
      for (Index e = 0; e < team.events.size(); ++e) {
        if (!team.events[e].thrownAt.empty() && !team.events[e].caughtAt.empty() && team.robots.size() > 1) {
          v.event[e] = addVar(name + ".ev." + team.events[e].name, 0, 1, 0, robot, {VariableRole::Kind::Event, r, t, e});
        }
      }
    }
  }
  for (Index tp = 0; tp < m_.topics.size(); ++tp) {
    const model::Topic& topic = m_.topics[tp];
    std::string topicName = m_.teams[topic.owner].name + "." + topic.var;
    if (topic.reliable) {
      channel_[tp] = addVar("ch." + topicName, 0, static_cast<std::int32_t>(topic.buffer) + 1, 0, ir::kNoRobot,
                            {VariableRole::Kind::Channel, model::kNone, topic.owner, tp});
      continue;
    }
    std::vector<std::string> names{"none"};
    for (const std::string& s : topic.symbols) names.push_back(s);
    if (names.size() == 1) names.push_back("some");
    for (Index t = 0; t < m_.teams.size(); ++t) {
      if (!topicRead(t, tp)) continue;
      for (Index r : m_.teams[t].robots) {
        auto robot = static_cast<std::int32_t>(r);
        auto top = static_cast<std::int32_t>(names.size()) - 1;
        vars_[r].view[tp] = addVar(m_.robots[r].name + ".view." + topicName, 0, top, 0, robot, {VariableRole::Kind::View, r, t, tp}, names);
        vars_[r].msg[tp] = addVar(m_.robots[r].name + ".msg." + topicName, 0, top, 0, robot, {VariableRole::Kind::Message, r, t, tp}, names);
      }
    }
  }
  for (Index b = 0; b < m_.groupBlocks.size(); ++b) {
    if (!m_.groupBlocks[b].isLeaderBlock) continue;
    leaderBlocks_.push_back(b);
    Index team = m_.groupBlocks[b].team;
    std::string tag = m_.services[m_.groupBlocks[b].service].name + "." + std::to_string(b);
    // Failure detection only matters when a leader can fail or its heartbeats can be lost (and is
    // absent when the strategy re-elects only when the group forms).
    bool detect = m_.groupBlocks[b].leader.detectsFailures && (crashBudget(team) > 0 || loseHeartbeats_);
    for (Index c : candidates(b)) {
      auto robot = static_cast<std::int32_t>(c);
      const std::string& name = m_.robots[c].name;
      vars_[c].leads[b] = addVar(name + ".leads." + tag, 0, 1, 0, robot, {VariableRole::Kind::Leads, c, team, b});
      if (detect) {
        vars_[c].silence[b] = addVar(name + ".silence." + tag, 0, timeoutPeriods(b), 0, robot, {VariableRole::Kind::Silence, c, team, b});
        out_.variables.back().isBool = false;
      }
      if (detect && loseHeartbeats_) {
        vars_[c].lossRun[b] = addVar(name + ".lost." + tag, 0, static_cast<std::int32_t>(m_.assumptions.lossBurst), 0, robot,
                                     {VariableRole::Kind::LostHeartbeats, c, team, b});
        out_.variables.back().isBool = false;
      }
    }
  }
}

std::vector<Index> Translator::modesRunning(Index team, std::size_t planIndex, Index service) const {
  std::vector<Index> modes;
  for (Index md : m_.teams[team].modes) {
    for (const model::PlanSetting& s : m_.modes[md].settings) {
      if (s.plan == planIndex && s.service == service) modes.push_back(md);
    }
  }
  return modes;
}

std::vector<ir::Assignment> Translator::enterMode(Index robot, Index mode) const {
  Index team = m_.robots[robot].team;
  std::vector<ir::Assignment> out;
  const RobotVars& v = vars_[robot];
  if (v.mode) {
    const std::vector<Index>& modes = m_.teams[team].modes;
    auto index = static_cast<std::int32_t>(std::find(modes.begin(), modes.end(), mode) - modes.begin());
    out.push_back({*v.mode, Expr::constant(index)});
  }
  for (std::size_t p = 0; p < v.pc.size(); ++p) {
    if (!v.pc[p]) continue;
    std::size_t entry = 0;
    for (const model::PlanSetting& s : m_.modes[mode].settings) {
      if (s.plan == p) entry = programs_[team][p].entryOf[s.service];
    }
    out.push_back({*v.pc[p], Expr::constant(static_cast<std::int32_t>(entry))});
  }
  // Its services restart, so it has left every group block: a leader stops leading (and sending
  // heartbeats) and the others may take over, unless it keeps the leadership (MissionModel::keepsLeadership):
  // then its `leads` passes the election when it is back at the formation point.
  for (const auto& [block, leads] : v.leads) {
    if (!m_.keepsLeadership(block, mode)) out.push_back({leads, Expr::constant(0)});
  }
  return out;
}

void Translator::programRules(Index robot, std::size_t planIndex) {
  const PlanProgram& prog = programs_[m_.robots[robot].team][planIndex];
  for (std::size_t i = 1; i < prog.code.size(); ++i) {
    if (prog.code[i].kind == Instr::Kind::GroupService) {
      groupServiceRules(robot, planIndex, i);
    } else if (prog.code[i].kind == Instr::Kind::BlockExit) {
      blockExitRules(robot, planIndex, i);
    } else if (prog.code[i].controlPoint) {
      walk(robot, planIndex, i, Path{}, i, 0);
    }
  }
}

void Translator::finish(Index robot, std::size_t planIndex, std::size_t start, std::size_t target, Path path) {
  const RobotVars& v = vars_[robot];
  ir::Rule rule;
  rule.robot = static_cast<std::int32_t>(robot);
  rule.kind = ir::RuleKind::Step;
  const PlanProgram& prog = programs_[m_.robots[robot].team][planIndex];
  rule.name = m_.robots[robot].name + "." + prog.plan + "." + std::to_string(start) + "." + std::to_string(++rulesPerPoint_);
  const Instr& first = prog.code[start];
  rule.origin = origin(first.stmt != nullptr ? first.stmt->at : SourceRange{}, constructOf(first));
  std::vector<Expr> guard{alive(robot), eq(Expr::var(*v.pc[planIndex]), static_cast<std::int32_t>(start))};
  for (Expr& g : path.guard) guard.push_back(std::move(g));
  rule.guard = ir::conjunction(std::move(guard));
  ir::Branch branch;
  // One assignment per variable: a later one in the walk (a mode change after leaving a block,
  // which both clear `leads`) overrides an earlier one.
  for (ir::Assignment& a : path.updates) {
    auto same = std::find_if(branch.assignments.begin(), branch.assignments.end(), [&](const ir::Assignment& b) { return b.var == a.var; });
    if (same != branch.assignments.end()) *same = std::move(a);
    else branch.assignments.push_back(std::move(a));
  }
  if (!path.changesMode && target != start) {
    branch.assignments.push_back({*v.pc[planIndex], Expr::constant(static_cast<std::int32_t>(target))});
  }
  RuleMeaning meaning;
  meaning.kind = RuleMeaning::Kind::ProgramStep;
  meaning.robot = robot;
  meaning.plan = planIndex;
  meaning.from = start;
  meaning.to = target;
  meaning.changesMode = path.changesMode;
  meaning.actions = std::move(path.actions);
  meaning.guards = std::move(path.guards);
  meaning.effects = std::move(path.effects);
  if (branch.assignments.empty() && path.words.empty()) {
    // An idle loop changes nothing the model sees: no rule, but the robot still walks it (its calls
    // run), and the runtime needs to know how.
    lowering_.stutters.push_back(std::move(meaning));
    return;
  }
  rule.branches.push_back(std::move(branch));
  std::string label;
  for (const std::string& w : path.words) label += (label.empty() ? "" : ", ") + w;
  rule.label = label.empty() ? "continues " + m_.services[first.service].name : label;
  // The robot does not stop: of the steps it may take from this control point, one is taken in
  // the end. Which one, where a sensed condition decides, is the environment's choice: per step,
  // fairness would force every outcome of a sensor that is read again and again.
  rule.weaklyFair = true;
  rule.fairGroup = m_.robots[robot].name + "." + prog.plan + "." + std::to_string(start);
  rule.sensed = std::move(path.sensed);
  addRule(std::move(rule), std::move(meaning));
}

void Translator::walk(Index robot, std::size_t planIndex, std::size_t at, Path path, std::size_t start, int depth) {
  const PlanProgram& prog = programs_[m_.robots[robot].team][planIndex];
  const Instr& in = prog.code[at];
  if (depth > 0 && in.loopBack != 0) {
    lowering::Action enters(lowering::Action::Kind::LoopStart, nullptr);
    enters.jump = in.loopBack;
    path.actions.push_back(enters);
  }
  if (depth > 0 && in.controlPoint) return finish(robot, planIndex, start, at, std::move(path));
  if (depth > 10000) return;  // cannot happen: every cycle holds a control point
  switch (in.kind) {
    case Instr::Kind::Done:
      return finish(robot, planIndex, start, 0, std::move(path));
    case Instr::Kind::Local:
    case Instr::Kind::Jump:
      if (!in.label.empty() && in.kind == Instr::Kind::Local) path.words.push_back(in.label);
      if (in.kind == Instr::Kind::Local && in.stmt != nullptr && in.stmt->kind == model::Stmt::Kind::CallPrimitive) {
        path.actions.push_back({lowering::Action::Kind::Call, in.stmt});
      } else if (in.kind == Instr::Kind::Local && in.stmt != nullptr && in.stmt->kind == model::Stmt::Kind::Wait) {
        path.actions.push_back({lowering::Action::Kind::Wait, in.stmt});
      }
      return walk(robot, planIndex, in.next, std::move(path), start, depth + 1);
    case Instr::Kind::Branch:
    case Instr::Kind::RepeatBranch: {
      std::optional<Expr> c = condition(robot, *in.cond);
      Path yes = path, no = std::move(path);
      bool repeat = in.kind == Instr::Kind::RepeatBranch;
      auto kind = c ? lowering::Action::Kind::Test : lowering::Action::Kind::Sense;
      yes.actions.push_back({kind, nullptr, in.cond, true, repeat});
      no.actions.push_back({kind, nullptr, in.cond, false, repeat});
      if (c) {
        yes.guard.push_back(*c);
        no.guard.push_back(lnot(std::move(*c)));
      } else {
        yes.words.push_back(in.kind == Instr::Kind::Branch ? "senses: condition holds" : "senses: repeat");
        no.words.push_back(in.kind == Instr::Kind::Branch ? "senses: condition fails" : "senses: stop repeating");
        // What is sensed: the robot, and the condition, the same wherever the robot senses it (a
        // settling world gives it one value); a negated comparison is its positive one, failing.
        bool negated = false;
        // A condition on values of one source for the whole team (strategy: source="team") is
        // one point for every robot: on a settling world they all read it the same way.
        const std::string text = sensedText(*in.cond, negated);
        const std::string point = readsTeamSourcesOnly(*in.cond) ? text : m_.robots[robot].name + "." + text;
        yes.sensed.push_back({point, !negated});
        no.sensed.push_back({point, negated});
      }
      walk(robot, planIndex, repeat ? in.alt : in.next, std::move(yes), start, depth + 1);
      walk(robot, planIndex, repeat ? in.next : in.alt, std::move(no), start, depth + 1);
      return;
    }
    case Instr::Kind::Groups: {
      const model::GroupBlock& block = m_.groupBlocks[in.block];
      if (block.isLeaderBlock) {
        std::size_t leaderArm = in.next, othersArm = in.next;
        std::size_t leaderIndex = 0, othersIndex = 0;
        for (std::size_t a = 0; a < block.arms.size(); ++a) {
          if (block.arms[a].kind == model::GroupArm::Kind::Leader) leaderArm = in.arms[a], leaderIndex = a;
          if (block.arms[a].kind == model::GroupArm::Kind::Others) othersArm = in.arms[a], othersIndex = a;
        }
        // The group starts together (synchronised start): whoever forms it first runs the election
        // among the robots forming it with it, and they agree on its result, the best of them, when
        // no live candidate leads yet.
        Expr best = bestFormingCandidate(in.block, planIndex, at);
        auto electedIs = [&](Index c) {
          return Expr::binary(Op::Or, Expr::var(vars_[c].leads.at(in.block)),
                              ir::conjunction({noLeader(in.block), eq(best, static_cast<std::int32_t>(c))}));
        };
        for (Index c : candidates(in.block)) path.updates.push_back({vars_[c].leads.at(in.block), electedIs(c)});
        // A new leader announces itself at once (its first heartbeat): waiting candidates start
        // their failure timeout afresh, so none takes over from a leader it has not yet heard.
        // Where heartbeats may be lost, so may the announcement: then nothing is reset.
        if (!loseHeartbeats_) {
          for (Index c : candidates(in.block)) {
            auto silence = vars_[c].silence.find(in.block);
            if (silence == vars_[c].silence.end()) continue;
            path.updates.push_back({silence->second, Expr::ite(noLeader(in.block), Expr::constant(0), Expr::var(silence->second))});
          }
        }
        path.effects.push_back({lowering::Effect::Kind::Elect, in.block});
        if (vars_[robot].leads.count(in.block) != 0) {
          Path leading = path;
          leading.guard.push_back(electedIs(robot));
          leading.guards.push_back(lowering::Guard(lowering::Guard::Kind::Elected, in.block, planIndex, at));
          leading.effects.push_back({lowering::Effect::Kind::JoinArm, in.block, leaderIndex});
          leading.words.push_back("leads the group");
          finish(robot, planIndex, start, leaderArm, std::move(leading));
          path.guard.push_back(lnot(electedIs(robot)));
          path.guards.push_back(lowering::Guard(lowering::Guard::Kind::NotElected, in.block, planIndex, at));
        }
        path.effects.push_back({lowering::Effect::Kind::JoinArm, in.block, othersIndex});
        path.words.push_back("follows the leader");
        return finish(robot, planIndex, start, othersArm, std::move(path));
      }
      bool any = false;
      for (std::size_t a = 0; a < block.arms.size(); ++a) {
        const model::GroupArm& arm = block.arms[a];
        if (std::find(arm.candidates.begin(), arm.candidates.end(), robot) == arm.candidates.end()) continue;
        any = true;
        Path take = path;
        std::string what = arm.kind == model::GroupArm::Kind::Others ? "others" : "group (" + arm.names.front() + (arm.names.size() > 1 ? ", ..." : "") + ")";
        take.words.push_back("joins " + what);
        take.effects.push_back({lowering::Effect::Kind::JoinArm, in.block, a});
        finish(robot, planIndex, start, in.arms[a], std::move(take));
      }
      if (!any) {
        path.words.push_back("takes no group");
        finish(robot, planIndex, start, in.next, std::move(path));
      }
      return;
    }
    default: {
      std::vector<Path> outcomes;
      effect(robot, planIndex, in, path, outcomes);
      for (Path& p : outcomes) {
        if (p.changesMode) {
          finish(robot, planIndex, start, start, std::move(p));
        } else {
          finish(robot, planIndex, start, in.next, std::move(p));
        }
      }
    }
  }
}

void Translator::effect(Index robot, std::size_t planIndex, const Instr& in, Path& path, std::vector<Path>& out) {
  const model::Stmt& s = *in.stmt;
  Index team = m_.robots[robot].team;
  switch (in.kind) {
    case Instr::Kind::Throw: {
      const model::Event& event = m_.teams[team].events[s.event];
      for (Index q : m_.teams[team].robots) {
        auto it = vars_[q].event.find(s.event);
        if (q == robot || it == vars_[q].event.end()) continue;
        path.updates.push_back({it->second, Expr::ite(alive(q), Expr::constant(1), Expr::var(it->second))});
      }
      // The thrower's own copy: it reacts at once, in whichever mode it is running this code.
      std::vector<Index> modes = modesRunning(team, planIndex, in.service);
      path.effects.push_back({lowering::Effect::Kind::Throw, s.event});
      for (Index md : modes) {
        Path p = path;
        if (vars_[robot].mode && modes.size() > 1) {
          const std::vector<Index>& all = m_.teams[team].modes;
          auto index = static_cast<std::int32_t>(std::find(all.begin(), all.end(), md) - all.begin());
          p.guard.push_back(eq(Expr::var(*vars_[robot].mode), index));
          p.guards.push_back(lowering::Guard(lowering::Guard::Kind::InMode, static_cast<Index>(index)));
        }
        p.words.push_back("throws " + event.name);
        for (const model::Transition& tr : m_.modes[md].transitions) {
          if (tr.isDefault || tr.event != s.event) continue;
          for (ir::Assignment& a : enterMode(robot, tr.target)) p.updates.push_back(std::move(a));
          p.effects.push_back({lowering::Effect::Kind::EnterMode, tr.target});
          p.words.push_back("mode " + m_.modes[tr.target].name);
          p.changesMode = true;
        }
        out.push_back(std::move(p));
        if (!vars_[robot].mode || modes.size() == 1) break;
      }
      return;
    }
    case Instr::Kind::Publish: {
      Index tp = s.topic;
      if (tp == model::kNone) return out.push_back(std::move(path));
      std::int32_t value = symbolValue(tp, s.value);
      if (value < 0) value = 1;
      for (Index q : m_.teams[s.peerTeam].robots) {
        auto msg = vars_[q].msg.find(tp);
        if (msg == vars_[q].msg.end()) continue;
        if (q == robot) {
          path.updates.push_back({vars_[q].view.at(tp), Expr::constant(value)});
        } else {
          path.updates.push_back({msg->second, Expr::ite(alive(q), Expr::constant(value), Expr::var(msg->second))});
        }
      }
      path.effects.push_back({lowering::Effect::Kind::Publish, tp, 0, &s});
      path.effects.back().value = value;
      path.words.push_back("publishes " + m_.teams[m_.topics[tp].owner].name + "." + m_.topics[tp].var);
      return out.push_back(std::move(path));
    }
    case Instr::Kind::Send: {
      if (s.topic == model::kNone) return out.push_back(std::move(path));
      ir::VarId ch = channel_.at(s.topic);
      // Stops one past the capacity: buffer_bounds reports the overflow there.
      path.guard.push_back(Expr::binary(Op::Le, Expr::var(ch), Expr::constant(static_cast<std::int32_t>(m_.topics[s.topic].buffer))));
      path.updates.push_back({ch, Expr::binary(Op::Add, Expr::var(ch), Expr::constant(1))});
      path.guards.push_back(lowering::Guard(lowering::Guard::Kind::ChannelSpace, s.topic));
      path.effects.push_back({lowering::Effect::Kind::Send, s.topic});
      path.words.push_back("sends " + m_.topics[s.topic].var);
      return out.push_back(std::move(path));
    }
    case Instr::Kind::Receive: {
      if (s.topic == model::kNone) return out.push_back(std::move(path));
      ir::VarId ch = channel_.at(s.topic);
      path.guard.push_back(Expr::binary(Op::Gt, Expr::var(ch), Expr::constant(0)));
      path.updates.push_back({ch, Expr::binary(Op::Sub, Expr::var(ch), Expr::constant(1))});
      path.guards.push_back(lowering::Guard(lowering::Guard::Kind::ChannelData, s.topic));
      path.effects.push_back({lowering::Effect::Kind::Receive, s.topic});
      path.words.push_back("receives " + m_.topics[s.topic].var);
      return out.push_back(std::move(path));
    }
    default:
      out.push_back(std::move(path));
  }
}

}  // namespace semo::detail
