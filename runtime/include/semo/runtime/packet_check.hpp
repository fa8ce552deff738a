#pragma once
// What a networked robot takes from a decoded packet (specs/runtime.md, "Networked robots"): only
// what the mission's tables allow. A packet well-formed on the wire may still name a robot, a
// leader block, an event or a fact the mission does not have, a program counter past its plan, a
// leader that is no candidate, or a pose that is not finite; such a packet is refused before it
// reaches the robot's state, and counted by reason.
#include <array>
#include <cstdint>
#include <string_view>

#include "semo/runtime/tables.hpp"
#include "semo/runtime/transport.hpp"

namespace semo::runtime {

enum class PacketRefusal : std::uint8_t {
  None,
  Sender,  // no robot of the mission, the receiver itself, or one that may not send this (not a
           // candidate of the leader block, not of the team)
  Kind,    // a kind this runtime never sends (KnowledgeDigest)
  Index,   // an event, topic, channel, leader block, knowledge item or plan the mission does not have
  Value,   // a value outside its domain: a topic's symbol, a fact, a leader, a mode, a program
           // counter, leader bits of blocks the sender is no candidate of
  Pose,    // a position or heading that is not finite
};
inline constexpr std::size_t kPacketRefusals = 6;
[[nodiscard]] std::string_view packetRefusalName(PacketRefusal r);

// Whether robot `self` of `tables` takes packet `p`, and if not, why.
[[nodiscard]] PacketRefusal checkPacket(const MissionTables& tables, Id self, const Packet& p);

// Refused packets, counted per reason (index: PacketRefusal).
struct PacketRefusals {
  std::array<std::uint64_t, kPacketRefusals> count{};
  void add(PacketRefusal r) { ++count[static_cast<std::size_t>(r)]; }
  [[nodiscard]] std::uint64_t total() const {
    std::uint64_t n = 0;
    for (std::size_t i = 1; i < kPacketRefusals; ++i) n += count[i];
    return n;
  }
};

}  // namespace semo::runtime
