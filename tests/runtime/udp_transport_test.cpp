// UdpTransport (runtime/udp_transport.hpp) on loopback: packets arrive whole and in order on an idle
// link, multicast fans out, malformed datagrams are counted and dropped, a taken port is an error.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "semo/runtime/udp_transport.hpp"

namespace semo::runtime {
namespace {

// A port range of its own (the e2e tests use 47000..47400).
constexpr std::uint16_t kBase = 47600;

std::vector<UdpEndpoint> endpoints(std::uint16_t base, int n) {
  std::vector<UdpEndpoint> out;
  for (int i = 0; i < n; ++i) out.push_back({"127.0.0.1", static_cast<std::uint16_t>(base + i)});
  return out;
}

// Polls until `want` packets arrived or a second passed.
std::vector<Packet> receive(UdpTransport& t, std::uint32_t self, std::size_t want) {
  std::vector<Packet> out;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  Packet p;
  while (out.size() < want && std::chrono::steady_clock::now() < until) {
    if (t.poll(self, p)) out.push_back(p);
    else std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return out;
}

TEST(UdpTransport, PacketsArriveWholeAndInOrder) {
  UdpTransport a(0, endpoints(kBase, 2)), b(1, endpoints(kBase, 2));
  std::string error;
  ASSERT_TRUE(a.open(error)) << error;
  ASSERT_TRUE(b.open(error)) << error;
  for (std::uint32_t i = 0; i < 100; ++i) {
    a.send(1, {.kind = Packet::Kind::Status, .sender = 0, .index = i, .value = -static_cast<std::int32_t>(i), .aux = 7,
               .word = 0x0123456789abcdefULL, .sequence = i});
  }
  const std::vector<Packet> got = receive(b, 1, 100);
  ASSERT_EQ(got.size(), 100u);
  for (std::uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(got[i], (Packet{.kind = Packet::Kind::Status, .sender = 0, .index = i, .value = -static_cast<std::int32_t>(i), .aux = 7,
                              .word = 0x0123456789abcdefULL, .sequence = i}));
  }
  EXPECT_EQ(a.counters().sent, 100u);
  EXPECT_EQ(b.counters().delivered, 100u);
  Packet none;
  EXPECT_FALSE(b.poll(1, none)) << "polling never blocks";
}

TEST(UdpTransport, MulticastFansOutToEveryMemberButTheSender) {
  UdpTransport t0(0, endpoints(kBase + 10, 3)), t1(1, endpoints(kBase + 10, 3)), t2(2, endpoints(kBase + 10, 3));
  std::string error;
  ASSERT_TRUE(t0.open(error) && t1.open(error) && t2.open(error)) << error;
  const std::uint32_t group[] = {0, 1, 2};
  t0.multicast(group, {.kind = Packet::Kind::Heartbeat, .sender = 0, .index = 3, .value = 1});
  EXPECT_EQ(receive(t1, 1, 1).size(), 1u);
  EXPECT_EQ(receive(t2, 2, 1).size(), 1u);
  Packet p;
  EXPECT_FALSE(t0.poll(0, p));
}

TEST(UdpTransport, MalformedDatagramsAreCountedAndDropped) {
  UdpTransport b(1, endpoints(kBase + 20, 2));
  std::string error;
  ASSERT_TRUE(b.open(error)) << error;
  const int raw = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(raw, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(kBase + 21);
  inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  const char junk[] = "not a semo packet at all, and not 40 bytes long";
  ::sendto(raw, junk, sizeof junk, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  PacketBytes fromNobody = encodePacket({.kind = Packet::Kind::Event, .sender = 99});  // no robot 99 in this team
  ::sendto(raw, fromNobody.data(), fromNobody.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  PacketBytes good = encodePacket({.kind = Packet::Kind::Event, .sender = 0, .index = 4});
  ::sendto(raw, good.data(), good.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(raw);
  const std::vector<Packet> got = receive(b, 1, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].index, 4u);
  EXPECT_EQ(b.malformed(), 2u);
}

TEST(UdpTransport, ATakenPortOrABadAddressIsAnError) {
  UdpTransport a(0, endpoints(kBase + 30, 1)), again(0, endpoints(kBase + 30, 1));
  std::string error;
  ASSERT_TRUE(a.open(error)) << error;
  EXPECT_FALSE(again.open(error));
  EXPECT_NE(error.find("cannot bind 127.0.0.1:"), std::string::npos) << error;
  UdpTransport bad(0, {{"robot-zero.local", 1}});
  EXPECT_FALSE(bad.open(error));
  EXPECT_NE(error.find("is not an IPv4 address"), std::string::npos) << error;
  EXPECT_FALSE(parseUdpEndpoint("127.0.0.1"));
  EXPECT_FALSE(parseUdpEndpoint("127.0.0.1:0"));
  EXPECT_FALSE(parseUdpEndpoint("127.0.0.1:70000"));
  EXPECT_FALSE(parseUdpEndpoint("localhost:5000"));
  ASSERT_TRUE(parseUdpEndpoint("10.0.0.7:5000"));
  EXPECT_EQ(parseUdpEndpoint("10.0.0.7:5000")->port, 5000);
}

// An IP multicast group on loopback (a LAN's way): what goes to every other robot is one datagram to
// the group, which every member receives and the sender does not; to fewer, one datagram each.
TEST(UdpTransport, AnIpMulticastGroupCarriesWhatGoesToEveryone) {
  const UdpMulticast group{{"239.255.47.1", 47690}, "127.0.0.1"};
  UdpTransport t0(0, endpoints(kBase + 40, 3), group), t1(1, endpoints(kBase + 40, 3), group), t2(2, endpoints(kBase + 40, 3), group);
  std::string error;
  if (!t0.open(error)) GTEST_SKIP() << "no IP multicast here: " << error;
  ASSERT_TRUE(t1.open(error) && t2.open(error)) << error;
  const std::uint32_t everyone[] = {0, 1, 2};
  t0.multicast(everyone, {.kind = Packet::Kind::Status, .sender = 0, .index = 1, .value = 5});
  EXPECT_EQ(t0.groupDatagrams(), 1u);
  EXPECT_EQ(t0.counters().sent, 2u) << "a packet to each of two receivers";
  EXPECT_EQ(receive(t1, 1, 1).size(), 1u);
  EXPECT_EQ(receive(t2, 2, 1).size(), 1u);
  Packet p;
  EXPECT_FALSE(t0.poll(0, p)) << "its own datagram, looped back, is not a packet for it";
  const std::uint32_t two[] = {0, 1};
  t0.multicast(two, {.kind = Packet::Kind::Heartbeat, .sender = 0, .index = 0, .value = 1});
  EXPECT_EQ(t0.groupDatagrams(), 1u) << "to fewer than everyone: unicast";
  EXPECT_EQ(receive(t1, 1, 1).size(), 1u);
  EXPECT_FALSE(t2.poll(2, p));
  UdpTransport notAGroup(0, endpoints(kBase + 50, 1), UdpMulticast{{"10.1.2.3", 47691}, "127.0.0.1"});
  EXPECT_FALSE(notAGroup.open(error));
  EXPECT_NE(error.find("is not an IPv4 multicast address"), std::string::npos) << error;
}

}  // namespace
}  // namespace semo::runtime
