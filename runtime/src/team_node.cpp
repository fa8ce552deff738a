// A networked robot (robot_node.hpp, specs/runtime.md "Networked robots"): the Team runs one robot
// of its own; every other robot is a replica kept from that robot's packets. What the simulator does
// to another robot's state directly goes out as a packet and is done by the robot it is about:
//
//   the simulator                              a networked robot
//   a throw fills the others' event slots      an Event packet; the receiver fills its own slot
//   a publish fills the others' message slots  a Publish packet; the receiver fills its own slot
//   the channel's count changes                ChannelSend / ChannelReceive to every peer
//   a heartbeat period of the whole block      each candidate's own period: a leader sends Heartbeat,
//                                              a waiting candidate counts a silent period unless one came
//   a gossip round of the whole team           each robot broadcasts its facts (KnowledgeFact), each
//                                              working robot merges what reaches it
//   an election sets the leader's belief       a LeaderAnnouncement; the leader sets its own
//   group guards and elections read the team   they read the replicas (Status packets: mode, program
//                                              counters, leader beliefs; Pose packets)
//   a crash                                    the robot falls silent; a peer silent for the peer
//                                              timeout is taken as crashed
#include <algorithm>
#include <bit>
#include <cmath>

#include "team.hpp"

namespace semo::runtime::detail {

namespace {

std::int32_t micrometres(double metres) {
  return static_cast<std::int32_t>(std::clamp(std::llround(metres * 1e6), -2147483647LL, 2147483647LL));
}
}  // namespace

void Team::emit(Id to, Packet p) {
  const Id self = node_->self;
  if (!robots_[self].alive) return;  // a crashed robot sends nothing
  p.sender = self;
  p.sequence = ++sequence_;
  node_->transport->send(to, p);
}

void Team::emitToTeam(Id team, Packet p) {
  const Id self = node_->self;
  if (!robots_[self].alive) return;
  p.sender = self;
  p.sequence = ++sequence_;
  node_->transport->multicast(t_.teams[team].robots, p);
}

void Team::emitToAll(Packet p) {
  const Id self = node_->self;
  if (!robots_[self].alive) return;
  p.sender = self;
  p.sequence = ++sequence_;
  node_->transport->multicast(everyone_, p);  // one datagram on an IP multicast group
}

void Team::pollNetwork() {
  Packet p;
  while (node_->transport->poll(node_->self, p)) onPacket(p);
  while (dirty_ && !stopped_) {
    dirty_ = false;
    retryBlocked();
  }
}

void Team::onPacket(const Packet& p) {
  const Id self = node_->self;
  // Only what the mission's tables allow reaches the robot's state; a refused packet does not even
  // count as its sender speaking.
  if (const PacketRefusal why = checkPacket(t_, self, p); why != PacketRefusal::None) {
    refusals_.add(why);
    return;
  }
  RobotRun& me = robots_[self];
  RobotRun& peer = robots_[p.sender];
  lastHeard_[p.sender] = now_;
  if (!peer.alive) {  // taken as crashed, yet it speaks: it was only late
    peer.alive = true;
    aliveFlags_[p.sender] = true;
    note(p.sender, TraceEvent::Kind::Note, "heard again: no longer taken as crashed");
  }
  dirty_ = true;  // whatever it says may let a blocked plan go on
  if (!me.alive) return;
  switch (p.kind) {
    case Packet::Kind::Event:
      if (p.index >= me.eventPending.size() || t_.robots[self].eventDeliveryRule[p.index] == kNone || me.eventPending[p.index] != 0) return;
      me.eventPending[p.index] = 1;
      me.lamport = std::max(me.lamport, p.word);
      schedule(now_, QueuedEvent::Kind::DeliverEvent, self, p.index);
      return;
    case Packet::Kind::Publish: {
      if (p.index >= me.message.size()) return;
      const bool onItsWay = me.message[p.index] != 0;
      me.message[p.index] = p.value;
      if (!onItsWay) schedule(now_, QueuedEvent::Kind::DeliverMessage, self, p.index);
      return;
    }
    case Packet::Kind::ChannelSend:
      if (p.index < channel_.size()) ++channel_[p.index];
      return;
    case Packet::Kind::ChannelReceive:
      if (p.index < channel_.size() && channel_[p.index] > 0) --channel_[p.index];
      return;
    case Packet::Kind::Heartbeat: {
      if (p.index >= t_.leaderBlocks.size()) return;
      if (peer.leads[p.index] == 0) leaderChange(p.index, p.sender);
      peer.leads[p.index] = 1;
      heard_[p.index] = 1;
      for (Id d : t_.leaderBlocks[p.index].preference) {
        if (d == self) break;
        if (d == p.sender) heardPreferred_[p.index] = 1;
      }
      return;
    }
    case Packet::Kind::LeaderAnnouncement: {
      const Id lb = p.index, leader = static_cast<Id>(p.value);
      if (lb >= t_.leaderBlocks.size() || leader >= robots_.size()) return;
      const LeaderBlockTable& l = t_.leaderBlocks[lb];
      if (l.detectsFailures && !l.lossyHeartbeats) me.silence[lb] = 0;  // the new leader announces itself
      if (leader != self) {
        if (robots_[leader].leads[lb] == 0) leaderChange(lb, leader);
        robots_[leader].leads[lb] = 1;
        return;
      }
      if (me.leads[lb] != 0) return;
      beginStep();
      me.leads[lb] = 1;
      setRole(self, l.block, leaderRole(l.block));
      leaderChange(lb, self);
      step(self, {}, "elected leader of " + t_.groupBlocks[l.block].name);
      sendStatus();
      return;
    }
    case Packet::Kind::KnowledgeFact: {
      const std::vector<Id>& items = t_.robots[self].knowledge;
      const auto slot = static_cast<std::size_t>(std::find(items.begin(), items.end(), p.index) - items.begin());
      if (slot >= items.size() || !inService(self, p.index)) return;
      const KnowledgeTable& item = t_.knowledge[p.index];
      if (lose(GossipLink, self, item.lossy, 0)) {  // injected loss (--loss), as the simulator's
        ++trace_.summary.messagesLost;
        note(self, TraceEvent::Kind::Drop, item.name + " gossip lost", item.name, p.sender);
        return;
      }
      beginStep();
      if (!me.knowledge[slot].mergeFact(static_cast<std::uint32_t>(p.value), {p.word, p.aux}, me.lamport)) return;
      const std::size_t count = static_cast<std::size_t>(me.knowledge[slot].count());
      const Id rule = count < t_.robots[self].learnRule[slot].size() ? t_.robots[self].learnRule[slot][count] : kNone;
      const std::string fact = p.value >= 0 && static_cast<std::size_t>(p.value) < item.facts.size() ? item.facts[static_cast<std::size_t>(p.value)] : std::to_string(p.value);
      note(self, TraceEvent::Kind::Fact, "learns " + item.name + " from " + t_.robots[p.sender].name + ": " + fact, item.name, p.sender);
      step(self, rule == kNone ? std::vector<Id>{} : std::vector<Id>{rule}, rule == kNone ? "learns " + item.name : t_.rules[rule].label,
           rule == kNone ? std::string() : t_.rules[rule].origin);
      afterStep(self);
      return;
    }
    case Packet::Kind::Status: {
      const TeamTable& team = t_.teams[t_.robots[p.sender].team];
      if (p.aux < team.modes.size()) peer.mode = p.aux;
      if (p.index < peer.plans.size()) peer.plans[p.index].pc = static_cast<Id>(p.value);
      for (Id lb = 0; lb < peer.leads.size() && lb < 64; ++lb) {
        const std::uint8_t leads = ((p.word >> lb) & 1U) != 0 ? 1 : 0;
        if (leads != 0 && peer.leads[lb] == 0) leaderChange(lb, p.sender);  // the summary's leader changes, as this robot learns of them
        peer.leads[lb] = leads;
      }
      return;
    }
    case Packet::Kind::Pose:
      poses_[p.sender] = {static_cast<double>(p.value) / 1e6, static_cast<double>(static_cast<std::int32_t>(p.aux)) / 1e6,
                          std::bit_cast<double>(p.word)};
      return;
    case Packet::Kind::KnowledgeDigest: return;  // not sent by this runtime
  }
}

// What the peers read of this robot: its mode, program counters and leader beliefs, and its pose.
void Team::sendStatus() {
  const Id self = node_->self;
  const RobotRun& me = robots_[self];
  if (!me.alive) return;
  std::uint64_t leads = 0;
  for (Id lb = 0; lb < me.leads.size() && lb < 64; ++lb) leads |= std::uint64_t{me.leads[lb]} << lb;
  for (Id plan = 0; plan < me.plans.size(); ++plan) {
    emitToAll({.kind = Packet::Kind::Status, .index = plan, .value = static_cast<std::int32_t>(me.plans[plan].pc), .aux = me.mode, .word = leads});
  }
  if (me.plans.empty()) emitToAll({.kind = Packet::Kind::Status, .index = kNone, .aux = me.mode, .word = leads});
  const Pose& at = poses_[self];
  emitToAll({.kind = Packet::Kind::Pose, .value = micrometres(at.x), .aux = static_cast<std::uint32_t>(micrometres(at.y)),
             .word = std::bit_cast<std::uint64_t>(at.theta)});
}

// Every status period: the robot's status, and a peer silent for the peer timeout is taken as crashed.
void Team::statusTick() {
  schedule(now_ + node_->statusPeriod, QueuedEvent::Kind::Status);
  sendStatus();
  dirty_ = true;  // a plan waiting for time to pass (an election window) tries again
  for (Id r = 0; r < robots_.size(); ++r) {
    RobotRun& peer = robots_[r];
    if (r == node_->self || !peer.alive || now_ - lastHeard_[r] <= node_->peerTimeout) continue;
    peer.alive = false;
    aliveFlags_[r] = false;
    crashTime_[r] = now();
    std::fill(peer.leads.begin(), peer.leads.end(), std::uint8_t{0});
    note(r, TraceEvent::Kind::Crash, "silent for " + formatSeconds(now_ - lastHeard_[r]) + " s: taken as crashed");
    dirty_ = true;
  }
}

// This robot's share of a heartbeat period of leader block lb.
void Team::nodeHeartbeat(Id lb) {
  const LeaderBlockTable& l = t_.leaderBlocks[lb];
  schedule(now_ + toMicros(l.heartbeat), QueuedEvent::Kind::Heartbeat, lb);
  const Id self = node_->self;
  RobotRun& me = robots_[self];
  if (!me.alive) return;
  if (me.leads[lb] != 0) {
    for (Id c : l.candidates) {
      if (c != self) emit(c, {.kind = Packet::Kind::Heartbeat, .index = lb, .value = 1});
    }
  }
  const bool isWaiting = waiting(self, lb);
  bool heard = heard_[lb] != 0;
  if (isWaiting && heard && l.lossyHeartbeats && lose(HeartbeatLink, self, true, 0)) {  // injected loss
    heard = false;
    ++trace_.summary.messagesLost;
    note(self, TraceEvent::Kind::Drop, "heartbeat lost", "heartbeat");
  }
  beginStep();
  const std::int32_t silence = me.silence[lb];
  me.silence[lb] = isWaiting ? (heard ? 0 : std::min(me.silence[lb] + 1, l.timeoutPeriods)) : 0;
  const bool stepsDown = me.leads[lb] != 0 && heardPreferred_[lb] != 0;
  if (stepsDown) {
    me.leads[lb] = 0;
    setRole(self, l.block, "candidate", "steps down: hears a preferred leader");
  }
  heard_[lb] = heardPreferred_[lb] = 0;
  if (silence != me.silence[lb] || stepsDown) step(self, {}, "a heartbeat period passes");
  takeovers(self);
  if (stepsDown) sendStatus();
}

// This robot's share of a gossip round: every fact it holds, with its stamp, to its team.
void Team::nodeGossip(Id k) {
  const KnowledgeTable& item = t_.knowledge[k];
  schedule(now_ + toMicros(item.period), QueuedEvent::Kind::Gossip, k);
  const Id self = node_->self;
  const std::vector<Id>& items = t_.robots[self].knowledge;
  const auto slot = static_cast<std::size_t>(std::find(items.begin(), items.end(), k) - items.begin());
  if (!robots_[self].alive || slot >= items.size()) return;
  const KnowledgeStore& store = robots_[self].knowledge[slot];
  if (store.count() == 0) return;
  const std::size_t peers = t_.teams[item.team].robots.size() - 1;
  for (std::uint32_t f = 0; f < store.facts().size(); ++f) {
    if (!store.holds(f)) continue;
    const FactStamp stamp = store.stamp(f);
    for (std::int64_t copy = 0; copy <= item.retransmissions; ++copy) {
      emitToTeam(item.team, {.kind = Packet::Kind::KnowledgeFact, .index = k, .value = static_cast<std::int32_t>(f), .aux = stamp.robot,
                             .word = stamp.lamport});
    }
    trace_.summary.messagesSent += peers;
  }
}

// The election of leader block lb, as this robot sees the candidates forming it.
void Team::nodeElect(Id lb) {
  const Id self = node_->self;
  const LeaderBlockTable& l = t_.leaderBlocks[lb];
  const bool none = noLeader(lb);
  const Id best = electedLeader(lb);
  if (none && best != kNone) {
    robots_[best].leads[lb] = 1;  // its own belief, or this robot's replica of it until its status says
    leaderChange(lb, best);
    if (best == self) {
      setRole(self, l.block, leaderRole(l.block));
    }
    for (Id c : l.candidates) {
      if (c != self) emit(c, {.kind = Packet::Kind::LeaderAnnouncement, .index = lb, .value = static_cast<std::int32_t>(best)});
    }
  }
  if (none && l.detectsFailures && !l.lossyHeartbeats) robots_[self].silence[lb] = 0;
}

}  // namespace semo::runtime::detail
