// checkPacket (packet_check.hpp): each kind's fields against the mission's tables, as the sender's
// side of team_node.cpp fills them.
#include "semo/runtime/packet_check.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace semo::runtime {

std::string_view packetRefusalName(PacketRefusal r) {
  switch (r) {
    case PacketRefusal::None: return "none";
    case PacketRefusal::Sender: return "sender";
    case PacketRefusal::Kind: return "kind";
    case PacketRefusal::Index: return "index";
    case PacketRefusal::Value: return "value";
    case PacketRefusal::Pose: return "pose";
  }
  return "none";
}

namespace {

bool candidate(const LeaderBlockTable& l, Id robot) {
  return std::find(l.candidates.begin(), l.candidates.end(), robot) != l.candidates.end();
}

PacketRefusal checkStatus(const MissionTables& t, const Packet& p) {
  const RobotTable& sender = t.robots[p.sender];
  const TeamTable& team = t.teams[sender.team];
  if (p.aux >= team.modes.size()) return PacketRefusal::Value;
  if (sender.plans.empty() ? p.index != kNone : p.index >= sender.plans.size()) return PacketRefusal::Index;
  if (!sender.plans.empty() && static_cast<std::uint32_t>(p.value) >= sender.plans[p.index].points.size()) return PacketRefusal::Value;
  // Leader bits only for the blocks it is a candidate of.
  for (std::size_t lb = 0; lb < 64; ++lb) {
    if (((p.word >> lb) & 1U) == 0) continue;
    if (lb >= t.leaderBlocks.size() || !candidate(t.leaderBlocks[lb], p.sender)) return PacketRefusal::Value;
  }
  return PacketRefusal::None;
}

}  // namespace

PacketRefusal checkPacket(const MissionTables& t, Id self, const Packet& p) {
  if (p.sender >= t.robots.size() || p.sender == self || self >= t.robots.size()) return PacketRefusal::Sender;
  const Id team = t.robots[p.sender].team;
  switch (p.kind) {
    case Packet::Kind::Event:
      if (team != t.robots[self].team) return PacketRefusal::Sender;
      return p.index < t.teams[team].events.size() ? PacketRefusal::None : PacketRefusal::Index;
    case Packet::Kind::Publish: {
      if (p.index >= t.topics.size() || t.topics[p.index].reliable) return PacketRefusal::Index;
      const TopicTable& topic = t.topics[p.index];
      // A view holds 0 for none, else a symbol + 1.
      if (!topic.symbols.empty() && (p.value < 1 || static_cast<std::size_t>(p.value) > topic.symbols.size())) return PacketRefusal::Value;
      return PacketRefusal::None;
    }
    case Packet::Kind::ChannelSend:
    case Packet::Kind::ChannelReceive:
      return p.index < t.topics.size() && t.topics[p.index].reliable ? PacketRefusal::None : PacketRefusal::Index;
    case Packet::Kind::Heartbeat:
      if (p.index >= t.leaderBlocks.size()) return PacketRefusal::Index;
      return candidate(t.leaderBlocks[p.index], p.sender) ? PacketRefusal::None : PacketRefusal::Sender;
    case Packet::Kind::LeaderAnnouncement: {
      if (p.index >= t.leaderBlocks.size()) return PacketRefusal::Index;
      const LeaderBlockTable& l = t.leaderBlocks[p.index];
      // Whoever forms the block first elects: a robot of the block's team.
      if (l.candidates.empty() || t.robots[l.candidates.front()].team != team) return PacketRefusal::Sender;
      return p.value >= 0 && candidate(l, static_cast<Id>(p.value)) ? PacketRefusal::None : PacketRefusal::Value;
    }
    case Packet::Kind::KnowledgeFact: {
      if (p.index >= t.knowledge.size()) return PacketRefusal::Index;
      const KnowledgeTable& item = t.knowledge[p.index];
      if (item.team != team) return PacketRefusal::Sender;
      if (p.value < 0 || static_cast<std::size_t>(p.value) >= item.facts.size() || p.aux >= t.robots.size()) return PacketRefusal::Value;
      return PacketRefusal::None;
    }
    case Packet::Kind::Status: return checkStatus(t, p);
    case Packet::Kind::Pose:
      return std::isfinite(std::bit_cast<double>(p.word)) ? PacketRefusal::None : PacketRefusal::Pose;
    case Packet::Kind::KnowledgeDigest: return PacketRefusal::Kind;
  }
  return PacketRefusal::Kind;
}

}  // namespace semo::runtime
