// The packet's wire layout and the in-process transport (transport.hpp).
#include "semo/runtime/transport.hpp"

namespace semo::runtime {
namespace {

constexpr std::uint8_t kMagic[4] = {0x53, 0x45, 0x4d, 0x4f};  // "SEMO"

// Little-endian, byte by byte: the same bytes whatever the host's order.
template <class U>
void put(std::uint8_t* at, U v) {
  for (std::size_t i = 0; i < sizeof(U); ++i) at[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

template <class U>
U get(const std::uint8_t* at) {
  U v = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) v |= static_cast<U>(static_cast<U>(at[i]) << (8 * i));
  return v;
}

}  // namespace

std::string_view packetKindName(Packet::Kind kind) {
  switch (kind) {
    case Packet::Kind::Event: return "event";
    case Packet::Kind::Publish: return "publish";
    case Packet::Kind::ChannelSend: return "channel send";
    case Packet::Kind::Heartbeat: return "heartbeat";
    case Packet::Kind::LeaderAnnouncement: return "leader announcement";
    case Packet::Kind::KnowledgeDigest: return "knowledge digest";
    case Packet::Kind::KnowledgeFact: return "knowledge fact";
    case Packet::Kind::Status: return "status";
    case Packet::Kind::Pose: return "pose";
    case Packet::Kind::ChannelReceive: return "channel receive";
  }
  return "unknown";
}

std::string_view decodeErrorName(DecodeError error) {
  switch (error) {
    case DecodeError::None: return "none";
    case DecodeError::Length: return "not 40 bytes";
    case DecodeError::Magic: return "bad magic";
    case DecodeError::Version: return "unknown version";
    case DecodeError::Kind: return "unknown kind";
    case DecodeError::Reserved: return "reserved bytes not zero";
    case DecodeError::Window: return "digest window not a multiple of 64";
  }
  return "unknown";
}

PacketBytes encodePacket(const Packet& packet) {
  PacketBytes b{};
  for (std::size_t i = 0; i < 4; ++i) b[i] = kMagic[i];
  b[4] = kPacketVersion;
  b[5] = static_cast<std::uint8_t>(packet.kind);
  put<std::uint16_t>(&b[6], 0);
  put<std::uint32_t>(&b[8], packet.sender);
  put<std::uint32_t>(&b[12], packet.index);
  put<std::uint32_t>(&b[16], static_cast<std::uint32_t>(packet.value));
  put<std::uint32_t>(&b[20], packet.aux);
  put<std::uint64_t>(&b[24], packet.word);
  put<std::uint64_t>(&b[32], packet.sequence);
  return b;
}

DecodeError decodePacket(std::span<const std::uint8_t> bytes, Packet& out) {
  if (bytes.size() != kPacketBytes) return DecodeError::Length;
  const std::uint8_t* b = bytes.data();
  for (std::size_t i = 0; i < 4; ++i) {
    if (b[i] != kMagic[i]) return DecodeError::Magic;
  }
  if (b[4] != kPacketVersion) return DecodeError::Version;
  if (b[5] < 1 || b[5] > Packet::kLastKind) return DecodeError::Kind;
  if (get<std::uint16_t>(&b[6]) != 0) return DecodeError::Reserved;
  Packet p;
  p.kind = static_cast<Packet::Kind>(b[5]);
  p.sender = get<std::uint32_t>(&b[8]);
  p.index = get<std::uint32_t>(&b[12]);
  p.value = static_cast<std::int32_t>(get<std::uint32_t>(&b[16]));  // two's complement (C++20)
  p.aux = get<std::uint32_t>(&b[20]);
  p.word = get<std::uint64_t>(&b[24]);
  p.sequence = get<std::uint64_t>(&b[32]);
  if (p.kind == Packet::Kind::KnowledgeDigest && (p.value < 0 || p.value % 64 != 0)) return DecodeError::Window;
  out = p;
  return DecodeError::None;
}

void Transport::multicast(std::span<const std::uint32_t> group, const Packet& packet) {
  for (std::uint32_t to : group) {
    if (to != packet.sender) send(to, packet);
  }
}

InProcessTransport::InProcessTransport(const Options& options)
    : robots_(options.robots), capacity_(options.queueCapacity), crashed_(options.robots, 0) {
  queues_.reserve(robots_);
  for (std::uint32_t r = 0; r < robots_; ++r) queues_.emplace_back(capacity_);
  links_.reserve(std::size_t{robots_} * robots_);
  for (std::uint32_t from = 0; from < robots_; ++from) {
    for (std::uint32_t to = 0; to < robots_; ++to) {
      links_.push_back({LinkLoss(options.loss), RandomStream::derive(options.seed, "transport-loss", std::uint64_t{from} * robots_ + to)});
    }
  }
}

void InProcessTransport::send(std::uint32_t to, const Packet& packet) {
  ++counters_.sent;
  const std::uint32_t from = packet.sender;
  if (from >= robots_ || to >= robots_ || crashed_[from] != 0 || crashed_[to] != 0) {
    ++counters_.discarded;
    return;
  }
  Link& l = link(from, to);
  if (l.loss.lose(l.draws)) {
    ++counters_.lost;
    return;
  }
  if (!queues_[to].tryPush(packet)) ++counters_.droppedFull;
}

bool InProcessTransport::poll(std::uint32_t self, Packet& packet) {
  if (self >= robots_ || !queues_[self].tryPop(packet)) return false;
  ++counters_.delivered;
  return true;
}

void InProcessTransport::crash(std::uint32_t robot) {
  if (robot >= robots_ || crashed_[robot] != 0) return;
  crashed_[robot] = 1;
  Packet dropped;
  while (queues_[robot].tryPop(dropped)) ++counters_.discarded;
}

void InProcessTransport::setLinkLoss(std::uint32_t from, std::uint32_t to, const LossModel& model) {
  link(from, to).loss = LinkLoss(model);
}

std::size_t InProcessTransport::queued() const {
  std::size_t n = 0;
  for (const BoundedChannel<Packet>& q : queues_) n += q.size();
  return n;
}

}  // namespace semo::runtime
