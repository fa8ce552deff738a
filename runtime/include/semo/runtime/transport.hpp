#pragma once
// How a robot program exchanges messages with its team (specs/runtime.md, "Transports"): fixed-size
// packets behind one small interface. The in-process transport (every robot of a team in one
// process, seeded per-link loss, crashes) is the default; UDP (udp_transport.hpp) and Cyclone DDS
// (dds_transport.hpp), for one process per robot, put a Packet on the wire with encodePacket /
// decodePacket.
//
// The simulator's own network (team_network.cpp) does not go through a Transport: it is the exact
// mirror of the IR's message slots (specs/runtime.md, section 3). Networked robots (robot_node.hpp)
// do.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

#include "semo/runtime/channel.hpp"
#include "semo/runtime/loss.hpp"
#include "semo/runtime/random.hpp"

namespace semo::runtime {

// One message between two robots of a team. Plain and trivially copyable; the fields each kind uses:
//
//   kind                index               value                   aux            word
//   Event               event               0                       0              sender's Lamport clock
//   Publish             topic               the value               0              0
//   ChannelSend         topic (a channel)   the value               0              0
//   Heartbeat           leader block        1 if the sender leads   0              heartbeat period number
//   LeaderAnnouncement  leader block        the leader (robot id)   0              election term
//   KnowledgeDigest     knowledge item      first fact of the window (a multiple of 64)
//                                                                   0              bit i: fact value + i held
//   KnowledgeFact       knowledge item      the fact                robot of the stamp   Lamport clock of the stamp
//   Status              plan                its program counter     the sender's mode    bit b: it leads leader block b
//   Pose                0                   x, micrometres          y, micrometres (two's complement)
//                                                                                  the heading's double, bit for bit
//   ChannelReceive      topic (a channel)   0                       0              0
//
// Status and Pose carry a networked robot's state to its peers (specs/runtime.md, "Networked
// robots"): what their group guards and elections read; ChannelSend and ChannelReceive keep every
// robot's count of a reliable channel.
// `sequence` is the sender's own count of what it sent, carried unchanged, for a receiver to tell
// gaps and duplicates. A field a kind does not use is 0 (transports carry it unchanged anyway).
struct Packet {
  enum class Kind : std::uint8_t {
    Event = 1,
    Publish = 2,
    ChannelSend = 3,
    Heartbeat = 4,
    LeaderAnnouncement = 5,
    KnowledgeDigest = 6,
    KnowledgeFact = 7,
    Status = 8,
    Pose = 9,
    ChannelReceive = 10,
  };
  static constexpr std::uint8_t kLastKind = 10;

  Kind kind = Kind::Event;
  std::uint32_t sender = 0;  // robot id
  std::uint32_t index = 0;
  std::int32_t value = 0;
  std::uint32_t aux = 0;
  std::uint64_t word = 0;
  std::uint64_t sequence = 0;

  friend bool operator==(const Packet&, const Packet&) = default;
};
static_assert(std::is_trivially_copyable_v<Packet> && std::is_standard_layout_v<Packet>);

[[nodiscard]] std::string_view packetKindName(Packet::Kind kind);

// ------------------------------------------------------------------ the wire layout (version 1)
//
//   offset  size  field
//        0     4  magic "SEMO" (0x53 0x45 0x4d 0x4f)
//        4     1  version (1)
//        5     1  kind (1..10)
//        6     2  reserved, 0
//        8     4  sender     (little-endian, as every field below)
//       12     4  index
//       16     4  value      (two's complement)
//       20     4  aux
//       24     8  word
//       32     8  sequence
//   40 bytes in all.
inline constexpr std::size_t kPacketBytes = 40;
inline constexpr std::uint8_t kPacketVersion = 1;
using PacketBytes = std::array<std::uint8_t, kPacketBytes>;

enum class DecodeError : std::uint8_t {
  None,
  Length,    // not exactly kPacketBytes bytes
  Magic,     // not "SEMO"
  Version,   // another version of the layout
  Kind,      // a kind byte outside 1..10
  Reserved,  // the reserved bytes are not 0
  Window,    // a KnowledgeDigest whose first fact is not a multiple of 64
};
[[nodiscard]] std::string_view decodeErrorName(DecodeError error);

[[nodiscard]] PacketBytes encodePacket(const Packet& packet);
// Reads a packet from bytes that came off a wire; `out` is set only when the result is None.
[[nodiscard]] DecodeError decodePacket(std::span<const std::uint8_t> bytes, Packet& out);

// ------------------------------------------------------------------ the interface

// What a transport did with the packets handed to it. Every (packet, receiver) pair that send or
// multicast took counts once in `sent` and, at any time, once in exactly one of delivered, lost,
// droppedFull, discarded, or is still on its way (InProcessTransport::queued()).
struct TransportCounters {
  std::uint64_t sent = 0;
  std::uint64_t delivered = 0;    // handed to the receiver by poll
  std::uint64_t lost = 0;         // lost on the link (the loss model)
  std::uint64_t droppedFull = 0;  // reached a receiver whose queue was full
  std::uint64_t discarded = 0;    // from or to a robot not running (crashed, or not of the team), or
                                  // waiting for one when it crashed
  std::uint64_t refused = 0;      // received but not taken: not a packet of the team's format
};

class Transport {
 public:
  virtual ~Transport() = default;

  // Sends `packet` from packet.sender to robot `to`. Never blocks; a packet may be lost or dropped
  // on the way, and the sender is not told.
  virtual void send(std::uint32_t to, const Packet& packet) = 0;
  // Sends to every robot of `group` but the sender itself (a team, a group's members, the
  // candidates of a leader block). Transports with a real multicast override it.
  virtual void multicast(std::span<const std::uint32_t> group, const Packet& packet);
  // The next packet that reached robot `self`, if any: true and `packet` set, or false at once.
  virtual bool poll(std::uint32_t self, Packet& packet) = 0;

  [[nodiscard]] virtual TransportCounters counters() const = 0;
};

// ------------------------------------------------------------------ in process

// All robots of a team in one process, driven by one thread (not thread-safe). Each robot has a
// queue of `queueCapacity` packets, allocated once: a packet that reaches a full queue is dropped
// and counted, the queue never grows. Each link (from, to) decides its own losses with its own
// LinkLoss and its own RandomStream, derived from the seed and the link, so the same seed gives
// the same losses on a link whatever the traffic on the others. Packets on one link (indeed to one
// receiver) arrive in the order they were sent. Sending and polling allocate nothing.
class InProcessTransport final : public Transport {
 public:
  struct Options {
    std::uint32_t robots = 0;
    std::size_t queueCapacity = 64;
    LossModel loss;  // every link's; p = 0: nothing is lost
    std::uint64_t seed = 0;
  };
  explicit InProcessTransport(const Options& options);

  void send(std::uint32_t to, const Packet& packet) override;
  bool poll(std::uint32_t self, Packet& packet) override;
  [[nodiscard]] TransportCounters counters() const override { return counters_; }

  // The robot stops for good: its queue is emptied, nothing it sends goes out, nothing reaches it.
  void crash(std::uint32_t robot);
  [[nodiscard]] bool crashed(std::uint32_t robot) const { return crashed_[robot] != 0; }
  // One link's own loss model instead of the common one (its loss state starts afresh; its random
  // stream goes on).
  void setLinkLoss(std::uint32_t from, std::uint32_t to, const LossModel& model);

  [[nodiscard]] std::uint32_t robots() const { return robots_; }
  [[nodiscard]] std::size_t queued(std::uint32_t robot) const { return queues_[robot].size(); }
  [[nodiscard]] std::size_t queued() const;
  [[nodiscard]] std::size_t queueCapacity() const { return capacity_; }

 private:
  struct Link {
    LinkLoss loss;
    RandomStream draws;
  };
  [[nodiscard]] Link& link(std::uint32_t from, std::uint32_t to) { return links_[std::size_t{from} * robots_ + to]; }

  std::uint32_t robots_;
  std::size_t capacity_;
  std::vector<BoundedChannel<Packet>> queues_;  // per receiver
  std::vector<Link> links_;                     // per (from, to)
  std::vector<std::uint8_t> crashed_;
  TransportCounters counters_;
};

}  // namespace semo::runtime
