// Throughput by self-timed execution: hand-computable graphs, and SDF3's periods for its benchmark
// graphs (specs/benchmarks/sdf3/README.md), with unbounded channels and with the buffer
// distributions SDF3 reports for samplerate.
#include <gtest/gtest.h>

#include "semo/sdf/buffers.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/sdf3_xml.hpp"
#include "semo/sdf/throughput.hpp"

#include "sdf_test_support.hpp"

namespace semo::sdf {
namespace {

using test::sdf3Benchmark;

Period periodOf(const Graph& g, const ThroughputOptions& options = {}) {
  RepetitionVector q = repetitionVector(g);
  EXPECT_TRUE(q.consistent()) << q.error;
  ThroughputResult r = throughput(g, q.firings, options);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.deadlock);
  return r.period;
}

Graph cycle(std::int64_t tokens) {
  // a (time 3) -> b (time 5) -> a, both at rate 1, `tokens` on the way back; each actor fires one at
  // a time (self-loops).
  Graph g;
  g.actors = {{"a", 3, {}}, {"b", 5, {}}};
  g.channels = {{"ab", 0, 1, 1, 1, 0, {}}, {"ba", 1, 0, 1, 1, tokens, {}}, {"aa", 0, 0, 1, 1, 1, {}}, {"bb", 1, 1, 1, 1, 1, {}}};
  return g;
}

TEST(SdfThroughput, ACycleIsAsSlowAsItsTokensAllow) {
  // One token: a and b take turns, 8 per iteration. Two: they overlap and b, the slower, sets the pace.
  EXPECT_EQ(periodOf(cycle(1)), (Period{8, 1}));
  EXPECT_EQ(periodOf(cycle(2)), (Period{5, 1}));
  RepetitionVector q = repetitionVector(cycle(0));
  EXPECT_TRUE(throughput(cycle(0), q.firings).deadlock);
}

TEST(SdfThroughput, AFractionalPeriod) {
  // Three tokens round a cycle of one actor taking 2 and producing one token per firing, with no
  // self-loop: three firings overlap, so one iteration takes 2/3 of a time unit on average.
  Graph g;
  g.actors = {{"a", 2, {}}};
  g.channels = {{"aa", 0, 0, 1, 1, 3, {}}};
  EXPECT_EQ(periodOf(g), (Period{2, 3}));
}

TEST(SdfThroughput, ABoundedChannelSlowsTheProducer) {
  // a (time 1) feeds b (time 4) at rate 1. Space is claimed when a starts and freed when b ends:
  // with room for one token a waits for b each time (1 + 4 = 5 per iteration); with two, a runs
  // ahead and b sets the pace (4); with none nothing moves.
  Graph g;
  g.actors = {{"a", 1, {}}, {"b", 4, {}}};
  g.channels = {{"ab", 0, 1, 1, 1, 0, {}}, {"aa", 0, 0, 1, 1, 1, {}}, {"bb", 1, 1, 1, 1, 1, {}}};
  ThroughputOptions bounded;
  bounded.capacities = {1, std::nullopt, std::nullopt};
  EXPECT_EQ(periodOf(g, bounded), (Period{5, 1}));
  bounded.capacities = {2, std::nullopt, std::nullopt};
  EXPECT_EQ(periodOf(g, bounded), (Period{4, 1}));
  EXPECT_EQ(periodOf(g), (Period{4, 1}));
  bounded.capacities = {0, std::nullopt, std::nullopt};
  RepetitionVector q = repetitionVector(g);
  EXPECT_TRUE(throughput(g, q.firings, bounded).deadlock);
}

TEST(SdfThroughput, Sdf3BenchmarkPeriods) {
  EXPECT_EQ(periodOf(sdf3Benchmark("h263decoder")), (Period{332046, 1}));
  EXPECT_EQ(periodOf(sdf3Benchmark("modem")), (Period{16, 1}));
  EXPECT_EQ(periodOf(sdf3Benchmark("samplerate")), (Period{960, 1}));
  EXPECT_EQ(periodOf(sdf3Benchmark("satellite")), (Period{1056, 1}));
  EXPECT_EQ(periodOf(sdf3Benchmark("mp3decoder_granule_parallelism")), (Period{278650, 1}));
}

TEST(SdfThroughput, SamplerateWithSdf3sBufferDistributions) {
  // SDF3: the smallest buffers with throughput > 0 are 1,4,8,14,5 (period 1088); 2,4,8,14,6 reach
  // the maximal throughput (period 960). ch1..ch5 are the graph's first five channels.
  Graph g = sdf3Benchmark("samplerate");
  ThroughputOptions smallest;
  smallest.capacities.assign(g.channels.size(), std::nullopt);
  const std::int64_t small[] = {1, 4, 8, 14, 5}, fast[] = {2, 4, 8, 14, 6};
  for (std::size_t c = 0; c < 5; ++c) smallest.capacities[c] = small[c];
  EXPECT_EQ(periodOf(g, smallest), (Period{1088, 1}));
  ThroughputOptions best = smallest;
  for (std::size_t c = 0; c < 5; ++c) best.capacities[c] = fast[c];
  EXPECT_EQ(periodOf(g, best), (Period{960, 1}));
  // One token less on the first channel of the smallest distribution, and it deadlocks.
  smallest.capacities[0] = 0;
  RepetitionVector q = repetitionVector(g);
  EXPECT_TRUE(throughput(g, q.firings, smallest).deadlock);
}

}  // namespace
}  // namespace semo::sdf

namespace semo::sdf {
namespace {

// Each Pareto point as (total, period) — a period of 0 for a deadlocked distribution.
std::vector<std::pair<std::int64_t, std::int64_t>> front(const std::string& name) {
  Graph g = sdf3Benchmark(name);
  RepetitionVector q = repetitionVector(g);
  ParetoFront f = bufferParetoFront(g, q.firings, 100'000);
  EXPECT_TRUE(f.error.empty()) << f.error;
  std::vector<std::pair<std::int64_t, std::int64_t>> out;
  for (const BufferPoint& p : f.points) {
    EXPECT_EQ(p.period.den, 1);
    out.push_back({p.total, p.deadlock ? 0 : p.period.num});
  }
  return out;
}

TEST(SdfBuffers, TheSmallestCapacityOfAChannelAlone) {
  // p + c - gcd(p, c) + d mod gcd, at least d.
  EXPECT_EQ(smallestCapacity({"x", 0, 1, 2, 3, 0, {}}), 4);
  EXPECT_EQ(smallestCapacity({"x", 0, 1, 4, 6, 1, {}}), 9);
  EXPECT_EQ(smallestCapacity({"x", 0, 1, 1, 1, 7, {}}), 7);
  EXPECT_EQ(smallestCapacity({"x", 0, 0, 1, 1, 1, {}}), 0);  // a self-loop is never bounded
}

TEST(SdfBuffers, Sdf3ParetoFronts) {
  // specs/benchmarks/sdf3/README.md: SDF3's smallest totals with throughput and at maximal
  // throughput, and the number of Pareto points (samplerate 3, modem 3, satellite 2).
  EXPECT_EQ(front("samplerate"), (std::vector<std::pair<std::int64_t, std::int64_t>>{{32, 1088}, {33, 1029}, {34, 960}}));
  EXPECT_EQ(front("modem"), (std::vector<std::pair<std::int64_t, std::int64_t>>{{38, 32}, {39, 18}, {40, 16}}));
  EXPECT_EQ(front("satellite"), (std::vector<std::pair<std::int64_t, std::int64_t>>{{1542, 1320}, {1544, 1056}}));
  std::vector<std::pair<std::int64_t, std::int64_t>> h263 = front("h263decoder");
  ASSERT_FALSE(h263.empty());
  EXPECT_EQ(h263.front(), (std::pair<std::int64_t, std::int64_t>{1189, 633253}));  // throughput 1.57915e-06, as SDF3
  EXPECT_EQ(h263.back(), (std::pair<std::int64_t, std::int64_t>{1224, 332046}));
}

}  // namespace
}  // namespace semo::sdf
