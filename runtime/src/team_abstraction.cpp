// The abstraction function (specs/runtime.md): the running team's state read as the IR's variables,
// and the bookkeeping of every step (the trace's Step events with the variables they changed, the
// observer's conformance check).
#include <fmt/format.h>

#include "team.hpp"

namespace semo::runtime::detail {

std::string formatSeconds(Micros t) { return fmt::format("{:.6f}", toSeconds(t)); }

void Team::abstractState(std::vector<std::int32_t>& out) const {
  out.resize(t_.abstraction.size());
  for (std::size_t v = 0; v < t_.abstraction.size(); ++v) {
    const AbstractVar& var = t_.abstraction[v];
    using K = AbstractVar::Kind;
    if (var.kind == K::Crashed) {
      out[v] = crashed_[var.team];
      continue;
    }
    if (var.kind == K::Channel) {  // a reliable channel belongs to no robot: a crash does not empty it
      out[v] = channel_[var.index];
      continue;
    }
    if (var.kind == K::Holding || var.kind == K::AtPoints) {  // a count of the team's live robots
      out[v] = teamCount(var);
      continue;
    }
    const RobotRun& r = robots_[var.robot];
    if (var.kind == K::Alive) {
      out[v] = r.alive ? 1 : 0;
      continue;
    }
    if (!r.alive) {  // a crashed robot's variables read as their initial values (the model clears them)
      out[v] = var.init;
      continue;
    }
    switch (var.kind) {
      case K::Mode: out[v] = static_cast<std::int32_t>(r.mode); break;
      case K::Pc: out[v] = static_cast<std::int32_t>(r.plans[var.index].pc); break;
      case K::Event: out[v] = r.eventPending[var.index]; break;
      case K::View: out[v] = r.view[var.index]; break;
      case K::Message: out[v] = r.message[var.index]; break;
      case K::Channel: out[v] = channel_[var.index]; break;
      case K::Leads: out[v] = r.leads[var.index]; break;
      case K::Silence: out[v] = r.silence[var.index]; break;
      case K::LostHeartbeats: out[v] = r.lostRun[var.index]; break;
      case K::Knows: out[v] = r.knowledge[static_cast<std::size_t>(varSlot_[v])].count(); break;
      case K::Alive:
      case K::Crashed:
      case K::Holding:
      case K::AtPoints: break;
    }
  }
}

// How many live robots of the count's team hold a counted number of facts of its item, or have
// their pc of its plan at a counted point. A networked robot counts the peers as it sees them.
std::int32_t Team::teamCount(const AbstractVar& var) const {
  std::int32_t n = 0;
  for (Id robot : t_.teams[var.team].robots) {
    const RobotRun& r = robots_[robot];
    if (!r.alive) continue;
    std::int32_t value = 0;
    if (var.kind == AbstractVar::Kind::AtPoints) {
      if (var.index >= r.plans.size()) continue;
      value = static_cast<std::int32_t>(r.plans[var.index].pc);
    } else {
      const std::vector<Id>& items = t_.robots[robot].knowledge;
      const auto slot = static_cast<std::size_t>(std::find(items.begin(), items.end(), var.index) - items.begin());
      if (slot >= items.size()) continue;
      value = r.knowledge[slot].count();
    }
    if (std::binary_search(var.values.begin(), var.values.end(), value)) ++n;
  }
  return n;
}

void Team::beginStep() { abstractState(before_); }

void Team::step(Id robot, std::vector<Id> rules, std::string what, std::string origin) {
  abstractState(after_);
  // Convergence needs every robot's facts: a networked robot has only its own.
  if (node_ == nullptr) {
    for (Id k = 0; k < t_.knowledge.size(); ++k) convergence(k);
  }
  lastStep_.assign(rules.begin(), rules.end());
  dirty_ = true;
  TraceEvent e;
  e.t = now();
  e.robot = robot == kNone ? kNoRobot : robot;
  e.kind = TraceEvent::Kind::Step;
  for (Id rule : rules) e.rule += (e.rule.empty() ? "" : ",") + t_.rules[rule].name;
  e.label = std::move(what);
  e.origin = std::move(origin);
  for (std::size_t v = 0; v < after_.size(); ++v) {
    if (before_[v] != after_[v]) e.changes.push_back({t_.abstraction[v].name, before_[v], after_[v]});
  }
  if (observer_ != nullptr && !outside_) {
    StepReport report;
    report.t = e.t;
    report.robot = e.robot;
    report.rules = rules;
    report.before = &before_;
    report.after = &after_;
    report.what = e.label;
    ++trace_.summary.stepsChecked;
    if (!observer_->onStep(report)) {
      ++trace_.summary.mismatches;
      stopped_ = true;
      trace_.events.push_back(e);
      note(robot, TraceEvent::Kind::Violation, observer_->why());
      trace_.summary.violations.push_back(observer_->why());
      return;
    }
  }
  if (rules.empty() && e.changes.empty()) return;  // a stutter: nothing worth a line
  trace_.events.push_back(std::move(e));
}

void Team::note(Id robot, TraceEvent::Kind kind, std::string label, std::string detail, Id peer) {
  TraceEvent e;
  e.t = now();
  e.robot = robot == kNone ? kNoRobot : robot;
  e.kind = kind;
  e.label = std::move(label);
  e.detail = std::move(detail);
  e.peer = peer == kNone ? kNoRobot : peer;
  trace_.events.push_back(std::move(e));
}

void Team::setRole(Id robot, Id groupBlock, std::string role, std::string why) {
  std::string& now = robots_[robot].roles[groupBlock];
  if (now == role && why.empty()) return;
  const std::string& block = t_.groupBlocks[groupBlock].name;
  note(robot, TraceEvent::Kind::Role, !why.empty() ? why : role.empty() ? "leaves " + block : role, role);
  trace_.events.back().block = block;
  now = std::move(role);
}

std::string Team::leaderRole(Id groupBlock) const { return "leader of " + t_.groupBlocks[groupBlock].name; }

void Team::leaderChange(Id lb, Id robot) {
  LeaderChange c;
  c.block = t_.leaderBlocks[lb].name;
  c.t = now();
  c.from = leaderNow_[lb] == kNone ? kNoRobot : leaderNow_[lb];
  c.to = robot;
  if (leaderNow_[lb] != kNone && !robots_[leaderNow_[lb]].alive) c.sinceCrash = now() - crashTime_[leaderNow_[lb]];
  if (leaderNow_[lb] == robot) return;
  leaderNow_[lb] = robot;
  trace_.summary.leaderChanges.push_back(c);
}

// Since when every live robot of the team that takes part (works in the service, or holds facts of
// it) has held the same facts of the item, and some fact: the start of the agreement that lasts, not
// the first one (a robot that finds a new fact, or joins the service empty-handed, breaks it; a
// crash may restore it). Called after every step, the only way the stores, the robots' service
// membership or their liveness change; -1 while they disagree.
void Team::convergence(Id k) {
  double& at = trace_.summary.convergedAt[k].second;
  const KnowledgeStore* first = nullptr;
  bool agreed = true;
  for (Id q : t_.teams[t_.knowledge[k].team].robots) {
    if (!robots_[q].alive) continue;
    const std::vector<Id>& items = t_.robots[q].knowledge;
    const auto slot = static_cast<std::size_t>(std::find(items.begin(), items.end(), k) - items.begin());
    const KnowledgeStore& store = robots_[q].knowledge[slot];
    if (store.count() == 0 && !inService(q, k)) continue;  // never took part: a Burger does not search papers
    if (store.count() == 0 || (first != nullptr && !store.sameFactsAs(*first))) {
      agreed = false;
      break;
    }
    if (first == nullptr) first = &store;
  }
  agreed = agreed && first != nullptr;
  if (!agreed) at = -1;
  else if (at < 0) at = now();
}

}  // namespace semo::runtime::detail
