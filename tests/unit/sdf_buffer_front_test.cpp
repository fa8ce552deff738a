// The throughput–buffer front (buffers.hpp) against exhaustive enumeration: on small random graphs,
// every distribution up to the front's last total is run by the self-timed state space
// (throughput.hpp, independent of the cycle-ratio evaluation the front uses), and the best period
// of each total must be the front's. Then the mp3 decoder's front, which SDF3 did not finish.
#include <gtest/gtest.h>

#include <functional>
#include <numeric>
#include <random>

#include "semo/sdf/automorphisms.hpp"
#include "semo/sdf/buffers.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/sdf3_xml.hpp"
#include "semo/sdf/throughput.hpp"

#include "sdf_test_support.hpp"

namespace semo::sdf {
namespace {

using test::benchmarkGraph;

__extension__ typedef __int128 Wide;

bool slower(const Period& a, const Period& b) { return static_cast<Wide>(a.num) * b.den > static_cast<Wide>(b.num) * a.den; }

// A random consistent graph: a tree of channels with random rates (always consistent), extra
// channels whose rates follow the repetition vector, tokens on channels that go back in the actors'
// order (so the graph can run), self-loops on some actors.
Graph randomGraph(std::mt19937_64& random, std::size_t actors) {
  Graph g;
  std::vector<std::int64_t> q(actors, 1);
  for (std::size_t a = 0; a < actors; ++a) g.actors.push_back({"a" + std::to_string(a), 1 + static_cast<std::int64_t>(random() % 9), {}});
  for (std::size_t a = 1; a < actors; ++a) {
    const std::size_t parent = random() % a;
    const std::int64_t p = 1 + static_cast<std::int64_t>(random() % 3), c = 1 + static_cast<std::int64_t>(random() % 3);
    // q[a] * c = q[parent] * p, scaled to integers.
    const std::int64_t num = q[parent] * p, common = std::gcd(num, c);
    const std::int64_t scale = c / common;
    for (std::size_t b = 0; b < a; ++b) q[b] *= scale;
    q[a] = num / common;
    g.channels.push_back({"t" + std::to_string(a), static_cast<ActorId>(parent), static_cast<ActorId>(a), p, c, 0, {}});
  }
  std::int64_t all = 0;
  for (std::int64_t x : q) all = std::gcd(all, x);
  for (std::int64_t& x : q) x /= all;
  for (int extra = static_cast<int>(random() % 3); extra > 0; --extra) {
    const auto from = static_cast<ActorId>(random() % actors), to = static_cast<ActorId>(random() % actors);
    if (from == to) continue;
    const std::int64_t common = std::gcd(q[from], q[to]);
    const std::int64_t p = q[to] / common, c = q[from] / common;
    const std::int64_t tokens = from > to ? q[to] * c : 0;  // back in the order: an iteration's worth
    g.channels.push_back({"x" + std::to_string(g.channels.size()), from, to, p, c, tokens, {}});
  }
  for (std::size_t a = 0; a < actors; ++a) {
    if (random() % 2 == 0) g.channels.push_back({"s" + std::to_string(a), static_cast<ActorId>(a), static_cast<ActorId>(a), 1, 1, 1, {}});
  }
  return g;
}

// The best period of each total up to `last` over every distribution on the channels' grids
// (nullopt: all deadlock); false when there are more than `limit` distributions.
bool bestByTotal(const Graph& g, const std::vector<std::int64_t>& q, std::int64_t last, std::size_t limit,
                 std::vector<std::optional<Period>>& best) {
  std::vector<std::size_t> bounded;
  std::int64_t lowestTotal = 0;
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (g.channels[c].selfLoop()) continue;
    bounded.push_back(c);
    lowestTotal += smallestCapacity(g.channels[c]);
  }
  best.assign(static_cast<std::size_t>(last + 1), std::nullopt);
  ThroughputOptions options;
  options.capacities.assign(g.channels.size(), std::nullopt);
  std::size_t count = 0;
  bool within = true;
  std::function<void(std::size_t, std::int64_t)> visit = [&](std::size_t i, std::int64_t total) {
    if (!within) return;
    if (i == bounded.size()) {
      if (++count > limit) {
        within = false;
        return;
      }
      ThroughputResult r = throughput(g, q, options);
      EXPECT_TRUE(r.error.empty()) << r.error;
      if (r.deadlock) return;
      for (std::int64_t t = total; t <= last; ++t) {
        if (!best[static_cast<std::size_t>(t)] || slower(*best[static_cast<std::size_t>(t)], r.period)) best[static_cast<std::size_t>(t)] = r.period;
      }
      return;
    }
    const Channel& ch = g.channels[bounded[i]];
    const std::int64_t step = std::gcd(ch.production, ch.consumption);
    for (std::int64_t capacity = smallestCapacity(ch); total + capacity - smallestCapacity(ch) <= last; capacity += step) {
      options.capacities[bounded[i]] = capacity;
      visit(i + 1, total + capacity - smallestCapacity(ch));
    }
  };
  visit(0, lowestTotal);
  return within;
}

// Compares the front with the best period of each total by enumeration; false when the front has
// no answer or the enumeration would be too long.
bool agreesWithEnumeration(const Graph& g, const std::string& what, std::size_t& points) {
  RepetitionVector q = repetitionVector(g);
  EXPECT_TRUE(q.consistent()) << q.error;
  if (!q.consistent() || !runIteration(g, q.firings).deadlockFree) return false;
  ParetoFront front = bufferParetoFront(g, q.firings, 100'000);
  if (!front.error.empty()) return false;  // nothing bounds the throughput (no cycle): no front
  EXPECT_FALSE(front.points.empty());
  if (front.points.empty()) return false;
  std::vector<std::optional<Period>> best;
  if (!bestByTotal(g, q.firings, front.points.back().total, 4000, best)) return false;
  points = front.points.size();
  // Below the first point with a throughput every distribution deadlocks; from each point on, the
  // best period is the point's until the next.
  std::size_t next = 0;
  std::optional<Period> expected;
  for (std::int64_t t = 0; t <= front.points.back().total; ++t) {
    while (next < front.points.size() && front.points[next].total == t) {
      if (!front.points[next].deadlock) expected = front.points[next].period;
      ++next;
    }
    EXPECT_EQ(best[static_cast<std::size_t>(t)].has_value(), expected.has_value()) << what << " total " << t;
    if (expected && best[static_cast<std::size_t>(t)]) {
      EXPECT_EQ(*best[static_cast<std::size_t>(t)], *expected) << what << " total " << t;
    }
  }
  EXPECT_EQ(front.points.back().period, front.best) << what;
  for (std::size_t i = 1; i < front.points.size(); ++i) {
    EXPECT_LT(front.points[i - 1].total, front.points[i].total);
    if (!front.points[i - 1].deadlock) {
      EXPECT_TRUE(slower(front.points[i - 1].period, front.points[i].period));
    }
  }
  return true;
}

TEST(SdfBufferFront, EqualsExhaustiveEnumerationOnRandomGraphs) {
  std::mt19937_64 random(7);
  int compared = 0, longFronts = 0;
  for (int sample = 0; sample < 120 && compared < 50; ++sample) {
    Graph g = randomGraph(random, 2 + static_cast<std::size_t>(random() % 4));
    std::size_t points = 0;
    if (!agreesWithEnumeration(g, "sample " + std::to_string(sample), points)) continue;
    ++compared;
    if (points >= 3) ++longFronts;
  }
  EXPECT_GE(compared, 30);
  EXPECT_GE(longFronts, 15);
}

TEST(SdfBufferFront, EqualsExhaustiveEnumerationOnSymmetricGraphs) {
  // A source feeding two or three alike branches of one or two actors that join in a sink (both
  // one firing at a time): the front learns each clause with its images under the branch swaps.
  std::mt19937_64 random(3);
  int compared = 0;
  for (int sample = 0; sample < 40 && compared < 15; ++sample) {
    const std::size_t branches = 2 + random() % 2, length = 1 + random() % 2;
    Graph g;
    g.actors = {{"source", 1 + static_cast<std::int64_t>(random() % 5), {}}, {"sink", 1 + static_cast<std::int64_t>(random() % 5), {}}};
    g.channels = {{"ss", 0, 0, 1, 1, 1, {}}, {"tt", 1, 1, 1, 1, 1, {}}};
    std::vector<std::int64_t> times, rates;
    for (std::size_t i = 0; i <= length; ++i) rates.push_back(1 + static_cast<std::int64_t>(random() % 2));
    for (std::size_t i = 0; i < length; ++i) times.push_back(1 + static_cast<std::int64_t>(random() % 9));
    for (std::size_t b = 0; b < branches; ++b) {
      ActorId previous = 0;
      std::int64_t produced = rates[0];
      for (std::size_t i = 0; i < length; ++i) {
        const auto actor = static_cast<ActorId>(g.actors.size());
        g.actors.push_back({"b" + std::to_string(b) + "_" + std::to_string(i), times[i], {}});
        g.channels.push_back({"c" + std::to_string(g.channels.size()), previous, actor, produced, 1, 0, {}});
        previous = actor;
        produced = rates[i + 1];
      }
      g.channels.push_back({"c" + std::to_string(g.channels.size()), previous, 1, produced, 1, 0, {}});
    }
    RepetitionVector q = repetitionVector(g);
    if (!q.consistent()) continue;  // the sink's rate: consumption 1 on every branch is consistent only when rates agree
    EXPECT_FALSE(findAutomorphisms(g).empty());
    std::size_t points = 0;
    if (agreesWithEnumeration(g, "symmetric sample " + std::to_string(sample), points)) ++compared;
  }
  EXPECT_GE(compared, 8);
}

TEST(SdfBufferFront, Mp3Decoder) {
  // SDF3 (specs/benchmarks/sdf3/README.md): the smallest total 20, and 76 at the maximal throughput
  // (period 278650); SDF3's own exploration did not finish in 300 s.
  Graph g = benchmarkGraph("sdf3/mp3decoder_granule_parallelism.xml");
  RepetitionVector q = repetitionVector(g);
  ParetoFront front = bufferParetoFront(g, q.firings, 10'000);
  ASSERT_TRUE(front.error.empty()) << front.error;
  ASSERT_EQ(front.points.size(), 29u);
  EXPECT_FALSE(front.points.front().deadlock);
  EXPECT_EQ(front.points.front().total, 20);
  EXPECT_EQ(front.points.front().period, (Period{2180506, 1}));
  EXPECT_EQ(front.points[1].total, 22);
  EXPECT_EQ(front.points[1].period, (Period{1737856, 1}));
  EXPECT_EQ(front.points[7].total, 34);
  EXPECT_EQ(front.points[7].period, (Period{2180506, 3}));  // fractional: three iterations per cycle
  EXPECT_EQ(front.points.back().total, 76);
  EXPECT_EQ(front.points.back().period, (Period{278650, 1}));
  // Every total is even: the two granule branches take the same capacities.
  for (const BufferPoint& p : front.points) EXPECT_EQ(p.total % 2, 0);
  // The first three points against every distribution up to total 24, by the state space.
  std::vector<std::optional<Period>> best;
  ASSERT_TRUE(bestByTotal(g, q.firings, 24, 10'000, best));
  EXPECT_EQ(best[20], (std::optional<Period>{Period{2180506, 1}}));
  EXPECT_EQ(best[21], (std::optional<Period>{Period{2180506, 1}}));
  EXPECT_EQ(best[22], (std::optional<Period>{Period{1737856, 1}}));
  EXPECT_EQ(best[23], (std::optional<Period>{Period{1737856, 1}}));
  EXPECT_EQ(best[24], (std::optional<Period>{Period{1596900, 1}}));
}

}  // namespace
}  // namespace semo::sdf
