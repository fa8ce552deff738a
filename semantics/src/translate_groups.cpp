// The robots' rules around group blocks: the barrier at a block's end, and working in a group
// service (discovering facts, leaving at the goal) with the synchronised start they share.
#include "translator.hpp"

namespace semo::detail {

// The end of a [[ ]] block is a barrier: a robot leaves when no other live robot of its team is
// still inside the block (between forming it and reaching its end).
void Translator::blockExitRules(Index robot, std::size_t planIndex, std::size_t at) {
  Index team = m_.robots[robot].team;
  const PlanProgram& prog = programs_[team][planIndex];
  const BlockRange* range = nullptr;
  for (const BlockRange& b : prog.blocks) {
    if (b.exit == at) range = &b;
  }
  Path path;
  if (counted(team)) {  // a large team: how many robots are inside, this one not counted
    std::vector<std::int32_t> inside;
    for (std::size_t i = range->first + 1; i < range->last; ++i) inside.push_back(static_cast<std::int32_t>(i));
    if (!inside.empty()) {
      ir::VarId count = teamCount(team, VariableRole::Kind::AtPoints, planIndex, {}, inside);
      path.guard.push_back(eq(othersCounted(count, robot, Expr::constant(static_cast<std::int32_t>(at))), 0));
    }
  }
  for (Index q : m_.teams[team].robots) {
    if (counted(team)) break;
    if (q == robot || !vars_[q].pc[planIndex]) continue;
    Expr pc = Expr::var(*vars_[q].pc[planIndex]);
    Expr inside = ir::conjunction({Expr::binary(Op::Gt, pc, Expr::constant(static_cast<std::int32_t>(range->first))),
                                   Expr::binary(Op::Lt, pc, Expr::constant(static_cast<std::int32_t>(range->last)))});
    path.guard.push_back(Expr::binary(Op::Or, lnot(alive(q)), lnot(std::move(inside))));
  }
  lowering::Guard clear(lowering::Guard::Kind::BlockClear, range->block, planIndex, at);
  for (std::size_t i = range->first + 1; i < range->last; ++i) clear.pcs.push_back(i);
  path.guards.push_back(std::move(clear));
  if (auto leads = vars_[robot].leads.find(range->block); leads != vars_[robot].leads.end()) {
    path.updates.push_back({leads->second, Expr::constant(0)});  // a leader's part ends with the block
  }
  path.effects.push_back({lowering::Effect::Kind::LeaveBlock, range->block});
  path.words.push_back("leaves the group block");
  walk(robot, planIndex, prog.code[at].next, std::move(path), at, 1);
}

// Working in a group service: the environment may show the robot a fact it does not hold; the
// robot leaves when it holds as many facts as the goal asks (never, without a goal). Knowledge is
// counted, not listed (specs/semantics.md): which facts a robot holds matters to no property here.
// Synchronised start (the paper's group semantics): a robot starts working in a group service
// only when no other live robot running the same service is still on its way to the block or
// forming it; those already in an arm, or elsewhere, do not hold it up.
Expr Translator::groupStarted(Index robot, std::size_t planIndex, std::size_t at, std::vector<std::size_t>* pcs) {
  const PlanProgram& prog = programs_[m_.robots[robot].team][planIndex];
  const Index service = prog.code[at].service;
  std::vector<Expr> ready;
  for (const BlockRange& range : prog.blocks) {
    if (range.armFirst.empty() || at < range.armFirst.front() || at >= range.last) continue;
    std::vector<std::size_t> before;  // in the service, at the block's formation or before it
    for (std::size_t i = 1; i < prog.code.size(); ++i) {
      if (prog.code[i].service == service && prog.code[i].controlPoint && (i < range.first || i >= range.last)) before.push_back(i);
    }
    if (pcs != nullptr) pcs->insert(pcs->end(), before.begin(), before.end());
    const Index team = m_.robots[robot].team;
    if (counted(team)) {  // a large team: how many robots are not there yet, this one not counted
      if (before.empty()) continue;
      std::vector<std::int32_t> values(before.begin(), before.end());
      ir::VarId count = teamCount(team, VariableRole::Kind::AtPoints, planIndex, {}, values);
      ready.push_back(eq(othersCounted(count, robot, Expr::constant(static_cast<std::int32_t>(at))), 0));
      continue;
    }
    for (Index q : m_.teams[team].robots) {
      if (q == robot || !vars_[q].pc[planIndex]) continue;
      Expr pc = Expr::var(*vars_[q].pc[planIndex]);
      std::vector<Expr> notYet;
      for (std::size_t i : before) notYet.push_back(eq(pc, static_cast<std::int32_t>(i)));
      if (!notYet.empty()) ready.push_back(Expr::binary(Op::Or, lnot(alive(q)), lnot(ir::disjunction(std::move(notYet)))));
    }
  }
  if (pcs != nullptr) {
    std::sort(pcs->begin(), pcs->end());
    pcs->erase(std::unique(pcs->begin(), pcs->end()), pcs->end());
  }
  return ir::conjunction(std::move(ready));
}

void Translator::groupServiceRules(Index robot, std::size_t planIndex, std::size_t at) {
  const PlanProgram& prog = programs_[m_.robots[robot].team][planIndex];
  const Instr& in = prog.code[at];
  const strategy::Service& sv = m_.serviceOf(*in.stmt);
  const RobotVars& v = vars_[robot];
  lowering::Guard started(lowering::Guard::Kind::GroupStarted, in.service, planIndex, at);
  Expr here = ir::conjunction({alive(robot), eq(Expr::var(*v.pc[planIndex]), static_cast<std::int32_t>(at)),
                               groupStarted(robot, planIndex, at, &started.pcs)});
  for (const strategy::Knowledge& k : sv.knowledge) {
    ir::VarId knows = v.knows.at(k.name);
    ir::Rule discover;
    discover.name = m_.robots[robot].name + ".discovers." + k.name + "." + std::to_string(at);
    discover.robot = static_cast<std::int32_t>(robot);
    discover.kind = ir::RuleKind::Environment;
    discover.label = "finds a new " + k.name + " fact while working in " + sv.name;
    discover.origin = origin(in.stmt->at, "group service call");
    discover.guard = ir::conjunction({here, Expr::binary(Op::Lt, Expr::var(knows), Expr::constant(static_cast<std::int32_t>(k.values.size())))});
    discover.branches.push_back({1.0, {{knows, Expr::binary(Op::Add, Expr::var(knows), Expr::constant(1))}}});
    RuleMeaning meaning;
    meaning.kind = RuleMeaning::Kind::Discover;
    meaning.robot = robot;
    meaning.plan = planIndex;
    meaning.from = meaning.to = at;
    meaning.service = sv.name;
    meaning.knowledge = k.name;
    meaning.guards.push_back(started);
    addRule(std::move(discover), std::move(meaning));
  }
  if (!sv.goal) return;
  Path path;
  path.guard.push_back(groupStarted(robot, planIndex, at));
  path.guards.push_back(std::move(started));
  path.guard.push_back(Expr::binary(Op::Ge, Expr::var(v.knows.at(sv.goal->knowledge)), Expr::constant(static_cast<std::int32_t>(sv.goal->count))));
  lowering::Guard goal(lowering::Guard::Kind::Goal);
  goal.knowledge = sv.goal->knowledge;
  goal.count = sv.goal->count;
  path.guards.push_back(std::move(goal));
  path.words.push_back("reaches the goal of " + sv.name);
  walk(robot, planIndex, in.next, std::move(path), at, 1);
}

}  // namespace semo::detail
