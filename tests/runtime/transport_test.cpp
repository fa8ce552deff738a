// The transport interface: the packet's wire layout (round trip, a pinned byte layout, every
// malformed input refused) and the in-process transport (order per link, loss rates and bursts,
// seeded determinism, crashes, full queues, the counters' balance, throughput).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <utility>
#include <vector>

#include "semo/runtime/transport.hpp"

namespace semo::runtime {
namespace {

Packet makePacket(Packet::Kind kind, std::uint32_t sender, std::uint64_t sequence) {
  Packet p;
  p.kind = kind;
  p.sender = sender;
  p.sequence = sequence;
  return p;
}

InProcessTransport::Options options(std::uint32_t robots, std::size_t capacity, LossModel loss = {}, std::uint64_t seed = 1) {
  InProcessTransport::Options o;
  o.robots = robots;
  o.queueCapacity = capacity;
  o.loss = loss;
  o.seed = seed;
  return o;
}

LossModel bernoulli(double p) {
  LossModel m;
  m.p = p;
  return m;
}

LossModel bursts(double p, int length) {
  LossModel m;
  m.kind = LossModel::Kind::Burst;
  m.p = p;
  m.burst = length;
  return m;
}

// Sends `count` packets on the link from -> to, polling each at once; returns, per packet, whether
// it arrived (told apart by its sequence number at the receiver).
std::vector<bool> arrivals(InProcessTransport& t, std::uint32_t from, std::uint32_t to, int count) {
  std::vector<bool> arrived(static_cast<std::size_t>(count), false);
  for (int i = 0; i < count; ++i) {
    t.send(to, makePacket(Packet::Kind::Publish, from, static_cast<std::uint64_t>(i)));
    Packet p;
    while (t.poll(to, p)) {
      EXPECT_EQ(p.sender, from);
      arrived[p.sequence] = true;
    }
  }
  return arrived;
}

// ------------------------------------------------------------------ the wire layout

TEST(PacketCodec, RoundTripsEveryKindAndExtremeValues) {
  std::vector<Packet> packets;
  for (std::uint8_t k = 1; k <= Packet::kLastKind; ++k) {
    Packet p;
    p.kind = static_cast<Packet::Kind>(k);
    p.sender = 3;
    p.index = 17u + k;
    p.value = k == static_cast<std::uint8_t>(Packet::Kind::KnowledgeDigest) ? 128 : -42;
    p.aux = 0xdeadbeefu;
    p.word = 0x0123456789abcdefULL;
    p.sequence = 1000u + k;
    packets.push_back(p);
  }
  Packet extreme;
  extreme.kind = Packet::Kind::Publish;
  extreme.sender = std::numeric_limits<std::uint32_t>::max();
  extreme.index = std::numeric_limits<std::uint32_t>::max();
  extreme.value = std::numeric_limits<std::int32_t>::min();
  extreme.aux = std::numeric_limits<std::uint32_t>::max();
  extreme.word = std::numeric_limits<std::uint64_t>::max();
  extreme.sequence = std::numeric_limits<std::uint64_t>::max();
  packets.push_back(extreme);
  extreme.value = std::numeric_limits<std::int32_t>::max();
  extreme.word = 0x8000000000000001ULL;
  packets.push_back(extreme);
  packets.push_back(Packet{});
  for (const Packet& p : packets) {
    const PacketBytes bytes = encodePacket(p);
    Packet back;
    back.sender = 12345;  // overwritten by a successful decode
    ASSERT_EQ(decodePacket(bytes, back), DecodeError::None) << packetKindName(p.kind);
    EXPECT_EQ(back, p) << packetKindName(p.kind);
    EXPECT_EQ(encodePacket(back), bytes);
  }
}

TEST(PacketCodec, LayoutIsLittleEndianWithMagicAndVersion) {
  Packet p;
  p.kind = Packet::Kind::Heartbeat;
  p.sender = 0x04030201u;
  p.index = 0x08070605u;
  p.value = -2;  // 0xfffffffe
  p.aux = 0x0c0b0a09u;
  p.word = 0x1817161514131211ULL;
  p.sequence = 0x2827262524232221ULL;
  const PacketBytes expected = {0x53, 0x45, 0x4d, 0x4f, 1,    4,    0,    0,    0x01, 0x02, 0x03, 0x04, 0x05, 0x06,
                                0x07, 0x08, 0xfe, 0xff, 0xff, 0xff, 0x09, 0x0a, 0x0b, 0x0c, 0x11, 0x12, 0x13, 0x14,
                                0x15, 0x16, 0x17, 0x18, 0x21, 0x22, 0x23, 0x24, 0x25, 0x26, 0x27, 0x28};
  EXPECT_EQ(encodePacket(p), expected);
  EXPECT_EQ(kPacketBytes, 40u);
}

TEST(PacketCodec, RefusesEveryMalformedInput) {
  Packet good;
  good.kind = Packet::Kind::Event;
  good.sender = 2;
  good.index = 5;
  good.word = 77;
  good.sequence = 9;
  const PacketBytes bytes = encodePacket(good);
  const Packet untouched = makePacket(Packet::Kind::Publish, 99, 99);

  auto refused = [&](std::span<const std::uint8_t> b, DecodeError why, const char* what, int detail) {
    Packet out = untouched;
    EXPECT_EQ(decodePacket(b, out), why) << what << " " << detail;
    EXPECT_EQ(out, untouched) << what << " " << detail << ": a refused decode leaves the packet as it was";
  };

  // Every length but 40, cut from a valid packet or padded after one.
  std::vector<std::uint8_t> longer(bytes.begin(), bytes.end());
  longer.resize(2 * kPacketBytes + 1, 0);
  for (std::size_t n = 0; n <= longer.size(); ++n) {
    if (n == kPacketBytes) continue;
    refused(std::span<const std::uint8_t>(longer.data(), n), DecodeError::Length, "length", static_cast<int>(n));
  }
  // Every other value of every magic byte.
  for (std::size_t i = 0; i < 4; ++i) {
    for (int v = 0; v < 256; ++v) {
      if (v == bytes[i]) continue;
      PacketBytes b = bytes;
      b[i] = static_cast<std::uint8_t>(v);
      refused(b, DecodeError::Magic, "magic byte", static_cast<int>(i) * 1000 + v);
    }
  }
  // Every other version.
  for (int v = 0; v < 256; ++v) {
    if (v == kPacketVersion) continue;
    PacketBytes b = bytes;
    b[4] = static_cast<std::uint8_t>(v);
    refused(b, DecodeError::Version, "version", v);
  }
  // Every kind byte outside 1..10, and every one inside accepted.
  for (int v = 0; v < 256; ++v) {
    PacketBytes b = bytes;
    b[5] = static_cast<std::uint8_t>(v);
    if (v >= 1 && v <= Packet::kLastKind) {
      Packet out;
      EXPECT_EQ(decodePacket(b, out), DecodeError::None) << v;  // value 0 is a valid digest window too
      EXPECT_EQ(static_cast<int>(out.kind), v);
      continue;
    }
    refused(b, DecodeError::Kind, "kind", v);
  }
  // Any bit of the reserved bytes.
  for (std::size_t i = 6; i < 8; ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      PacketBytes b = bytes;
      b[i] = static_cast<std::uint8_t>(1 << bit);
      refused(b, DecodeError::Reserved, "reserved", static_cast<int>(i) * 100 + bit);
    }
  }
  // A knowledge digest's window starts at a multiple of 64.
  for (std::int32_t first : {1, 63, 65, -64, std::numeric_limits<std::int32_t>::min()}) {
    Packet digest = good;
    digest.kind = Packet::Kind::KnowledgeDigest;
    digest.value = first;
    refused(encodePacket(digest), DecodeError::Window, "window", first);
  }
  for (std::int32_t first : {0, 64, 1 << 20}) {
    Packet digest = good;
    digest.kind = Packet::Kind::KnowledgeDigest;
    digest.value = first;
    Packet out;
    EXPECT_EQ(decodePacket(encodePacket(digest), out), DecodeError::None) << first;
  }
  for (auto e : {DecodeError::None, DecodeError::Length, DecodeError::Magic, DecodeError::Version, DecodeError::Kind,
                 DecodeError::Reserved, DecodeError::Window}) {
    EXPECT_NE(decodeErrorName(e), "unknown");
  }
}

// Every byte of the layout is a field or checked, so a decode that accepts gives back the very
// bytes on encoding: no two byte strings mean the same packet.
TEST(PacketCodec, AcceptedBytesEncodeBackToThemselves) {
  RandomStream r(17);
  int accepted = 0;
  for (int i = 0; i < 100000; ++i) {
    PacketBytes b;
    for (std::uint8_t& byte : b) byte = static_cast<std::uint8_t>(r.next());
    if (r.bernoulli(0.9)) {  // mostly a valid header, so that most get past it
      b[0] = 0x53, b[1] = 0x45, b[2] = 0x4d, b[3] = 0x4f, b[4] = kPacketVersion;
      b[5] = static_cast<std::uint8_t>(1 + r.below(Packet::kLastKind));
      b[6] = r.bernoulli(0.9) ? 0 : b[6];
      b[7] = 0;
    }
    Packet out;
    if (decodePacket(b, out) != DecodeError::None) continue;
    ++accepted;
    ASSERT_EQ(encodePacket(out), b) << i;
  }
  EXPECT_GT(accepted, 50000);
}

// ------------------------------------------------------------------ the in-process transport

TEST(InProcessTransport, DeliversInTheOrderSentOnEachLink) {
  InProcessTransport t(options(3, 256));
  // Robots 0 and 1 interleave 100 packets each to robot 2 (which of them goes first changes), each
  // numbering its own; robot 2 sends 50 to robot 0 in between.
  std::uint64_t next[3] = {0, 0, 0};
  std::vector<std::pair<std::uint32_t, std::uint64_t>> order;  // (sender, sequence) as sent to robot 2
  for (int i = 0; i < 100; ++i) {
    const std::uint32_t first = i % 3 == 0 ? 1 : 0;
    for (std::uint32_t s : {first, 1 - first}) {
      order.emplace_back(s, next[s]);
      t.send(2, makePacket(Packet::Kind::Publish, s, next[s]++));
      if (s == first && i % 2 == 0) t.send(0, makePacket(Packet::Kind::Event, 2, next[2]++));
    }
  }
  EXPECT_EQ(t.queued(2), 200u);
  EXPECT_EQ(t.queued(0), 50u);
  EXPECT_EQ(t.queued(1), 0u);
  std::vector<std::pair<std::uint32_t, std::uint64_t>> received;
  std::uint64_t expected[3] = {0, 0, 0};
  Packet p;
  while (t.poll(2, p)) {
    received.emplace_back(p.sender, p.sequence);
    EXPECT_EQ(p.sequence, expected[p.sender]++) << "from robot " << p.sender;  // in order on each link
  }
  EXPECT_EQ(received, order) << "to one receiver, in the order sent, across senders too";
  while (t.poll(0, p)) {
    EXPECT_EQ(p.kind, Packet::Kind::Event);
    EXPECT_EQ(p.sequence, expected[2]++);
  }
  EXPECT_EQ(expected[0], 100u);
  EXPECT_EQ(expected[1], 100u);
  EXPECT_EQ(expected[2], 50u);
  EXPECT_FALSE(t.poll(1, p));
  const TransportCounters c = t.counters();
  EXPECT_EQ(c.sent, 250u);
  EXPECT_EQ(c.delivered, 250u);
  EXPECT_EQ(c.lost + c.droppedFull + c.discarded, 0u);
}

TEST(InProcessTransport, BernoulliLossRateOverAHundredThousandPackets) {
  for (double p : {0.01, 0.1, 0.3, 0.5}) {
    InProcessTransport t(options(2, 8, bernoulli(p), 7));
    const std::vector<bool> arrived = arrivals(t, 0, 1, 100000);
    const TransportCounters c = t.counters();
    const double rate = static_cast<double>(c.lost) / 100000.0;
    // One percentage point: more than six standard deviations of 100,000 draws at any p.
    EXPECT_NEAR(rate, p, 0.01) << "p = " << p;
    EXPECT_EQ(c.sent, 100000u);
    EXPECT_EQ(c.delivered + c.lost, c.sent);
    std::uint64_t arrivedCount = 0;
    for (bool a : arrived) arrivedCount += a ? 1 : 0;
    EXPECT_EQ(arrivedCount, c.delivered);
  }
  InProcessTransport none(options(2, 8, bernoulli(0), 7));
  (void)arrivals(none, 1, 0, 10000);
  EXPECT_EQ(none.counters().lost, 0u);
  EXPECT_EQ(none.counters().delivered, 10000u);
}

TEST(InProcessTransport, BurstModelLosesRunsOfTheBurstLength) {
  constexpr int kBurst = 5;
  InProcessTransport t(options(2, 8, bursts(0.02, kBurst), 3));
  const std::vector<bool> arrived = arrivals(t, 0, 1, 100000);
  // The receiver sees the runs as gaps in the sequence numbers.
  int run = 0, runs = 0, exact = 0;
  for (bool a : arrived) {
    if (!a) {
      ++run;
      continue;
    }
    if (run > 0) {
      EXPECT_EQ(run % kBurst, 0) << "a loss run of " << run;
      ++runs;
      exact += run == kBurst ? 1 : 0;
    }
    run = 0;
  }
  EXPECT_GT(runs, 1000);  // about 100,000 * 0.02 / (1 + 0.02 * 5) bursts
  EXPECT_GT(exact, runs * 9 / 10);  // back-to-back bursts (one more loss right after one) are rare
}

TEST(InProcessTransport, SameSeedSameLossesOtherSeedOtherLosses) {
  const LossModel loss = bernoulli(0.2);
  InProcessTransport a(options(3, 8, loss, 42)), b(options(3, 8, loss, 42)), c(options(3, 8, loss, 43));
  const std::vector<bool> a01 = arrivals(a, 0, 1, 2000), a21 = arrivals(a, 2, 1, 2000);
  // b has other traffic first, on other links: each link's losses are its own.
  (void)arrivals(b, 1, 2, 777);
  (void)arrivals(b, 2, 0, 333);
  const std::vector<bool> b21 = arrivals(b, 2, 1, 2000), b01 = arrivals(b, 0, 1, 2000);
  EXPECT_EQ(a01, b01);
  EXPECT_EQ(a21, b21);
  EXPECT_NE(a01, a21) << "two links of one seed lose differently";
  const std::vector<bool> c01 = arrivals(c, 0, 1, 2000);
  EXPECT_NE(a01, c01) << "another seed loses differently";
  // Something was lost at all (else the equalities above say nothing).
  EXPECT_NE(std::count(a01.begin(), a01.end(), false), 0);
}

TEST(InProcessTransport, ACrashedRobotSendsNothingAndReceivesNothing) {
  InProcessTransport t(options(3, 16));
  for (std::uint64_t i = 0; i < 5; ++i) t.send(1, makePacket(Packet::Kind::Publish, 0, i));
  for (std::uint64_t i = 0; i < 3; ++i) t.send(0, makePacket(Packet::Kind::Publish, 1, i));
  ASSERT_EQ(t.queued(1), 5u);
  EXPECT_FALSE(t.crashed(1));
  t.crash(1);
  EXPECT_TRUE(t.crashed(1));
  EXPECT_EQ(t.queued(1), 0u) << "its queue is emptied";
  EXPECT_EQ(t.counters().discarded, 5u);
  Packet p;
  EXPECT_FALSE(t.poll(1, p));
  // What it had sent before the crash has gone out and stays; what it sends now does not.
  t.send(0, makePacket(Packet::Kind::Publish, 1, 100));
  t.send(2, makePacket(Packet::Kind::Publish, 1, 101));
  const std::uint32_t team[] = {0, 1, 2};
  t.multicast(team, makePacket(Packet::Kind::Heartbeat, 1, 102));
  EXPECT_EQ(t.queued(0), 3u);
  EXPECT_EQ(t.queued(2), 0u);
  // Nothing reaches it, unicast or multicast; the others still talk.
  t.send(1, makePacket(Packet::Kind::Event, 0, 200));
  t.multicast(team, makePacket(Packet::Kind::Heartbeat, 2, 201));
  EXPECT_FALSE(t.poll(1, p));
  EXPECT_EQ(t.queued(0), 4u);
  std::vector<std::uint64_t> atZero;
  while (t.poll(0, p)) atZero.push_back(p.sequence);
  EXPECT_EQ(atZero, (std::vector<std::uint64_t>{0, 1, 2, 201}));
  t.crash(1);  // again: nothing changes
  const TransportCounters c = t.counters();
  EXPECT_EQ(c.sent, 5u + 3u + 2u + 2u + 1u + 2u);
  EXPECT_EQ(c.discarded, 5u + 2u + 2u + 1u + 1u);  // the queue; its unicasts; its multicast; to it; the multicast's copy to it
  EXPECT_EQ(c.delivered, 4u);
  EXPECT_EQ(c.sent, c.delivered + c.lost + c.droppedFull + c.discarded + t.queued());
}

TEST(InProcessTransport, AFullQueueDropsAndCountsNeverGrows) {
  InProcessTransport t(options(2, 4));
  for (std::uint64_t i = 0; i < 10; ++i) {
    t.send(1, makePacket(Packet::Kind::ChannelSend, 0, i));
    EXPECT_LE(t.queued(1), 4u);
  }
  EXPECT_EQ(t.queued(1), 4u);
  EXPECT_EQ(t.queueCapacity(), 4u);
  EXPECT_EQ(t.counters().droppedFull, 6u);
  Packet p;
  for (std::uint64_t i = 0; i < 4; ++i) {  // the first four stay, the later ones were dropped
    ASSERT_TRUE(t.poll(1, p));
    EXPECT_EQ(p.sequence, i);
  }
  EXPECT_FALSE(t.poll(1, p));
  t.send(1, makePacket(Packet::Kind::ChannelSend, 0, 10));  // room again
  ASSERT_TRUE(t.poll(1, p));
  EXPECT_EQ(p.sequence, 10u);
  const TransportCounters c = t.counters();
  EXPECT_EQ(c.sent, 11u);
  EXPECT_EQ(c.delivered, 5u);
  EXPECT_EQ(c.droppedFull, 6u);
  EXPECT_EQ(c.lost + c.discarded, 0u);
}

TEST(InProcessTransport, MulticastReachesEveryMemberButTheSender) {
  InProcessTransport t(options(5, 8));
  const std::uint32_t group[] = {0, 2, 3};
  Packet hb = makePacket(Packet::Kind::Heartbeat, 2, 7);
  hb.index = 1;
  hb.value = 1;
  t.multicast(group, hb);
  EXPECT_EQ(t.queued(0), 1u);
  EXPECT_EQ(t.queued(1), 0u);
  EXPECT_EQ(t.queued(2), 0u);
  EXPECT_EQ(t.queued(3), 1u);
  EXPECT_EQ(t.queued(4), 0u);
  Packet p;
  ASSERT_TRUE(t.poll(3, p));
  EXPECT_EQ(p, hb);
  EXPECT_EQ(t.counters().sent, 2u);
}

TEST(InProcessTransport, OneLinkCanHaveItsOwnLossModel) {
  InProcessTransport t(options(3, 8));
  t.setLinkLoss(0, 1, bernoulli(1.0));
  (void)arrivals(t, 0, 1, 100);
  EXPECT_EQ(t.counters().lost, 100u);
  (void)arrivals(t, 1, 0, 100);
  (void)arrivals(t, 0, 2, 100);
  EXPECT_EQ(t.counters().lost, 100u);
  EXPECT_EQ(t.counters().delivered, 200u);
}

// Random traffic among six robots (unicasts, multicasts, a robot id outside the team), random
// polls, two crashes, small queues and bursty loss; the traffic is the same whatever the
// transport's seed.
TransportCounters mixedTraffic(InProcessTransport& t) {
  RandomStream r(5);
  const std::uint32_t team[] = {0, 1, 2, 3, 4, 5, 6};  // 6 is no robot of the team: discarded
  for (std::uint64_t i = 0; i < 50000; ++i) {
    const auto from = static_cast<std::uint32_t>(r.below(6));
    if (r.bernoulli(0.3)) {
      t.multicast(team, makePacket(Packet::Kind::KnowledgeDigest, from, i));
    } else {
      t.send(static_cast<std::uint32_t>(r.below(7)), makePacket(Packet::Kind::Publish, from, i));
    }
    Packet p;
    if (r.bernoulli(0.5)) (void)t.poll(static_cast<std::uint32_t>(r.below(6)), p);
    if (i == 20000) t.crash(4);
    if (i == 30000) t.crash(0);
    for (std::uint32_t q = 0; q < 6; ++q) EXPECT_LE(t.queued(q), 5u);
  }
  return t.counters();
}

TEST(InProcessTransport, EveryPacketIsAccountedForUnderLossCrashesAndFullQueues) {
  InProcessTransport t(options(6, 5, bursts(0.1, 3), 99));
  const TransportCounters c = mixedTraffic(t);
  EXPECT_EQ(c.sent, c.delivered + c.lost + c.droppedFull + c.discarded + t.queued());
  EXPECT_GT(c.delivered, 0u);
  EXPECT_GT(c.lost, 0u);
  EXPECT_GT(c.droppedFull, 0u);
  EXPECT_GT(c.discarded, 0u);
  EXPECT_EQ(t.queued(4) + t.queued(0), 0u);
  // The whole run again under the same seed: the same counts; under another seed, other losses.
  InProcessTransport same(options(6, 5, bursts(0.1, 3), 99)), other(options(6, 5, bursts(0.1, 3), 100));
  const TransportCounters again = mixedTraffic(same), otherCounts = mixedTraffic(other);
  EXPECT_EQ(again.lost, c.lost);
  EXPECT_EQ(again.delivered, c.delivered);
  EXPECT_EQ(again.droppedFull, c.droppedFull);
  EXPECT_EQ(again.discarded, c.discarded);
  EXPECT_EQ(otherCounts.sent, c.sent);
  EXPECT_NE(otherCounts.lost, c.lost);
}

// How many packets per second go through send and poll (printed; a quick local figure, not a bound).
TEST(InProcessTransport, Throughput) {
  constexpr std::uint32_t kRobots = 8;
  InProcessTransport t(options(kRobots, 64, bernoulli(0.1), 1));
  std::vector<std::uint32_t> team(kRobots);
  for (std::uint32_t i = 0; i < kRobots; ++i) team[i] = i;
  constexpr int kRounds = 200000;
  std::uint64_t received = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int round = 0; round < kRounds; ++round) {
    const auto from = static_cast<std::uint32_t>(round % kRobots);
    t.multicast(team, makePacket(Packet::Kind::Publish, from, static_cast<std::uint64_t>(round)));
    Packet p;
    for (std::uint32_t q = 0; q < kRobots; ++q) {
      while (t.poll(q, p)) ++received;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const TransportCounters c = t.counters();
  EXPECT_EQ(received, c.delivered);
  EXPECT_EQ(c.sent, std::uint64_t{kRounds} * (kRobots - 1));
  std::printf("[ figures  ] InProcessTransport: %llu packets sent, %llu delivered in %.3f s: %.1f million packets/s\n",
              static_cast<unsigned long long>(c.sent), static_cast<unsigned long long>(c.delivered), seconds,
              static_cast<double>(c.sent) / seconds / 1e6);
}

}  // namespace
}  // namespace semo::runtime
