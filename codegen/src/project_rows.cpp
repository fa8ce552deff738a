// Each robot's plan tables: one point per instruction of its team's plan program (the IR's program
// counters), one row per IR rule of the robot's program, and one row without a rule per idle walk
// (a stutter: the robot runs its calls, the model sees nothing change). Conditions, calls and
// operands are turned into the runtime's plain data once and shared by index.
#include <algorithm>

#include "projector.hpp"

namespace semo::codegen::detail {

using MeaningKind = lowering::RuleMeaning::Kind;

std::string Projector::where(const SourceRange& r) const {
  if (!r.begin.valid() || r.begin.file >= sources_.fileCount()) return {};
  return sources_.path(r.begin.file) + ":" + std::to_string(r.begin.line) + ":" + std::to_string(r.begin.column);
}

void Projector::plans(Id robot) {
  const model::Robot& r = m_.robots[robot];
  const std::vector<lowering::PlanProgram>& programs = t_.lowering.programs[r.team];
  runtime::RobotTable& out = out_.robots[robot];
  for (const lowering::PlanProgram& prog : programs) {
    runtime::PlanTable plan;
    plan.name = prog.plan;
    for (std::size_t i = 0; i < prog.code.size(); ++i) {
      const lowering::Instr& in = prog.code[i];
      runtime::PlanPoint point;
      point.controlPoint = in.controlPoint;
      point.service = in.service;
      point.label = i == 0 ? "done" : m_.services[in.service].name + "#" + std::to_string(i);
      if (in.kind == lowering::Instr::Kind::GroupService) point.work = call(*in.stmt);
      if (in.kind == lowering::Instr::Kind::Jump) {
        point.loopHead = static_cast<Id>(in.next);
        std::int64_t millis = 0;
        if (in.stmt != nullptr) {
          millis = in.stmt->durationMillis;  // loop (D)
        } else if (const auto& rep = m_.services[in.service].repeat; rep && rep->isPeriod) {
          millis = rep->periodMillis;  // repeat (D)
        }
        point.loopPeriod = static_cast<double>(millis) / 1000.0;
      }
      plan.points.push_back(std::move(point));
    }
    out.plans.push_back(std::move(plan));
  }
  const std::vector<lowering::RuleMeaning>& rules = t_.lowering.rules;
  for (Id i = 0; i < rules.size(); ++i) {
    if (rules[i].kind == MeaningKind::ProgramStep && rules[i].robot == robot) out.plans[rules[i].plan].rows.push_back(row(i, rules[i]));
  }
  for (const lowering::RuleMeaning& stutter : t_.lowering.stutters) {
    if (stutter.robot == robot) out.plans[stutter.plan].rows.push_back(row(kNone, stutter));
  }
  for (runtime::PlanTable& plan : out_.robots[robot].plans) {
    // By control point; within one, in the IR's rule order (stutters last).
    std::stable_sort(plan.rows.begin(), plan.rows.end(), [](const runtime::Row& a, const runtime::Row& b) { return a.from < b.from; });
    plan.firstRow.resize(plan.points.size() + 1);
    for (std::size_t pc = 0; pc < plan.firstRow.size(); ++pc) {
      auto first = std::lower_bound(plan.rows.begin(), plan.rows.end(), pc, [](const runtime::Row& r, std::size_t at) { return r.from < at; });
      plan.firstRow[pc] = static_cast<Id>(first - plan.rows.begin());
    }
  }
}

runtime::Row Projector::row(Id rule, const lowering::RuleMeaning& m) {
  runtime::Row out;
  out.from = static_cast<Id>(m.from);
  out.to = static_cast<Id>(m.to);
  out.changesMode = m.changesMode;
  out.irRule = rule;
  for (const lowering::Action& a : m.actions) out.actions.push_back(action(a));
  for (const lowering::Guard& g : m.guards) out.guards.push_back(guard(g, m.robot));
  for (const lowering::Effect& e : m.effects) out.effects.push_back(effect(e, m.robot));
  return out;
}

runtime::ActionRow Projector::action(const lowering::Action& a) {
  using K = lowering::Action::Kind;
  runtime::ActionRow out;
  out.expect = a.expect;
  switch (a.kind) {
    case K::Call:
      out.kind = runtime::ActionRow::Kind::Call;
      out.index = call(*a.stmt);
      break;
    case K::Wait:
      out.kind = runtime::ActionRow::Kind::Wait;
      out.seconds = static_cast<double>(a.stmt->durationMillis) / 1000.0;
      break;
    case K::Sense:
    case K::Test:
      out.kind = a.kind == K::Sense ? runtime::ActionRow::Kind::Sense : runtime::ActionRow::Kind::Test;
      out.index = condition(*a.cond);
      break;
    case K::LoopStart:
      out.kind = runtime::ActionRow::Kind::LoopStart;
      out.index = static_cast<Id>(a.jump);
      break;
  }
  return out;
}

runtime::GuardRow Projector::guard(const lowering::Guard& g, Id robot) {
  using K = lowering::Guard::Kind;
  using R = runtime::GuardRow::Kind;
  runtime::GuardRow out;
  out.plan = static_cast<Id>(g.plan);
  switch (g.kind) {
    case K::InMode: out.kind = R::InMode, out.index = g.index; break;
    case K::ChannelSpace: out.kind = R::ChannelSpace, out.index = g.index; break;
    case K::ChannelData: out.kind = R::ChannelData, out.index = g.index; break;
    case K::GroupStarted: out.kind = R::GroupStarted, out.index = pcSet({g.pcs.begin(), g.pcs.end()}); break;
    case K::BlockClear: out.kind = R::BlockClear, out.index = pcSet({g.pcs.begin(), g.pcs.end()}); break;
    case K::Elected: out.kind = R::Elected, out.index = leaderIndex_[g.index]; break;
    case K::NotElected: out.kind = R::NotElected, out.index = leaderIndex_[g.index]; break;
    case K::Goal:
      out.kind = R::Goal;
      out.index = knowledgeItem(m_.robots[robot].team, g.knowledge);
      out.count = g.count;
      break;
  }
  return out;
}

runtime::EffectRow Projector::effect(const lowering::Effect& e, Id /*robot*/) {
  using K = lowering::Effect::Kind;
  using R = runtime::EffectRow::Kind;
  runtime::EffectRow out;
  out.index = e.index;
  switch (e.kind) {
    case K::Throw: out.kind = R::Throw; break;
    case K::EnterMode: out.kind = R::EnterMode, out.index = teamModeIndex(e.index); break;
    case K::Publish:
      out.kind = R::Publish;
      // The value the model's slots get; what the robot really sends (facts, a reading) is the
      // statement's expression, carried beside it for the trace and the receiver's display.
      out.value.kind = runtime::Operand::Kind::Number;
      out.value.number = e.value;
      if (e.stmt != nullptr) out.value.text = operand(e.stmt->value).text, out.team = e.stmt->peerTeam;
      break;
    case K::Send: out.kind = R::Send; break;
    case K::Receive: out.kind = R::Receive; break;
    case K::Elect: out.kind = R::Elect, out.index = leaderIndex_[e.index]; break;
    case K::JoinArm: out.kind = R::JoinArm, out.arm = static_cast<Id>(e.arm); break;
    case K::LeaveBlock: out.kind = R::LeaveBlock; break;
  }
  return out;
}

Id Projector::pcSet(const std::vector<std::size_t>& pcs) {
  std::vector<Id> key(pcs.begin(), pcs.end());
  std::sort(key.begin(), key.end());
  auto [it, added] = pcSets_.try_emplace(key, static_cast<Id>(out_.pcSets.size()));
  if (added) out_.pcSets.push_back(std::move(key));
  return it->second;
}

runtime::Operand Projector::operand(const model::Expr& e) {
  using K = model::Expr::Kind;
  runtime::Operand out;
  switch (e.kind) {
    case K::Int: out.kind = runtime::Operand::Kind::Number, out.number = static_cast<double>(e.intValue); break;
    case K::Number: out.kind = runtime::Operand::Kind::Number, out.number = e.numberValue; break;
    case K::String:
    case K::Symbol: out.kind = runtime::Operand::Kind::Symbol, out.text = e.text; break;
    case K::Bool: out.kind = runtime::Operand::Kind::Symbol, out.text = e.intValue != 0 ? "true" : "false"; break;
    case K::Value: {
      const std::string name = m_.teams[e.owner].name + "." + e.var;
      out.text = name;
      if (e.valueKind == model::ValueKind::Topic) {
        out.kind = runtime::Operand::Kind::View;
        out.index = e.topic;
      } else if (e.valueKind == model::ValueKind::Knowledge) {
        out.kind = runtime::Operand::Kind::Facts;
        out.index = knowledgeItem(e.owner, e.var);
      } else {
        out.kind = runtime::Operand::Kind::Sensed;
        auto it = std::find_if(out_.sensed.begin(), out_.sensed.end(), [&](const runtime::SensedValueTable& s) { return s.name == name; });
        out.index = it == out_.sensed.end() ? kNone : static_cast<Id>(it - out_.sensed.begin());
      }
      break;
    }
  }
  return out;
}

Id Projector::condition(const model::Cond& c) {
  if (auto it = conditions_.find(&c); it != conditions_.end()) return it->second;
  runtime::CondNode node;
  node.kind = static_cast<runtime::CondNode::Kind>(c.kind);
  node.rel = static_cast<runtime::CondNode::Rel>(c.op);
  if (c.kind == model::Cond::Kind::Compare || c.kind == model::Cond::Kind::Test) {
    node.lhs = operand(c.lhs);
    if (c.kind == model::Cond::Kind::Compare) node.rhs = operand(c.rhs);
  }
  if (c.left) node.left = condition(*c.left);
  if (c.right) node.right = condition(*c.right);
  auto id = static_cast<Id>(out_.conditions.size());
  out_.conditions.push_back(std::move(node));
  conditions_[&c] = id;
  return id;
}

Id Projector::call(const model::Stmt& s) {
  if (auto it = calls_.find(&s); it != calls_.end()) return it->second;
  runtime::CallTable out;
  out.service = s.service;
  for (const model::Expr& a : s.args) out.args.push_back(operand(a));
  out.origin = where(s.at);
  auto id = static_cast<Id>(out_.calls.size());
  out_.calls.push_back(std::move(out));
  calls_[&s] = id;
  return id;
}

}  // namespace semo::codegen::detail
