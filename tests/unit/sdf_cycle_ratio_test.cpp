// The period as the maximum cycle ratio of the HSDF expansion (cycle_ratio.hpp) against the
// self-timed state space (throughput.hpp): hand-computable graphs, and random buffer distributions
// of the five SDF3 benchmark graphs, where both must give the same exact period or both deadlock.
#include <gtest/gtest.h>

#include <random>

#include "semo/sdf/buffers.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/cycle_ratio.hpp"
#include "semo/sdf/sdf3_xml.hpp"
#include "semo/sdf/throughput.hpp"

#include "sdf_test_support.hpp"

namespace semo::sdf {
namespace {

using test::sdf3Benchmark;

CycleRatioResult ratioOf(const Graph& g, const std::vector<std::optional<std::int64_t>>& capacities = {}) {
  RepetitionVector q = repetitionVector(g);
  EXPECT_TRUE(q.consistent()) << q.error;
  HsdfExpansion expansion(g, q.firings);
  CycleRatioResult r = expansion.evaluate(capacities);
  EXPECT_TRUE(r.error.empty()) << r.error;
  return r;
}

TEST(SdfCycleRatio, HandComputableGraphs) {
  // a (3) -> b (5) -> a with one or two tokens back, each actor one firing at a time: 8, then 5.
  Graph g;
  g.actors = {{"a", 3, {}}, {"b", 5, {}}};
  g.channels = {{"ab", 0, 1, 1, 1, 0, {}}, {"ba", 1, 0, 1, 1, 1, {}}, {"aa", 0, 0, 1, 1, 1, {}}, {"bb", 1, 1, 1, 1, 1, {}}};
  EXPECT_EQ(ratioOf(g).period, (Period{8, 1}));
  g.channels[1].initialTokens = 2;
  EXPECT_EQ(ratioOf(g).period, (Period{5, 1}));
  g.channels[1].initialTokens = 0;
  EXPECT_TRUE(ratioOf(g).deadlock);
  // Three tokens round one actor of time 2 without a self-loop: three firings overlap.
  Graph lone;
  lone.actors = {{"a", 2, {}}};
  lone.channels = {{"aa", 0, 0, 1, 1, 3, {}}};
  EXPECT_EQ(ratioOf(lone).period, (Period{2, 3}));
  // a (1) feeds b (4): room for one token, a waits for b (5); for two, b sets the pace (4); none
  // deadlocks, and the critical cycle names the channel's space and the capacity that moves it.
  Graph pipe;
  pipe.actors = {{"a", 1, {}}, {"b", 4, {}}};
  pipe.channels = {{"ab", 0, 1, 1, 1, 0, {}}, {"aa", 0, 0, 1, 1, 1, {}}, {"bb", 1, 1, 1, 1, 1, {}}};
  CycleRatioResult one = ratioOf(pipe, {1, std::nullopt, std::nullopt});
  EXPECT_EQ(one.period, (Period{5, 1}));
  ASSERT_FALSE(one.cycles.empty());
  ASSERT_EQ(one.cycles.front().space.size(), 1u);
  EXPECT_EQ(one.cycles.front().space.front().channel, 0u);
  EXPECT_EQ(one.cycles.front().space.front().capacityThatMovesIt, 2);
  EXPECT_EQ(ratioOf(pipe, {2, std::nullopt, std::nullopt}).period, (Period{4, 1}));
  CycleRatioResult none = ratioOf(pipe, {0, std::nullopt, std::nullopt});
  EXPECT_TRUE(none.deadlock);
  ASSERT_FALSE(none.cycles.empty());
  EXPECT_EQ(none.cycles.front().space.front().capacityThatMovesIt, 1);
}

TEST(SdfCycleRatio, MultirateSpaceEdges) {
  // a produces 3, b consumes 2 (q = 2, 3), both one firing at a time. Capacity 4 (the smallest
  // without deadlock) and more: the state space and the expansion agree on every capacity.
  Graph g;
  g.actors = {{"a", 2, {}}, {"b", 3, {}}};
  g.channels = {{"ab", 0, 1, 3, 2, 0, {}}, {"aa", 0, 0, 1, 1, 1, {}}, {"bb", 1, 1, 1, 1, 1, {}}};
  RepetitionVector q = repetitionVector(g);
  HsdfExpansion expansion(g, q.firings);
  for (std::int64_t capacity = 0; capacity <= 10; ++capacity) {
    ThroughputOptions options;
    options.capacities = {capacity, std::nullopt, std::nullopt};
    ThroughputResult selfTimed = throughput(g, q.firings, options);
    CycleRatioResult ratio = expansion.evaluate(options.capacities);
    ASSERT_TRUE(selfTimed.error.empty() && ratio.error.empty());
    EXPECT_EQ(selfTimed.deadlock, ratio.deadlock) << capacity;
    if (!selfTimed.deadlock) {
      EXPECT_EQ(selfTimed.period, ratio.period) << capacity;
    }
  }
}

TEST(SdfCycleRatio, AgreesWithTheStateSpaceOnRandomDistributions) {
  std::mt19937_64 random(20261123);
  for (const char* name : {"samplerate", "modem", "satellite", "h263decoder", "mp3decoder_granule_parallelism"}) {
    Graph g = sdf3Benchmark(name);
    RepetitionVector q = repetitionVector(g);
    HsdfExpansion expansion(g, q.firings);
    ASSERT_TRUE(expansion.error().empty());
    // Unbounded: the SDF3 periods.
    ThroughputResult unbounded = throughput(g, q.firings);
    EXPECT_EQ(expansion.evaluate({}).period, unbounded.period) << name;
    int deadlocks = 0, live = 0;
    for (int sample = 0; sample < 40; ++sample) {
      ThroughputOptions options;
      options.capacities.assign(g.channels.size(), std::nullopt);
      for (std::size_t c = 0; c < g.channels.size(); ++c) {
        const Channel& ch = g.channels[c];
        if (ch.selfLoop() || random() % 8 == 0) continue;  // a few unbounded
        const std::int64_t smallest = smallestCapacity(ch);
        // Mostly from the smallest capacity up to about twice the tokens an iteration moves; now and
        // then below it (a deadlock, or not: other channels may space the firings).
        const std::int64_t moved = q.firings[ch.source] * ch.production;
        std::int64_t capacity = smallest + static_cast<std::int64_t>(random() % static_cast<std::uint64_t>(std::max<std::int64_t>(2, moved)));
        if (random() % 10 == 0) capacity = ch.initialTokens + static_cast<std::int64_t>(random() % static_cast<std::uint64_t>(smallest - ch.initialTokens + 1));
        options.capacities[c] = capacity;
      }
      ThroughputResult selfTimed = throughput(g, q.firings, options);
      CycleRatioResult ratio = expansion.evaluate(options.capacities);
      ASSERT_TRUE(selfTimed.error.empty()) << selfTimed.error;
      ASSERT_TRUE(ratio.error.empty()) << ratio.error;
      EXPECT_EQ(selfTimed.deadlock, ratio.deadlock) << name << " sample " << sample;
      if (selfTimed.deadlock || ratio.deadlock) {
        ++deadlocks;
        continue;
      }
      ++live;
      EXPECT_EQ(selfTimed.period, ratio.period) << name << " sample " << sample;
    }
    EXPECT_GT(live, 10) << name;
  }
}

}  // namespace
}  // namespace semo::sdf
