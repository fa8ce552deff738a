// Replay of a counterexample (replay.hpp): every IR rule of the script is taken where the runtime
// takes it, by the code that takes it in a free run (a plan row's guards and effects, a delivery, a
// heartbeat period, a takeover, a merge, a crash), with the choices the counterexample made forced:
// which row (what the environment answered), whether a message was lost, who crashes. A step the
// running team cannot take stops the replay with the reason.
#include <algorithm>

#include <fmt/format.h>

#include "team.hpp"

namespace semo::runtime {

std::vector<RuleSite> ruleSites(const MissionTables& t) {
  std::vector<RuleSite> sites(t.rules.size());
  auto at = [&](Id rule) -> RuleSite* { return rule < sites.size() ? &sites[rule] : nullptr; };
  using K = RuleSite::Kind;
  for (Id robot = 0; robot < t.robots.size(); ++robot) {
    const RobotTable& r = t.robots[robot];
    for (Id plan = 0; plan < r.plans.size(); ++plan) {
      for (Id k = 0; k < r.plans[plan].rows.size(); ++k) {
        if (RuleSite* s = at(r.plans[plan].rows[k].irRule)) *s = {K::Row, robot, plan, k, 0, 0};
      }
    }
    if (RuleSite* s = at(r.crashRule)) *s = {K::Crash, robot, kNone, kNone, 0, 0};
    for (Id e = 0; e < r.eventDeliveryRule.size(); ++e) {
      if (RuleSite* s = at(r.eventDeliveryRule[e])) *s = {K::EventDelivery, robot, kNone, e, 0, 0};
      if (RuleSite* s = at(r.eventLossRule[e])) *s = {K::EventLoss, robot, kNone, e, 0, 0};
    }
    for (Id topic = 0; topic < r.messageDeliveryRule.size(); ++topic) {
      if (RuleSite* s = at(r.messageDeliveryRule[topic])) *s = {K::MessageDelivery, robot, kNone, topic, 0, 0};
      if (RuleSite* s = at(r.messageLossRule[topic])) *s = {K::MessageLoss, robot, kNone, topic, 0, 0};
    }
    for (Id mode = 0; mode < r.defaultRule.size(); ++mode) {
      if (RuleSite* s = at(r.defaultRule[mode])) *s = {K::ModeDefault, robot, kNone, mode, 0, 0};
    }
    for (Id slot = 0; slot < r.takeoverRule.size(); ++slot) {
      if (RuleSite* s = at(r.takeoverRule[slot])) *s = {K::Takeover, robot, kNone, slot, 0, 0};
    }
    for (Id d = 0; d < r.discoverRules.size(); ++d) {
      if (RuleSite* s = at(r.discoverRules[d].rule)) *s = {K::Discover, robot, r.discoverRules[d].plan, d, 0, 0};
    }
    for (Id slot = 0; slot < r.learnRule.size(); ++slot) {
      for (std::size_t n = 0; n < r.learnRule[slot].size(); ++n) {
        if (RuleSite* s = at(r.learnRule[slot][n])) *s = {K::Learn, robot, kNone, slot, 0, static_cast<std::int64_t>(n)};
      }
    }
  }
  for (Id lb = 0; lb < t.leaderBlocks.size(); ++lb) {
    for (std::size_t mask = 0; mask < t.leaderBlocks[lb].heartbeatRule.size(); ++mask) {
      if (RuleSite* s = at(t.leaderBlocks[lb].heartbeatRule[mask])) *s = {K::Heartbeat, kNone, kNone, lb, mask, 0};
    }
  }
  return sites;
}

namespace detail {

std::string Team::forceRow(Id robot, Id plan, Id k) {
  const PlanTable& table = t_.robots[robot].plans[plan];
  const Row& row = table.rows[k];
  const PlanRun& p = robots_[robot].plans[plan];
  if (p.pc != row.from) {
    return fmt::format("{} rests at {} of its plan {}; the step starts at {}", t_.robots[robot].name, table.points[p.pc].label, table.name,
                       table.points[row.from].label);
  }
  if (!guardsHold(robot, row)) return "its guard does not hold in the running team";
  if (!testsHold(robot, row)) return "its condition on the robot's topic views does not hold";
  // The walk's calls, waits and sensed tests: the counterexample chose what the environment answered
  // by choosing the row.
  beginStep();
  const Row chosen = row;  // effects may restart this plan; keep the row
  applyEffects(robot, plan, chosen);
  if (!chosen.changesMode) startPlan(robot, plan, chosen.to);
  step(robot, {chosen.irRule}, t_.rules[chosen.irRule].label, t_.rules[chosen.irRule].origin);
  return {};
}

std::string Team::forceStep(Id rule, const RuleSite& site) {
  using K = RuleSite::Kind;
  if (site.kind == K::None) return "no step of the runtime is this rule (the projection did not index it)";
  if (site.kind != K::Heartbeat && !robots_[site.robot].alive) return t_.robots[site.robot].name + " has crashed";
  RobotRun& r = site.robot == kNone ? robots_.front() : robots_[site.robot];
  const RobotTable* table = site.robot == kNone ? nullptr : &t_.robots[site.robot];
  switch (site.kind) {
    case K::None: break;
    case K::Row: return forceRow(site.robot, site.plan, site.index);
    case K::Crash: crash(site.robot, "as the counterexample chooses"); return {};
    case K::EventDelivery:
    case K::EventLoss:
      if (r.eventPending[site.index] == 0) return "no event " + t_.teams[table->team].events[site.index].name + " is on its way to it";
      forcedLoss_ = site.kind == K::EventLoss ? 1 : 0;
      deliverEvent(site.robot, site.index);
      forcedLoss_ = -1;
      return {};
    case K::MessageDelivery:
    case K::MessageLoss:
      if (r.message[site.index] == 0) return "no value of " + t_.topics[site.index].name + " is on its way to it";
      forcedLoss_ = site.kind == K::MessageLoss ? 1 : 0;
      deliverMessage(site.robot, site.index);
      forcedLoss_ = -1;
      return {};
    case K::ModeDefault: {
      const ModeTable& mode = t_.teams[table->team].modes[site.index];
      if (r.mode != site.index) return "it is not in mode " + mode.name;
      if (!std::all_of(r.plans.begin(), r.plans.end(), [](const PlanRun& p) { return p.pc == 0; })) return "some plan of it is not done";
      beginStep();
      enterMode(site.robot, mode.defaultTarget);
      step(site.robot, {rule}, t_.rules[rule].label, t_.rules[rule].origin);
      return {};
    }
    case K::Takeover: {
      if (!canTakeOver(site.robot, site.index)) {
        const Id lb = table->leaderBlocks[site.index];
        return fmt::format("it does not suspect the leader of {} (silent periods {} of {}, waiting: {})", t_.leaderBlocks[lb].name,
                           r.silence[lb], t_.leaderBlocks[lb].timeoutPeriods, waiting(site.robot, lb) ? "yes" : "no");
      }
      takeOver(site.robot, site.index);
      return {};
    }
    case K::Discover: {
      const RobotTable::Discover& d = table->discoverRules[site.index];
      if (r.plans[d.plan].pc != d.pc) return "it does not work in the service";
      if (!groupStarted(site.robot, d.plan, d.started)) return "its group has not started the service";
      const auto slot = static_cast<std::size_t>(std::find(table->knowledge.begin(), table->knowledge.end(), d.knowledge) - table->knowledge.begin());
      const KnowledgeTable& item = t_.knowledge[d.knowledge];
      for (std::uint32_t fact = 0; fact < item.facts.size(); ++fact) {
        if (r.knowledge[slot].holds(fact)) continue;
        discoverFact(site.robot, d, fact);  // the first fact it lacks (the model counts facts: any will do)
        return {};
      }
      return "it already holds every fact of " + item.name;
    }
    case K::Learn: {
      // The model's rule says how many facts the learner holds after, not from whom: the first
      // live teammate whose facts merged with the learner's make exactly that many teaches it.
      const Id k = table->knowledge[site.index];
      if (!inService(site.robot, k)) return "it does not work in the service";
      const std::size_t slot = site.index;
      const KnowledgeStore& mine = robots_[site.robot].knowledge[slot];
      for (Id teacher : t_.teams[t_.knowledge[k].team].robots) {
        if (teacher == site.robot || !robots_[teacher].alive) continue;
        const std::vector<Id>& theirItems = t_.robots[teacher].knowledge;
        const auto from = static_cast<std::size_t>(std::find(theirItems.begin(), theirItems.end(), k) - theirItems.begin());
        if (from >= theirItems.size()) continue;
        std::int64_t merged = 0;
        for (std::uint32_t f = 0; f < t_.knowledge[k].facts.size(); ++f) {
          merged += mine.holds(f) || robots_[teacher].knowledge[from].holds(f) ? 1 : 0;
        }
        if (merged == site.count) {
          learnFrom(site.robot, teacher, k);
          return {};
        }
      }
      return "no live teammate holds the facts that would bring it to " + std::to_string(site.count);
    }
    case K::Heartbeat: {
      const LeaderBlockTable& l = t_.leaderBlocks[site.index];
      bool anyWaiting = false;
      for (Id c : l.candidates) anyWaiting = anyWaiting || waiting(c, site.index);
      if (!anyWaiting) return "no candidate of " + l.name + " waits for heartbeats";
      forcedHeartbeatLoss_ = site.extra;
      heartbeatPeriod(site.index);
      forcedHeartbeatLoss_ = kNoForcedMask;
      return {};
    }
  }
  return "unknown step";
}

void Team::runScript(const std::vector<Id>& rules, const ReplayOptions& options) {
  scripted_ = true;
  for (Id robot = 0; robot < robots_.size(); ++robot) {
    const TeamTable& team = t_.teams[t_.robots[robot].team];
    for (Id p = 0; p < robots_[robot].plans.size(); ++p) startPlan(robot, p, team.modes[robots_[robot].mode].entry[p]);
  }
  abstractState(before_);
  samplePoses();
  const std::vector<RuleSite> sites = ruleSites(t_);
  for (std::size_t k = 0; k < rules.size() && !stopped_; ++k) {
    now_ += toMicros(options.pace);
    const Id rule = rules[k];
    lastStep_.clear();
    std::string why = rule < sites.size() ? forceStep(rule, sites[rule]) : "the model has no such rule";
    if (why.empty() && !stopped_ && (lastStep_.size() != 1 || lastStep_.front() != rule)) {
      std::string took;
      for (Id other : lastStep_) took += (took.empty() ? "" : ", ") + t_.rules[other].name;
      why = "the running team took " + (took.empty() ? std::string("no step the model sees") : took) + " instead";
    }
    if (!why.empty()) {
      stopped_ = true;
      const std::string name = rule < t_.rules.size() ? t_.rules[rule].name : std::to_string(rule);
      const std::string message = fmt::format("step {} ({}): the running team cannot take it: {}", k + 1, name, why);
      note(kNone, TraceEvent::Kind::Violation, message);
      trace_.summary.violations.push_back(message);
      break;
    }
    samplePoses();
  }
  scripted_ = false;
  if (!stopped_ && options.settle > 0) {
    note(kNone, TraceEvent::Kind::Note, fmt::format("the counterexample's steps are done: the team runs on freely for {:g} s", options.settle));
    startTimers();
    processUntil(now_ + toMicros(options.settle));
    finish();
  } else {
    now_ += toMicros(options.pace);  // the picture shows the last state for one more pace
    samplePoses();
    trace_.duration = now();
  }
}

}  // namespace detail

SimTrace replay(const MissionTables& tables, const World& world, const TaskLibrary& library, const std::vector<Id>& rules,
                const SimulationOptions& options, const ReplayOptions& replayOptions, StepObserver* observer) {
  SimTrace trace = detail::emptyTrace(tables, world, options);
  trace.faults = "as the counterexample chooses";
  detail::Team team(tables, world, library, options, observer, trace);
  team.runScript(rules, replayOptions);
  return trace;
}

}  // namespace semo::runtime
