#pragma once
// UDP as a Transport (specs/runtime.md, "Transports"): one socket per robot program, bound to its
// own endpoint; a packet to a robot is one datagram (encodePacket's 40 bytes) to that robot's
// endpoint. Multicast is one datagram per member (unicast fan-out: it works on any network, and on
// loopback, where IP multicast often does not), or, with an IP multicast group (UdpMulticast, for a
// LAN), one datagram to the group when it goes to every other robot of the mission (Status, Pose:
// most of the traffic); to fewer, it fans out. Best effort, as UDP is: a lost datagram is lost;
// what the protocol above needs again, it sends again (Status every period, gossip every round).
// Receiving never blocks; malformed datagrams are counted and dropped. Sending and polling
// allocate nothing.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/runtime/transport.hpp"

namespace semo::runtime {

struct UdpEndpoint {
  std::string host = "127.0.0.1";  // a dotted IPv4 address
  std::uint16_t port = 0;
};

// An IP multicast group every robot of the mission joins (a LAN: 239.x.y.z, administratively scoped).
struct UdpMulticast {
  UdpEndpoint group;                 // its address and port
  std::string interface = "0.0.0.0";  // the address of the interface to use (0.0.0.0: the system's choice)
};

class UdpTransport final : public Transport {
 public:
  // `endpoints[r]` is robot r's; this program binds endpoints[self].
  UdpTransport(std::uint32_t self, std::vector<UdpEndpoint> endpoints, std::optional<UdpMulticast> multicast = std::nullopt);
  ~UdpTransport() override;
  UdpTransport(const UdpTransport&) = delete;
  UdpTransport& operator=(const UdpTransport&) = delete;

  // Opens and binds the socket; false with `error` set (an address in use, a host that is not an
  // IPv4 address).
  bool open(std::string& error);

  void send(std::uint32_t to, const Packet& packet) override;
  void multicast(std::span<const std::uint32_t> group, const Packet& packet) override;
  bool poll(std::uint32_t self, Packet& packet) override;
  [[nodiscard]] TransportCounters counters() const override { return counters_; }
  [[nodiscard]] std::uint64_t malformed() const { return malformed_; }
  [[nodiscard]] std::uint64_t groupDatagrams() const { return groupDatagrams_; }  // sent to the IP group

 private:
  std::uint32_t self_;
  std::vector<UdpEndpoint> endpoints_;
  std::vector<std::array<std::uint8_t, 16>> addresses_;  // sockaddr_in per robot, resolved once
  int socket_ = -1;
  std::optional<UdpMulticast> multicast_;
  std::array<std::uint8_t, 16> groupAddress_{};
  int groupSocket_ = -1;  // bound to the group's port, a member of the group
  TransportCounters counters_;
  std::uint64_t malformed_ = 0;
  std::uint64_t groupDatagrams_ = 0;
  bool receive(int socket, Packet& packet);
};

// "host:port" -> an endpoint (nullopt when it is not an IPv4 address and a port).
std::optional<UdpEndpoint> parseUdpEndpoint(const std::string& text);

}  // namespace semo::runtime
