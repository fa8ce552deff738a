// UdpTransport (udp_transport.hpp): POSIX datagram sockets, non-blocking.
#include "semo/runtime/udp_transport.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace semo::runtime {

namespace {

bool toAddress(const UdpEndpoint& e, sockaddr_in& out) {
  std::memset(&out, 0, sizeof out);
  out.sin_family = AF_INET;
  out.sin_port = htons(e.port);
  return inet_pton(AF_INET, e.host.c_str(), &out.sin_addr) == 1;
}

}  // namespace

std::optional<UdpEndpoint> parseUdpEndpoint(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) return std::nullopt;
  UdpEndpoint e;
  e.host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const unsigned long p = std::stoul(port);
  if (p == 0 || p > 65535) return std::nullopt;
  e.port = static_cast<std::uint16_t>(p);
  sockaddr_in check{};
  if (!toAddress(e, check)) return std::nullopt;
  return e;
}

UdpTransport::UdpTransport(std::uint32_t self, std::vector<UdpEndpoint> endpoints, std::optional<UdpMulticast> multicast)
    : self_(self), endpoints_(std::move(endpoints)), multicast_(std::move(multicast)) {}

UdpTransport::~UdpTransport() {
  if (socket_ >= 0) ::close(socket_);
  if (groupSocket_ >= 0) ::close(groupSocket_);
}

bool UdpTransport::open(std::string& error) {
  if (self_ >= endpoints_.size()) {
    error = "no endpoint for this robot";
    return false;
  }
  addresses_.assign(endpoints_.size(), {});
  for (std::size_t r = 0; r < endpoints_.size(); ++r) {
    sockaddr_in a{};
    if (!toAddress(endpoints_[r], a)) {
      error = "'" + endpoints_[r].host + "' is not an IPv4 address";
      return false;
    }
    static_assert(sizeof a <= 16);
    std::memcpy(addresses_[r].data(), &a, sizeof a);
  }
  socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (socket_ < 0) {
    error = std::string("cannot open a UDP socket: ") + std::strerror(errno);
    return false;
  }
  // Room for bursts (a Status per plan and a Pose from every peer at once).
  const int buffer = 1 << 20;  // also the group socket's
  ::setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
  sockaddr_in own{};
  std::memcpy(&own, addresses_[self_].data(), sizeof own);
  if (::bind(socket_, reinterpret_cast<const sockaddr*>(&own), sizeof own) != 0) {
    error = "cannot bind " + endpoints_[self_].host + ":" + std::to_string(endpoints_[self_].port) + ": " + std::strerror(errno);
    ::close(socket_);
    socket_ = -1;
    return false;
  }
  if (!multicast_) return true;
  // The group: datagrams to it go out on the interface, to this host's members too (loop), one hop.
  sockaddr_in group{};
  in_addr interface{};
  if (!toAddress(multicast_->group, group) || !IN_MULTICAST(ntohl(group.sin_addr.s_addr))) {
    error = "'" + multicast_->group.host + "' is not an IPv4 multicast address (224.0.0.0 to 239.255.255.255)";
    return false;
  }
  if (inet_pton(AF_INET, multicast_->interface.c_str(), &interface) != 1) {
    error = "'" + multicast_->interface + "' is not an IPv4 address";
    return false;
  }
  std::memcpy(groupAddress_.data(), &group, sizeof group);
  const unsigned char loop = 1, ttl = 1;
  ::setsockopt(socket_, IPPROTO_IP, IP_MULTICAST_IF, &interface, sizeof interface);
  ::setsockopt(socket_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
  ::setsockopt(socket_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
  groupSocket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  const int reuse = 1;  // every robot program on this host binds the group's port
  ::setsockopt(groupSocket_, SOL_SOCKET, SO_REUSEADDR, &reuse, sizeof reuse);
  ::setsockopt(groupSocket_, SOL_SOCKET, SO_REUSEPORT, &reuse, sizeof reuse);
  ::setsockopt(groupSocket_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
  sockaddr_in any = group;
  any.sin_addr.s_addr = htonl(INADDR_ANY);
  ip_mreq membership{};
  membership.imr_multiaddr = group.sin_addr;
  membership.imr_interface = interface;
  if (groupSocket_ < 0 || ::bind(groupSocket_, reinterpret_cast<const sockaddr*>(&any), sizeof any) != 0 ||
      ::setsockopt(groupSocket_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
    error = "cannot join the multicast group " + multicast_->group.host + ":" + std::to_string(multicast_->group.port) + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

void UdpTransport::multicast(std::span<const std::uint32_t> group, const Packet& packet) {
  std::size_t others = 0;
  for (const std::uint32_t r : group) others += r != packet.sender ? 1 : 0;
  if (groupSocket_ < 0 || others + 1 != endpoints_.size() || group.size() != endpoints_.size()) {
    Transport::multicast(group, packet);  // to fewer than every other robot: one datagram each
    return;
  }
  counters_.sent += others;
  ++groupDatagrams_;
  const PacketBytes bytes = encodePacket(packet);
  sockaddr_in a{};
  std::memcpy(&a, groupAddress_.data(), sizeof a);
  if (::sendto(socket_, bytes.data(), bytes.size(), MSG_DONTWAIT | MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&a), sizeof a) !=
      static_cast<ssize_t>(bytes.size())) {
    counters_.lost += others;
  }
}

void UdpTransport::send(std::uint32_t to, const Packet& packet) {
  ++counters_.sent;
  if (socket_ < 0 || to >= addresses_.size() || to == self_) {
    ++counters_.discarded;
    return;
  }
  const PacketBytes bytes = encodePacket(packet);
  sockaddr_in a{};
  std::memcpy(&a, addresses_[to].data(), sizeof a);
  // A full socket buffer or an unreachable port: the datagram is lost, as any.
  if (::sendto(socket_, bytes.data(), bytes.size(), MSG_DONTWAIT | MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&a), sizeof a) !=
      static_cast<ssize_t>(bytes.size())) {
    ++counters_.lost;
  }
}

bool UdpTransport::poll(std::uint32_t /*self*/, Packet& packet) {
  return (socket_ >= 0 && receive(socket_, packet)) || (groupSocket_ >= 0 && receive(groupSocket_, packet));
}

bool UdpTransport::receive(int socket, Packet& packet) {
  std::array<std::uint8_t, 64> buffer{};
  for (;;) {
    const ssize_t n = ::recv(socket, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n < 0) return false;  // nothing waiting (or an error, which is the same to a poller)
    if (decodePacket(std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(n)), packet) != DecodeError::None ||
        packet.sender >= endpoints_.size()) {
      ++malformed_;
      ++counters_.refused;
      continue;
    }
    if (packet.sender == self_) continue;  // its own datagram to the group, looped back
    ++counters_.delivered;
    return true;
  }
}

}  // namespace semo::runtime
