// The in-process network and the team's timers, mirroring the IR's network variables one for one
// (specs/runtime.md, "Messages"): one slot per (receiver, event) and per (receiver, topic), where a
// newer value overwrites an older one still on its way; a delivery after a latency, where the loss
// model decides between the IR's delivery rule and its loss rule. Heartbeat periods, takeovers and
// gossip rounds are steps of their own at the periods the strategy gives.
#include <algorithm>

#include "team.hpp"

namespace semo::runtime::detail {

bool Team::lose(Id kind, Id receiver, bool lossy, std::int64_t retransmissions) {
  if (forcedLoss_ >= 0) return forcedLoss_ != 0;  // replay: the counterexample decides
  if (!lossy || options_.loss <= 0) return false;
  return links_[kind * robots_.size() + receiver].loseWithRetransmissions(lossDraws_, static_cast<int>(retransmissions));
}

// The heartbeat to candidate i (robot c) of a period: in a replay, lost as the counterexample says.
bool Team::loseHeartbeat(std::size_t i, Id c) {
  if (forcedHeartbeatLoss_ != kNoForcedMask) return ((forcedHeartbeatLoss_ >> i) & 1U) != 0;
  return lose(HeartbeatLink, c, true, 0);
}

Micros Team::latency() { return toMicros(0.001 + 0.004 * latency_.uniform()); }

void Team::throwEvent(Id robot, Id event) {
  const TeamTable& team = t_.teams[t_.robots[robot].team];
  note(robot, TraceEvent::Kind::Send, "throws " + team.events[event].name, team.events[event].name);
  if (node_ != nullptr) {  // each receiver keeps its own slot (team_node.cpp)
    for (Id q : team.robots) {
      if (q == robot || t_.robots[q].eventDeliveryRule[event] == kNone) continue;
      ++trace_.summary.messagesSent;
      emit(q, {.kind = Packet::Kind::Event, .index = event, .word = robots_[robot].lamport});
    }
    return;
  }
  for (Id q : team.robots) {
    RobotRun& r = robots_[q];
    if (q == robot || !r.alive || t_.robots[q].eventDeliveryRule[event] == kNone) continue;
    ++trace_.summary.messagesSent;
    if (r.eventPending[event] != 0) continue;  // one on its way already: the model's slot holds one
    r.eventPending[event] = 1;
    schedule(now_ + latency(), QueuedEvent::Kind::DeliverEvent, q, event);
  }
}

void Team::deliverEvent(Id robot, Id event) {
  RobotRun& r = robots_[robot];
  if (!r.alive || r.eventPending[event] == 0) return;
  const RobotTable& table = t_.robots[robot];
  const TeamTable& team = t_.teams[table.team];
  const EventTable& ev = team.events[event];
  beginStep();
  r.eventPending[event] = 0;
  if (table.eventLossRule[event] != kNone && lose(EventLink, robot, ev.lossy, ev.retransmissions)) {
    ++trace_.summary.messagesLost;
    note(robot, TraceEvent::Kind::Drop, "event " + ev.name + " lost", ev.name);
    step(robot, {table.eventLossRule[event]}, t_.rules[table.eventLossRule[event]].label);
    return;
  }
  note(robot, TraceEvent::Kind::Deliver, "event " + ev.name, ev.name);
  for (const auto& [caught, target] : team.modes[r.mode].catches) {
    if (caught == event) {
      enterMode(robot, target);
      break;
    }
  }
  const Id rule = table.eventDeliveryRule[event];
  step(robot, {rule}, t_.rules[rule].label, t_.rules[rule].origin);
  afterStep(robot);
}

void Team::publish(Id robot, const EffectRow& e) {
  const TopicTable& topic = t_.topics[e.index];
  const auto value = static_cast<std::int32_t>(e.value.number);
  note(robot, TraceEvent::Kind::Send, "publishes " + topic.name, topic.name + " = " + e.value.text);
  // To every robot of the team it is published to. The model keeps a view (and a message slot) only
  // for robots whose conditions read the topic; the others (a display, a log) still get it, as
  // steps the model does not see.
  for (Id q : t_.teams[e.team].robots) {
    RobotRun& r = robots_[q];
    if (q == robot) {
      if (std::find(topic.subscribers.begin(), topic.subscribers.end(), q) != topic.subscribers.end()) r.view[e.index] = value;
      continue;
    }
    if (node_ != nullptr) {  // the receiver keeps its own message slot (team_node.cpp)
      ++trace_.summary.messagesSent;
      emit(q, {.kind = Packet::Kind::Publish, .index = e.index, .value = value});
      continue;
    }
    if (!r.alive) continue;
    ++trace_.summary.messagesSent;
    const bool onItsWay = r.message[e.index] != 0;
    r.message[e.index] = value;
    if (!onItsWay) schedule(now_ + latency(), QueuedEvent::Kind::DeliverMessage, q, e.index);
  }
}

void Team::deliverMessage(Id robot, Id topic) {
  RobotRun& r = robots_[robot];
  if (!r.alive || r.message[topic] == 0) return;
  const RobotTable& table = t_.robots[robot];
  beginStep();
  const Id lossRule = table.messageLossRule[topic], deliveryRule = table.messageDeliveryRule[topic];
  const bool seen = deliveryRule != kNone;  // the model keeps this robot's view of the topic
  if ((lossRule != kNone || !seen) && lose(MessageLink, robot, t_.topics[topic].lossy, 0)) {
    r.message[topic] = 0;
    ++trace_.summary.messagesLost;
    note(robot, TraceEvent::Kind::Drop, t_.topics[topic].name + " lost", t_.topics[topic].name);
    step(robot, seen ? std::vector<Id>{lossRule} : std::vector<Id>{}, seen ? t_.rules[lossRule].label : "loses " + t_.topics[topic].name);
    return;
  }
  r.view[topic] = r.message[topic];
  r.message[topic] = 0;
  note(robot, TraceEvent::Kind::Deliver, t_.topics[topic].name, t_.topics[topic].name);
  step(robot, seen ? std::vector<Id>{deliveryRule} : std::vector<Id>{}, seen ? t_.rules[deliveryRule].label : "receives " + t_.topics[topic].name);
  afterStep(robot);
}

// A live candidate in the `others` part of the block, listening for the leader's heartbeats.
bool Team::waiting(Id robot, Id lb) const {
  const RobotRun& r = robots_[robot];
  if (!r.alive || r.leads[lb] != 0) return false;
  const GroupBlockTable& block = t_.groupBlocks[t_.leaderBlocks[lb].block];
  const ArmTable& others = block.arms[t_.leaderBlocks[lb].othersArm];
  const Id pc = r.plans[block.plan].pc;
  return pc >= others.first && pc < others.end;
}

// One heartbeat period of a leader block: every live leader sends a heartbeat; a waiting candidate
// that hears none counts a silent period; a leader that hears a more preferred one steps down.
void Team::heartbeatPeriod(Id lb) {
  const LeaderBlockTable& l = t_.leaderBlocks[lb];
  if (!scripted_) schedule(now_ + toMicros(l.heartbeat), QueuedEvent::Kind::Heartbeat, lb);
  bool anyWaiting = false;
  for (Id c : l.candidates) anyWaiting = anyWaiting || waiting(c, lb);
  if (!anyWaiting) return;  // the model's period rule is not enabled: nothing it sees changes
  const std::size_t n = l.candidates.size();
  std::size_t mask = 0;
  std::vector<std::int32_t>& silence = scratchA_;
  std::vector<std::int32_t>& lost = scratchB_;
  std::vector<std::uint8_t>& leads = scratchC_;
  silence.assign(n, 0), lost.assign(n, 0), leads.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Id c = l.candidates[i];
    const RobotRun& r = robots_[c];
    bool heard = false;
    for (Id d : l.candidates) heard = heard || (d != c && robots_[d].alive && robots_[d].leads[lb] != 0);
    const bool isWaiting = waiting(c, lb);
    const std::int32_t louder = std::min(r.silence[lb] + 1, l.timeoutPeriods);
    if (heard) trace_.summary.messagesSent += isWaiting ? 1 : 0;
    if (isWaiting && heard && l.lossyHeartbeats && loseHeartbeat(i, c)) {
      if (r.lostRun[lb] >= l.lossBurst && !outside_) {
        outside_ = true;
        trace_.summary.outsideAssumptions = "at " + formatSeconds(now_) + " s more than " + std::to_string(l.lossBurst) +
                                            " heartbeats in a row were lost on the way to " + t_.robots[c].name;
      }
      mask |= std::size_t{1} << i;
      ++trace_.summary.messagesLost;
      note(c, TraceEvent::Kind::Drop, "heartbeat lost", "heartbeat");
      silence[i] = louder;
      lost[i] = r.lostRun[lb] + 1;
      leads[i] = r.leads[lb];
      continue;
    }
    silence[i] = isWaiting ? (heard ? 0 : louder) : 0;
    lost[i] = heard ? 0 : r.lostRun[lb];
    bool better = false;
    for (Id d : l.preference) {
      if (d == c) break;
      better = better || (robots_[d].alive && robots_[d].leads[lb] != 0);
    }
    leads[i] = r.leads[lb] != 0 && !better ? 1 : 0;
  }
  beginStep();
  for (std::size_t i = 0; i < n; ++i) {
    RobotRun& r = robots_[l.candidates[i]];
    if (r.leads[lb] != 0 && leads[i] == 0) setRole(l.candidates[i], l.block, "candidate", "steps down: hears a preferred leader");
    r.silence[lb] = silence[i];
    r.lostRun[lb] = l.lossyHeartbeats ? lost[i] : 0;
    r.leads[lb] = leads[i];
  }
  const Id rule = mask < l.heartbeatRule.size() ? l.heartbeatRule[mask] : kNone;
  step(kNone, rule == kNone ? std::vector<Id>{} : std::vector<Id>{rule}, rule == kNone ? "a heartbeat period passes" : t_.rules[rule].label,
       rule == kNone ? std::string() : t_.rules[rule].origin);
  for (Id c : l.candidates) takeovers(c);
}

// A candidate that heard no heartbeat for the failure timeout suspects the leader and takes over
// (in a replay only when the counterexample says so: takeOver is then called on its own).
void Team::takeovers(Id robot) {
  if (scripted_) return;
  const RobotTable& table = t_.robots[robot];
  for (std::size_t slot = 0; slot < table.leaderBlocks.size(); ++slot) {
    if (canTakeOver(robot, slot)) takeOver(robot, slot);
  }
}

bool Team::canTakeOver(Id robot, std::size_t slot) const {
  const RobotTable& table = t_.robots[robot];
  const Id lb = table.leaderBlocks[slot];
  return table.takeoverRule[slot] != kNone && waiting(robot, lb) && robots_[robot].silence[lb] >= t_.leaderBlocks[lb].timeoutPeriods;
}

void Team::takeOver(Id robot, std::size_t slot) {
  RobotRun& r = robots_[robot];
  const Id lb = t_.robots[robot].leaderBlocks[slot];
  const Id rule = t_.robots[robot].takeoverRule[slot];
  const LeaderBlockTable& l = t_.leaderBlocks[lb];
  const GroupBlockTable& block = t_.groupBlocks[l.block];
  beginStep();
  r.leads[lb] = 1;
  r.silence[lb] = 0;
  r.lostRun[lb] = 0;
  if (!l.lossyHeartbeats) {  // the new leader's announcement
    for (Id d : l.candidates) robots_[d].silence[lb] = 0;
  }
  setRole(robot, l.block, leaderRole(l.block));
  leaderChange(lb, robot);
  startPlan(robot, block.plan, block.arms[l.leaderArm].entry);
  step(robot, {rule}, t_.rules[rule].label, t_.rules[rule].origin);
}

bool Team::inService(Id robot, Id k) const {
  for (const RobotTable::Discover& d : t_.robots[robot].discoverRules) {
    if (d.knowledge == k && robots_[robot].plans[d.plan].pc == d.pc) return true;
  }
  return false;
}

// One gossip round of a knowledge item: every live robot of the team broadcasts what it holds;
// each robot working in the service merges what reaches it (one learn step when it learnt facts).
void Team::gossip(Id k) {
  const KnowledgeTable& item = t_.knowledge[k];
  schedule(now_ + toMicros(item.period), QueuedEvent::Kind::Gossip, k);
  const TeamTable& team = t_.teams[item.team];
  for (Id sender : team.robots) {
    const RobotRun& s = robots_[sender];
    const std::vector<Id>& senderItems = t_.robots[sender].knowledge;
    const auto from = std::find(senderItems.begin(), senderItems.end(), k) - senderItems.begin();
    if (!s.alive || s.knowledge[from].count() == 0) continue;
    for (Id q : team.robots) {
      if (q == sender || !robots_[q].alive || !inService(q, k)) continue;
      ++trace_.summary.messagesSent;
      if (lose(GossipLink, q, item.lossy, item.retransmissions)) {
        ++trace_.summary.messagesLost;
        note(q, TraceEvent::Kind::Drop, item.name + " gossip lost", item.name, sender);
        continue;
      }
      learnFrom(q, sender, k);
    }
  }
}

// Robot q merges what `sender` holds of item k: one learn step when it learnt facts.
bool Team::learnFrom(Id q, Id sender, Id k) {
  const KnowledgeTable& item = t_.knowledge[k];
  const std::vector<Id>& senderItems = t_.robots[sender].knowledge;
  const auto from = std::find(senderItems.begin(), senderItems.end(), k) - senderItems.begin();
  RobotRun& r = robots_[q];
  const std::vector<Id>& items = t_.robots[q].knowledge;
  const auto slot = std::find(items.begin(), items.end(), k) - items.begin();
  const int before = r.knowledge[slot].count();
  std::vector<char> had(item.facts.size());
  for (std::size_t f = 0; f < had.size(); ++f) had[f] = r.knowledge[slot].holds(static_cast<std::uint32_t>(f)) ? 1 : 0;
  beginStep();
  r.knowledge[slot].merge(robots_[sender].knowledge[from], r.lamport);
  const int after = r.knowledge[slot].count();
  if (after == before) return false;  // nothing new: the model sees no change
  std::string learnt;  // the facts it did not hold before, by name
  for (std::size_t f = 0; f < had.size(); ++f) {
    if (had[f] == 0 && r.knowledge[slot].holds(static_cast<std::uint32_t>(f))) learnt += (learnt.empty() ? "" : ", ") + item.facts[f];
  }
  const Id rule = t_.robots[q].learnRule[slot][static_cast<std::size_t>(after)];
  note(q, TraceEvent::Kind::Fact, "learns " + item.name + " from " + t_.robots[sender].name + ": " + learnt, item.name, sender);
  step(q, rule == kNone ? std::vector<Id>{} : std::vector<Id>{rule}, rule == kNone ? "learns " + item.name : t_.rules[rule].label,
       rule == kNone ? std::string() : t_.rules[rule].origin);
  afterStep(q);
  return true;
}

// A robot working in a group service finds the facts within reach it does not hold yet.
void Team::discover(Id robot, Id plan) {
  RobotRun& r = robots_[robot];
  const PlanRun& p = r.plans[plan];
  const RobotTable& table = t_.robots[robot];
  for (const RobotTable::Discover& d : table.discoverRules) {
    if (d.plan != plan || d.pc != p.pc) continue;
    const KnowledgeTable& item = t_.knowledge[d.knowledge];
    const auto slot = std::find(table.knowledge.begin(), table.knowledge.end(), d.knowledge) - table.knowledge.begin();
    for (const FactSite& site : world_.facts) {
      if (site.knowledge != item.name) continue;
      const auto fact = std::find(item.facts.begin(), item.facts.end(), site.fact) - item.facts.begin();
      if (fact == static_cast<std::ptrdiff_t>(item.facts.size()) || r.knowledge[slot].holds(static_cast<std::uint32_t>(fact))) continue;
      const Pose& at = poses_[robot];
      const double dx = at.x - site.at.x, dy = at.y - site.at.y;
      if (dx * dx + dy * dy > site.radius * site.radius) continue;
      discoverFact(robot, d, static_cast<std::uint32_t>(fact));
    }
  }
}

void Team::discoverFact(Id robot, const RobotTable::Discover& d, std::uint32_t fact) {
  RobotRun& r = robots_[robot];
  const RobotTable& table = t_.robots[robot];
  const KnowledgeTable& item = t_.knowledge[d.knowledge];
  const auto slot = std::find(table.knowledge.begin(), table.knowledge.end(), d.knowledge) - table.knowledge.begin();
  beginStep();
  r.knowledge[slot].discover(fact, robot, r.lamport);
  note(robot, TraceEvent::Kind::Fact, "finds " + item.name + ": " + item.facts[fact], item.name + ": " + item.facts[fact]);
  step(robot, {d.rule}, t_.rules[d.rule].label, t_.rules[d.rule].origin);
}

void Team::crash(Id robot, const std::string& why) {
  RobotRun& r = robots_[robot];
  if (!r.alive) return;
  const RobotTable& table = t_.robots[robot];
  const TeamTable& team = t_.teams[table.team];
  beginStep();
  r.alive = false;
  aliveFlags_[robot] = false;
  crashTime_[robot] = now();
  ++crashed_[table.team];
  if ((table.crashRule == kNone || crashed_[table.team] > team.crashBudget) && !outside_) {
    outside_ = true;
    trace_.summary.outsideAssumptions = "at " + formatSeconds(now_) + " s " + table.name + " crashed, beyond the model's assumption of at most " +
                                        std::to_string(team.crashBudget) + " crash(es) in " + team.name;
  }
  for (Id p = 0; p < r.plans.size(); ++p) abandonWalk(robot, p);
  std::fill(r.eventPending.begin(), r.eventPending.end(), std::uint8_t{0});
  std::fill(r.message.begin(), r.message.end(), 0);
  std::fill(r.leads.begin(), r.leads.end(), std::uint8_t{0});
  bodies_[robot].command(0, 0);
  note(robot, TraceEvent::Kind::Crash, "crashes (" + why + ")");
  step(robot, table.crashRule == kNone ? std::vector<Id>{} : std::vector<Id>{table.crashRule}, "crashes", "crash");
}

}  // namespace semo::runtime::detail
