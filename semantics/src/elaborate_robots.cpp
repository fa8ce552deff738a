// Which robots may run each statement, and whether their robot types can: every primitive or group
// service they call and every sensed value they read needs an implementation for their type. Also
// marks the services in use and rejects recursion.
#include <algorithm>

#include "elaborator.hpp"

namespace semo::detail {

std::string Elaborator::robotsOfType(const RobotSet& robots, const std::string& type) const {
  std::string out;
  for (Index r = 0; r < robots.size(); ++r) {
    if (robots[r] && m_.robots[r].type == type) out += (out.empty() ? "" : ", ") + m_.robots[r].name;
  }
  return out;
}

void Elaborator::checkRobotSets() {
  for (const model::Mode& mode : m_.modes) {
    RobotSet robots(m_.robots.size(), false);
    for (Index r : m_.teams[mode.team].robots) robots[r] = true;
    for (const model::PlanSetting& setting : mode.settings) {
      std::vector<Index> stack;
      walkService(setting.service, robots, stack);
    }
  }
}

void Elaborator::walkService(Index service, const RobotSet& robots, std::vector<Index>& stack) {
  m_.services[service].used = true;
  if (!walked_.insert({service, robots}).second) return;
  stack.push_back(service);
  walkBody(m_.services[service].body, robots, stack, false);
  if (m_.services[service].repeat && m_.services[service].repeat->cond) walkCond(*m_.services[service].repeat->cond, robots);
  stack.pop_back();
}

bool Elaborator::containsGroups(Index service, std::set<Index>& seen) const {
  if (!seen.insert(service).second) return false;
  std::vector<const std::vector<model::Stmt>*> bodies{&m_.services[service].body};
  while (!bodies.empty()) {
    const std::vector<model::Stmt>* body = bodies.back();
    bodies.pop_back();
    for (const model::Stmt& s : *body) {
      if (s.kind == model::Stmt::Kind::Groups) return true;
      if (s.kind == model::Stmt::Kind::If) {
        bodies.push_back(&s.thenBody);
        bodies.push_back(&s.elseBody);
      }
      if (s.kind == model::Stmt::Kind::CallComposite && containsGroups(s.composite, seen)) return true;
    }
  }
  return false;
}

void Elaborator::walkBody(const std::vector<model::Stmt>& body, const RobotSet& robots, std::vector<Index>& stack,
                          bool insideGroup) {
  for (const model::Stmt& s : body) {
    switch (s.kind) {
      case model::Stmt::Kind::CallPrimitive:
      case model::Stmt::Kind::CallGroupService:
        requireImplementation(s, robots);
        break;
      case model::Stmt::Kind::CallComposite: {
        m_.services[s.composite].used = true;  // even when the call is rejected below: it is not "unused"
        if (std::find(stack.begin(), stack.end(), s.composite) != stack.end()) {
          std::string chain;
          auto from = std::find(stack.begin(), stack.end(), s.composite);
          for (auto it = from; it != stack.end(); ++it) chain += m_.services[*it].name + " -> ";
          Diagnostic& d = diags_.error(s.at, "recursive service call: " + chain + s.service);
          DiagnosticEngine::note(d, m_.services[s.composite].at, "'" + s.service + "' is defined here");
          break;
        }
        std::set<Index> seen;
        if (insideGroup && containsGroups(s.composite, seen)) {
          Diagnostic& d = diags_.error(s.at, "service '" + s.service + "' contains a group block '[[ ]]' and cannot be called inside a group");
          DiagnosticEngine::note(d, m_.services[s.composite].at, "'" + s.service + "' is defined here");
          break;
        }
        walkService(s.composite, robots, stack);
        break;
      }
      case model::Stmt::Kind::If:
        walkCond(*s.cond, robots);
        walkBody(s.thenBody, robots, stack, insideGroup);
        walkBody(s.elseBody, robots, stack, insideGroup);
        break;
      case model::Stmt::Kind::Groups:
        for (const model::GroupArm& arm : m_.groupBlocks[s.groupBlock].arms) {
          RobotSet armRobots(m_.robots.size(), false);
          for (Index r : arm.candidates) armRobots[r] = robots[r];
          walkBody(arm.body, armRobots, stack, true);
        }
        break;
      default:
        break;
    }
  }
}

void Elaborator::walkCond(const model::Cond& c, const RobotSet& robots) {
  if (c.left) walkCond(*c.left, robots);
  if (c.right) walkCond(*c.right, robots);
  for (const model::Expr* e : {&c.lhs, &c.rhs}) {
    if (e->kind != model::Expr::Kind::Value || e->valueKind != model::ValueKind::Sensed) continue;
    const strategy::Value* value = m_.strategy.value(m_.teams[e->owner].name, e->var);
    if (value == nullptr) continue;
    std::vector<std::string> missing;
    for (Index r = 0; r < robots.size(); ++r) {
      if (!robots[r] || value->implementationFor(m_.robots[r].type) != nullptr) continue;
      if (m_.catalog.find(m_.robots[r].type) == nullptr) continue;
      if (std::find(missing.begin(), missing.end(), m_.robots[r].type) == missing.end()) missing.push_back(m_.robots[r].type);
    }
    for (const std::string& type : missing) {
      std::string key = std::to_string(e->at.begin.line) + ":" + std::to_string(e->at.begin.column) + ":" + type;
      if (!reportedMissing_.insert({0, key}).second) continue;
      Diagnostic& d = diags_.error(e->at, "value '" + value->team + "." + value->var + "' has no sensing task for robot type '" +
                                              type + "', which reads it here (" + robotsOfType(robots, type) + ")");
      DiagnosticEngine::note(d, value->at, "add an <implementation robot=\"" + type + "\"> to this value");
    }
  }
}

void Elaborator::requireImplementation(const model::Stmt& call, const RobotSet& robots) {
  if (call.strategyService == model::kNone) return;
  const strategy::Service* service = &m_.serviceOf(call);
  std::vector<std::string> missing;
  std::size_t count = 0;
  for (Index r = 0; r < robots.size(); ++r) {
    if (!robots[r]) continue;
    ++count;
    // A robot of an unknown type is already an error; asking for its implementation would repeat it.
    if (m_.catalog.find(m_.robots[r].type) == nullptr) continue;
    if (service->implementationFor(m_.robots[r].type) != nullptr) continue;
    if (std::find(missing.begin(), missing.end(), m_.robots[r].type) == missing.end()) missing.push_back(m_.robots[r].type);
  }
  for (const std::string& type : missing) {
    std::string key = std::to_string(call.at.begin.line) + ":" + std::to_string(call.at.begin.column) + ":" + type;
    if (!reportedMissing_.insert({1, key}).second) continue;
    Diagnostic& d = diags_.error(call.at, "service '" + call.service + "' has no implementation for robot type '" + type +
                                              "', which runs it here (" + robotsOfType(robots, type) + ")");
    DiagnosticEngine::note(d, service->at, "add an <implementation robot=\"" + type + "\"> to this service");
  }
  if (service->kind == strategy::Service::Kind::Group && count > 0 && static_cast<std::int64_t>(count) < service->minRobots) {
    Diagnostic& d = diags_.error(call.at, "group service '" + call.service + "' needs at least " + std::to_string(service->minRobots) +
                                              " robots, but only " + std::to_string(count) + " can run it here");
    DiagnosticEngine::note(d, service->at, "min-robots is set here");
  }
}

}  // namespace semo::detail
