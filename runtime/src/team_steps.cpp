// A robot's plans at work: from its control point a plan walks the actions its rows share (calls,
// waits, sensed tests), keeping the rows the tests agree with, and commits the first row whose
// guards hold, atomically with its effects (specs/runtime.md, "The plan interpreter"). Rows are the
// IR's rules, so the step the robot takes is the rule the row names.
#include <algorithm>
#include <cmath>

#include "team.hpp"

namespace semo::runtime::detail {

void Team::startPlan(Id robot, Id plan, Id pc) {
  PlanRun& p = robots_[robot].plans[plan];
  const PlanTable& table = t_.robots[robot].plans[plan];
  abandonWalk(robot, plan);
  p.pc = pc;
  p.restingSince = now_;
  const PlanPoint& point = table.points[pc];
  const bool hasRows = table.firstRow[pc] < table.firstRow[pc + 1];
  if (point.work != kNone) {
    p.phase = PlanRun::Phase::Blocked;  // works in the group service until its goal row can commit
    dirty_ = true;
    return;
  }
  if (!hasRows) {
    p.phase = PlanRun::Phase::Idle;
    return;
  }
  if (point.loopPeriod > 0 && p.iterationStart[pc] >= 0) {
    p.phase = PlanRun::Phase::Period;
    schedule(std::max(now_, p.iterationStart[pc] + toMicros(point.loopPeriod)), QueuedEvent::Kind::Wake, robot, plan, p.generation);
    return;
  }
  p.phase = PlanRun::Phase::Ready;
  schedule(now_, QueuedEvent::Kind::Wake, robot, plan, p.generation);
}

void Team::abandonWalk(Id robot, Id plan) {
  PlanRun& p = robots_[robot].plans[plan];
  ++p.generation;
  if (p.behaviour) bodies_[robot].command(0, 0);  // a call cut short leaves the robot standing
  p.behaviour.reset();
  p.behaviourCall = kNone;
  p.working = false;
  p.phase = PlanRun::Phase::Idle;
}

void Team::advance(Id robot, Id plan) {
  RobotRun& r = robots_[robot];
  if (!r.alive) return;
  PlanRun& p = r.plans[plan];
  const PlanTable& table = t_.robots[robot].plans[plan];
  const Id first = table.firstRow[p.pc], last = table.firstRow[p.pc + 1];
  if (p.phase == PlanRun::Phase::Ready || p.phase == PlanRun::Phase::Period) {
    p.phase = PlanRun::Phase::Busy;
    p.action = 0;
    std::fill(p.keep.begin(), p.keep.begin() + (last - first), std::uint8_t{1});
  }
  for (;;) {
    const Row* next = nullptr;
    for (Id k = first; k < last; ++k) {
      if (p.keep[k - first] != 0 && table.rows[k].actions.size() > p.action) {
        next = &table.rows[k];
        break;
      }
    }
    if (next == nullptr) {
      commit(robot, plan);
      return;
    }
    // The walk goes on: rows that ended before here are not what happened.
    for (Id k = first; k < last; ++k) {
      if (table.rows[k].actions.size() <= p.action) p.keep[k - first] = 0;
    }
    const ActionRow& a = next->actions[p.action];
    ++p.action;
    switch (a.kind) {
      case ActionRow::Kind::Call:
        startCall(robot, plan, a.index);
        return;
      case ActionRow::Kind::Wait:
        p.busyUntil = now_ + toMicros(a.seconds);
        schedule(p.busyUntil, QueuedEvent::Kind::Wake, robot, plan, p.generation);
        return;
      case ActionRow::Kind::LoopStart:
        p.iterationStart[a.index] = now_;
        break;
      case ActionRow::Kind::Sense:
      case ActionRow::Kind::Test: {
        const bool outcome = evaluate(robot, a.index);
        for (Id k = first; k < last; ++k) {
          const std::vector<ActionRow>& acts = table.rows[k].actions;
          if (p.keep[k - first] != 0 && acts[p.action - 1].index == a.index && acts[p.action - 1].expect != outcome) p.keep[k - first] = 0;
        }
        break;
      }
    }
  }
}

bool Team::testsHold(Id robot, const Row& row) const {
  for (const ActionRow& a : row.actions) {
    if (a.kind == ActionRow::Kind::Test && evaluate(robot, a.index) != a.expect) return false;
  }
  return true;
}

bool Team::commit(Id robot, Id plan) {
  RobotRun& r = robots_[robot];
  PlanRun& p = r.plans[plan];
  const PlanTable& table = t_.robots[robot].plans[plan];
  const Id first = table.firstRow[p.pc], last = table.firstRow[p.pc + 1];
  const bool walked = t_.robots[robot].plans[plan].points[p.pc].work == kNone;
  const Row* chosen = nullptr;
  bool testsChanged = false;
  for (Id k = first; k < last && chosen == nullptr; ++k) {
    const Row& row = table.rows[k];
    if (walked && (p.keep[k - first] == 0 || row.actions.size() > p.action)) continue;
    if (!guardsHold(robot, row)) continue;
    if (!testsHold(robot, row)) {
      testsChanged = true;
      continue;
    }
    chosen = &row;
  }
  if (chosen == nullptr) {
    if (testsChanged && walked) {  // a view changed under the walk: walk again from the control point
      p.phase = PlanRun::Phase::Ready;
      schedule(now_, QueuedEvent::Kind::Wake, robot, plan, p.generation);
    } else {
      p.phase = PlanRun::Phase::Blocked;
    }
    return false;
  }
  if (++zeroTimeSteps_ > 100000) {
    stopped_ = true;
    note(robot, TraceEvent::Kind::Violation, "the team keeps stepping without time passing (a loop without a call, a wait or a period)");
    return false;
  }
  beginStep();
  const Row row = *chosen;  // effects may restart this plan; keep the row
  applyEffects(robot, plan, row);
  if (!row.changesMode) startPlan(robot, plan, row.to);
  std::vector<Id> rules;
  if (row.irRule != kNone) rules.push_back(row.irRule);
  const PlanPoint& from = table.points[row.from];
  step(robot, std::move(rules), row.irRule != kNone ? t_.rules[row.irRule].label : "continues " + from.label,
       row.irRule != kNone ? t_.rules[row.irRule].origin : std::string());
  afterStep(robot);
  return true;
}

bool Team::guardsHold(Id robot, const Row& row) const {
  const RobotRun& r = robots_[robot];
  for (const GuardRow& g : row.guards) {
    bool holds = true;
    switch (g.kind) {
      case GuardRow::Kind::InMode: holds = r.mode == g.index; break;
      case GuardRow::Kind::ChannelSpace: holds = channel_[g.index] <= t_.topics[g.index].capacity; break;
      case GuardRow::Kind::ChannelData: holds = channel_[g.index] > 0; break;
      case GuardRow::Kind::GroupStarted:
      case GuardRow::Kind::BlockClear: holds = groupStarted(robot, g.plan, g.index); break;
      case GuardRow::Kind::Elected:
      case GuardRow::Kind::NotElected: {
        const bool elected = r.leads[g.index] != 0 || (noLeader(g.index) && electedLeader(g.index) == robot);
        holds = elected == (g.kind == GuardRow::Kind::Elected);
        break;
      }
      case GuardRow::Kind::Goal: {
        const std::vector<Id>& items = t_.robots[robot].knowledge;
        auto slot = std::find(items.begin(), items.end(), g.index) - items.begin();
        holds = r.knowledge[slot].count() >= g.count;
        break;
      }
    }
    if (!holds) return false;
  }
  // A networked robot runs an election (its own, or as a robot of the `others` arm forming the
  // block first) only once the candidates arriving with it have had time to say so.
  for (const EffectRow& e : row.effects) {
    if (e.kind == EffectRow::Kind::Elect && !settledForElection(robot, e.index)) return false;
  }
  return true;
}

// No other live robot of the team has its program counter of `plan` in the set.
bool Team::groupStarted(Id robot, Id plan, Id pcSet) const {
  if (pcSet == kNone) return true;
  const std::vector<Id>& set = t_.pcSets[pcSet];
  for (Id q : t_.teams[t_.robots[robot].team].robots) {
    if (q == robot || !robots_[q].alive) continue;
    if (std::binary_search(set.begin(), set.end(), robots_[q].plans[plan].pc)) return false;
  }
  return true;
}

// A networked robot elects only once its peers arriving at the formation point with it have told it
// so (NodeLink::electionWindow); the simulator sees them at once.
bool Team::settledForElection(Id robot, Id lb) const {
  if (node_ == nullptr) return true;
  const GroupBlockTable& block = t_.groupBlocks[t_.leaderBlocks[lb].block];
  const PlanRun& p = robots_[robot].plans[block.plan];
  return p.pc != block.formPoint || now_ - p.restingSince >= node_->electionWindow;
}

bool Team::noLeader(Id lb) const {
  for (Id c : t_.leaderBlocks[lb].candidates) {
    if (robots_[c].alive && robots_[c].leads[lb] != 0) return false;
  }
  return true;
}

// The most preferred live candidate resting at the block's formation point now.
Id Team::electedLeader(Id lb) const {
  const LeaderBlockTable& l = t_.leaderBlocks[lb];
  const GroupBlockTable& block = t_.groupBlocks[l.block];
  for (Id c : l.preference) {
    if (robots_[c].alive && robots_[c].plans[block.plan].pc == block.formPoint) return c;
  }
  return kNone;
}

void Team::applyEffects(Id robot, Id plan, const Row& row) {
  RobotRun& r = robots_[robot];
  for (const EffectRow& e : row.effects) {
    switch (e.kind) {
      case EffectRow::Kind::Throw: throwEvent(robot, e.index); break;
      case EffectRow::Kind::EnterMode: enterMode(robot, e.index); break;
      case EffectRow::Kind::Publish: publish(robot, e); break;
      case EffectRow::Kind::Send:
        ++channel_[e.index];
        ++trace_.summary.messagesSent;
        note(robot, TraceEvent::Kind::Send, "sends " + t_.topics[e.index].name, t_.topics[e.index].name);
        if (node_ != nullptr) emitToAll({.kind = Packet::Kind::ChannelSend, .index = e.index});
        break;
      case EffectRow::Kind::Receive:
        --channel_[e.index];
        if (node_ != nullptr) emitToAll({.kind = Packet::Kind::ChannelReceive, .index = e.index});
        break;
      case EffectRow::Kind::Elect: {
        if (node_ != nullptr) {
          nodeElect(e.index);
          break;
        }
        // Decided on the state before the election, as the model's rule is.
        const bool none = noLeader(e.index);
        const Id best = electedLeader(e.index);
        const LeaderBlockTable& l = t_.leaderBlocks[e.index];
        if (none && best != kNone) {
          robots_[best].leads[e.index] = 1;
          leaderChange(e.index, best);
          if (best != robot) {  // elected while still at the formation point: its timeline shows it from now
            setRole(best, l.block, leaderRole(l.block));
          }
        }
        if (none && l.detectsFailures && !l.lossyHeartbeats) {  // the new leader's announcement
          for (Id c : l.candidates) robots_[c].silence[e.index] = 0;
        }
        break;
      }
      case EffectRow::Kind::JoinArm: {
        const GroupBlockTable& block = t_.groupBlocks[e.index];
        const ArmTable& arm = block.arms[e.arm];
        setRole(robot, e.index, arm.leader ? leaderRole(e.index) : arm.label);
        break;
      }
      case EffectRow::Kind::LeaveBlock: {
        const Id lb = t_.groupBlocks[e.index].leader;
        if (lb != kNone) r.leads[lb] = 0;
        setRole(robot, e.index, "");
        break;
      }
    }
  }
  (void)plan;
}

void Team::enterMode(Id robot, Id mode) {
  RobotRun& r = robots_[robot];
  const TeamTable& team = t_.teams[t_.robots[robot].team];
  r.mode = mode;
  // Its services restart: it leaves every block, and stops leading but where the strategy keeps
  // the leadership across modes (on-mode-change="keep") and this mode runs the block again.
  const std::vector<Id>& kept = team.modes[mode].keepsLeaders;
  for (Id lb = 0; lb < r.leads.size(); ++lb) {
    if (std::find(kept.begin(), kept.end(), lb) == kept.end()) r.leads[lb] = 0;
  }
  for (Id b = 0; b < r.roles.size(); ++b) {
    if (!r.roles[b].empty()) setRole(robot, b, "");
  }
  note(robot, TraceEvent::Kind::Mode, team.modes[mode].name, team.modes[mode].name);
  trace_.summary.modeChanges.emplace_back(now(), t_.robots[robot].name + ": " + team.modes[mode].name);
  for (Id p = 0; p < r.plans.size(); ++p) startPlan(robot, p, team.modes[mode].entry[p]);
}

void Team::afterStep(Id robot) {
  RobotRun& r = robots_[robot];
  if (!r.alive || stopped_ || scripted_) return;  // a replay takes mode defaults and takeovers when its trace does
  const TeamTable& team = t_.teams[t_.robots[robot].team];
  const ModeTable& mode = team.modes[r.mode];
  const Id rule = t_.robots[robot].defaultRule[r.mode];
  if (mode.defaultTarget != kNone && rule != kNone &&
      std::all_of(r.plans.begin(), r.plans.end(), [](const PlanRun& p) { return p.pc == 0; })) {
    beginStep();
    enterMode(robot, mode.defaultTarget);
    step(robot, {rule}, t_.rules[rule].label, t_.rules[rule].origin);
  }
  takeovers(robot);
  if (node_ != nullptr) sendStatus();  // the peers' group guards and elections read where it is now
}

void Team::retryBlocked() {
  for (Id robot = 0; robot < robots_.size() && !stopped_; ++robot) {
    RobotRun& r = robots_[robot];
    if (!r.alive || !local(robot)) continue;
    for (Id plan = 0; plan < r.plans.size() && !stopped_; ++plan) {
      if (r.plans[plan].phase == PlanRun::Phase::Blocked) commit(robot, plan);
    }
  }
}

}  // namespace semo::runtime::detail
