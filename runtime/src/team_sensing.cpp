// What the robots sense and do in the world: conditions evaluated over sensed values (from the world
// file), topic views and knowledge; calls handed to the task library's behaviours, stepped once per
// control period while the bodies move.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "team.hpp"

namespace semo::runtime::detail {

namespace {
constexpr std::string_view kTrue = "true", kFalse = "false";

bool near(const World& world, Vec2 p, double within) {
  return std::any_of(world.obstacles.begin(), world.obstacles.end(), [&](const Obstacle& o) { return o.shape.distance(p) <= within; });
}
}  // namespace

Team::Reading Team::sense(Id robot, Id sensed) const {
  if (sensed == kNone) return {};
  const SensedValueTable& table = t_.sensed[sensed];
  const ValueSource* src = world_.value(table.name);
  auto value = [](const SensedValue& v) { return v.isNumber ? Reading{true, v.number, {}} : Reading{false, 0, v.symbol}; };
  if (src == nullptr) return table.domain == SensedValueTable::Domain::Bool ? Reading{false, 0, kFalse} : Reading{true, 0, {}};
  const Pose& pose = poses_[robot];
  const Vec2 at{pose.x, pose.y};
  switch (src->kind) {
    case ValueSource::Kind::Constant:
    case ValueSource::Kind::Schedule: {
      const SensedValue* v = &src->schedule.front().second;
      for (const auto& [from, entry] : src->schedule) {
        if (from <= now()) v = &entry;
      }
      return value(*v);
    }
    case ValueSource::Kind::Regions:
      for (const ValueSource::Region& region : src->regions) {
        if (region.shape.contains(at)) return value(region.value);
      }
      return value(src->otherwise);
    case ValueSource::Kind::Sensor: {
      bool holds = false;
      const RobotRun& r = robots_[robot];
      const double dx = at.x - r.destination.x, dy = at.y - r.destination.y;
      if (src->sensor == "at_destination" || src->sensor == "not_at_destination") {
        holds = (dx * dx + dy * dy <= 0.2 * 0.2) == (src->sensor == "at_destination");
      } else if (src->sensor == "touching_obstacle") {
        holds = near(world_, at, 0.05);
      } else if (src->sensor == "obstacle_ahead") {
        for (double d = 0; d <= src->range + 1e-9 && !holds; d += 0.05) {
          holds = near(world_, {at.x + d * std::cos(pose.theta), at.y + d * std::sin(pose.theta)}, 0.0);
        }
      }
      return {false, 0, holds ? kTrue : kFalse};
    }
  }
  return {};
}

Team::Reading Team::read(Id robot, const Operand& o) const {
  const RobotRun& r = robots_[robot];
  switch (o.kind) {
    case Operand::Kind::Number: return {true, o.number, {}};
    case Operand::Kind::Symbol: return {false, 0, o.text};
    case Operand::Kind::Sensed: return sense(robot, o.index);
    case Operand::Kind::View: {
      const std::int32_t v = r.view[o.index];
      const std::vector<std::string>& symbols = t_.topics[o.index].symbols;
      if (v == 0) return {false, 0, "none"};
      return {false, 0, static_cast<std::size_t>(v) <= symbols.size() ? std::string_view(symbols[v - 1]) : std::string_view("some")};
    }
    case Operand::Kind::Facts: {
      const std::vector<Id>& items = t_.robots[robot].knowledge;
      const auto slot = std::find(items.begin(), items.end(), o.index) - items.begin();
      return {true, slot < static_cast<std::ptrdiff_t>(r.knowledge.size()) ? static_cast<double>(r.knowledge[slot].count()) : 0.0, {}};
    }
  }
  return {};
}

bool Team::evaluate(Id robot, Id condition) const {
  const CondNode& c = t_.conditions[condition];
  switch (c.kind) {
    case CondNode::Kind::Not: return !evaluate(robot, c.left);
    case CondNode::Kind::And: return evaluate(robot, c.left) && evaluate(robot, c.right);
    case CondNode::Kind::Or: return evaluate(robot, c.left) || evaluate(robot, c.right);
    case CondNode::Kind::Test: {
      if (c.lhs.kind == Operand::Kind::View) return robots_[robot].view[c.lhs.index] != 0;
      const Reading v = read(robot, c.lhs);
      return v.isNumber ? v.number != 0 : v.symbol == kTrue;
    }
    case CondNode::Kind::Compare: break;
  }
  const Reading a = read(robot, c.lhs), b = read(robot, c.rhs);
  if (a.isNumber && b.isNumber) {
    switch (c.rel) {
      case CondNode::Rel::Lt: return a.number < b.number;
      case CondNode::Rel::Le: return a.number <= b.number;
      case CondNode::Rel::Gt: return a.number > b.number;
      case CondNode::Rel::Ge: return a.number >= b.number;
      case CondNode::Rel::Eq: return a.number == b.number;
      case CondNode::Rel::Ne: return a.number != b.number;
    }
  }
  if (c.rel == CondNode::Rel::Eq) return !a.isNumber && !b.isNumber && a.symbol == b.symbol;
  if (c.rel == CondNode::Rel::Ne) return a.isNumber || b.isNumber || a.symbol != b.symbol;
  return false;  // ordering symbols means nothing
}

std::vector<std::string> Team::callArgs(Id robot, Id call) const {
  std::vector<std::string> out;
  for (const Operand& o : t_.calls[call].args) {
    const Reading v = read(robot, o);
    out.push_back(v.isNumber ? fmt::format("{:g}", v.number) : std::string(v.symbol));
  }
  return out;
}

void Team::startCall(Id robot, Id plan, Id call) {
  PlanRun& p = robots_[robot].plans[plan];
  p.phase = PlanRun::Phase::Busy;
  p.behaviour = library_.make(t_.calls[call].service);
  p.behaviourCall = call;
  p.context.robot = robot;
  p.context.now = now();
  p.context.dt = options_.controlPeriod;
  p.context.body = &bodies_[robot];
  p.context.world = &world_;
  p.context.poses = &poses_;
  p.context.alive = &aliveFlags_;
  p.context.teams = &teamNames_;
  p.context.args = callArgs(robot, call);
  p.context.destination = &robots_[robot].destination;
  p.context.unknownFacts.clear();
  p.behaviour->start(p.context);
}

// One control period: the bodies move to now, then every call under way and every group service
// worked in takes one step.
void Team::stepBehaviours() {
  for (std::size_t r = 0; r < bodies_.size(); ++r) {
    if (!local(static_cast<Id>(r))) continue;  // a peer's pose is the one its last Pose packet gave
    if (robots_[r].alive) bodies_[r].advanceTo(now());
    poses_[r] = bodies_[r].pose();
  }
  stepDataflow();  // the scenarios of the calls under way run through the period now beginning
  for (Id robot = 0; robot < robots_.size() && !stopped_; ++robot) {
    RobotRun& r = robots_[robot];
    if (!r.alive || !local(robot)) continue;
    const RobotTable& table = t_.robots[robot];
    for (Id plan = 0; plan < r.plans.size() && r.alive; ++plan) {
      PlanRun& p = r.plans[plan];
      const PlanPoint& point = table.plans[plan].points[p.pc];
      if (point.work != kNone && p.phase == PlanRun::Phase::Blocked) {
        Id started = kNone;
        for (const RobotTable::Discover& d : table.discoverRules) {
          if (d.plan == plan && d.pc == p.pc) started = d.started;
        }
        if (!groupStarted(robot, plan, started)) continue;  // the others are still on their way
        if (!p.behaviour) {
          startCall(robot, plan, point.work);
          p.phase = PlanRun::Phase::Blocked;
          p.working = true;
        }
        p.context.unknownFacts.clear();
        for (const FactSite& site : world_.facts) {
          for (std::size_t slot = 0; slot < table.knowledge.size(); ++slot) {
            const KnowledgeTable& item = t_.knowledge[table.knowledge[slot]];
            if (site.knowledge != item.name) continue;
            const auto fact = std::find(item.facts.begin(), item.facts.end(), site.fact) - item.facts.begin();
            if (fact < static_cast<std::ptrdiff_t>(item.facts.size()) && !r.knowledge[slot].holds(static_cast<std::uint32_t>(fact))) {
              p.context.unknownFacts.push_back(&site);
            }
          }
        }
        p.context.now = now();
        p.behaviour->step(p.context);
        discover(robot, plan);
        continue;
      }
      if (p.phase != PlanRun::Phase::Busy || !p.behaviour) continue;
      p.context.now = now();
      if (p.behaviour->step(p.context)) {
        p.behaviour.reset();
        p.behaviourCall = kNone;
        schedule(now_, QueuedEvent::Kind::Wake, robot, plan, p.generation);
      }
    }
  }
}

}  // namespace semo::runtime::detail

namespace semo::runtime {

std::vector<std::string> checkWorld(const MissionTables& tables, const World& world) {
  std::vector<std::string> problems;
  for (const RobotTable& r : tables.robots) {
    if (world.start(r.name) == nullptr) problems.push_back("no start pose for robot " + r.name + " (add it under \"robots\")");
  }
  for (const CallTable& call : tables.calls) {
    if ((call.service == "move" || call.service == "walk") && !call.args.empty() && call.args.front().kind == Operand::Kind::Symbol &&
        world.place(call.args.front().text) == nullptr) {
      problems.push_back(call.origin + ": " + call.service + "(\"" + call.args.front().text + "\") names a place the world does not have (add it under \"places\")");
    }
  }
  std::vector<bool> read(tables.sensed.size(), false);
  auto mark = [&](const Operand& o) {
    if (o.kind == Operand::Kind::Sensed && o.index != kNone) read[o.index] = true;
  };
  for (const CondNode& c : tables.conditions) mark(c.lhs), mark(c.rhs);
  for (const CallTable& call : tables.calls) {
    for (const Operand& o : call.args) mark(o);
  }
  for (std::size_t s = 0; s < tables.sensed.size(); ++s) {
    if (read[s] && world.value(tables.sensed[s].name) == nullptr) {
      problems.push_back("the mission reads " + tables.sensed[s].name + " but the world gives it no source (add it under \"values\")");
    }
  }
  return problems;
}

}  // namespace semo::runtime
