// SDF consistency (repetition vectors) and one iteration's schedule on hand-computable graphs, and
// on the SDF3 benchmark graphs of specs/benchmarks/sdf3 against SDF3's own figures.
#include <gtest/gtest.h>

#include <map>

#include "semo/sdf/consistency.hpp"
#include "semo/sdf/sdf3_xml.hpp"

#include "sdf_test_support.hpp"

namespace semo::sdf {
namespace {

using test::sdf3Benchmark;

// Actors named by the letters of `names`; each channel "a>b p:c t" (production, consumption,
// initial tokens).
Graph graph(const std::string& names, const std::vector<std::tuple<char, char, int, int, int>>& channels) {
  Graph g;
  for (char c : names) g.actors.push_back({std::string(1, c), 1, {}});
  for (const auto& [from, to, p, c, t] : channels) {
    auto id = [&](char x) { return static_cast<ActorId>(names.find(x)); };
    g.channels.push_back({std::string(1, from) + to, id(from), id(to), p, c, t, {}});
  }
  return g;
}

TEST(SdfConsistency, AMultirateChain) {
  // a produces 2, b consumes 3: 3 firings of a, 2 of b; the channel holds at most 6 tokens.
  Graph g = graph("ab", {{'a', 'b', 2, 3, 0}});
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent()) << q.error;
  EXPECT_EQ(q.firings, (std::vector<std::int64_t>{3, 2}));
  Iteration it = runIteration(g, q.firings);
  EXPECT_TRUE(it.deadlockFree);
  EXPECT_EQ(scheduleText(g, it.schedule), "3a 2b");
  EXPECT_EQ(it.maxTokens[0], 6);
  EXPECT_EQ(it.tokensAtEnd[0], 0);
}

TEST(SdfConsistency, ACycleNeedsInitialTokens) {
  Graph g = graph("ab", {{'a', 'b', 1, 1, 0}, {'b', 'a', 1, 1, 0}});
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent());
  EXPECT_EQ(q.firings, (std::vector<std::int64_t>{1, 1}));
  Iteration it = runIteration(g, q.firings);
  EXPECT_FALSE(it.deadlockFree);
  EXPECT_TRUE(it.schedule.empty());
  g.channels[1].initialTokens = 1;
  it = runIteration(g, q.firings);
  EXPECT_TRUE(it.deadlockFree);
  EXPECT_EQ(scheduleText(g, it.schedule), "a b");
  EXPECT_EQ(it.tokensAtEnd, (std::vector<std::int64_t>{0, 1}));
}

TEST(SdfConsistency, AMultirateCycleDeadlocksWithTooFewTokens) {
  // a needs 2 tokens from b per firing; b fires twice per a. One initial token is not enough, two are.
  Graph g = graph("ab", {{'a', 'b', 2, 1, 0}, {'b', 'a', 1, 2, 1}});
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent());
  EXPECT_EQ(q.firings, (std::vector<std::int64_t>{1, 2}));
  EXPECT_FALSE(runIteration(g, q.firings).deadlockFree);
  g.channels[1].initialTokens = 2;
  Iteration it = runIteration(g, q.firings);
  EXPECT_TRUE(it.deadlockFree);
  EXPECT_EQ(scheduleText(g, it.schedule), "a 2b");
}

TEST(SdfConsistency, AnInconsistentTriangleNamesAChannel) {
  // a -> b -> c at rate 1, but a -> c produces 2 per firing of a: c cannot fire both 1 and 2 times per a.
  Graph g = graph("abc", {{'a', 'b', 1, 1, 0}, {'b', 'c', 1, 1, 0}, {'a', 'c', 2, 1, 0}});
  RepetitionVector q = repetitionVector(g);
  EXPECT_FALSE(q.consistent());
  ASSERT_TRUE(q.conflictChannel.has_value());
  EXPECT_TRUE(q.firings.empty());
  EXPECT_NE(q.error.find("inconsistent"), std::string::npos);
}

TEST(SdfConsistency, ASelfLoopMustBalance) {
  Graph g = graph("a", {{'a', 'a', 2, 1, 1}});
  EXPECT_FALSE(repetitionVector(g).consistent());
  g.channels[0].production = 1;
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent());
  EXPECT_EQ(q.firings, (std::vector<std::int64_t>{1}));
}

TEST(SdfConsistency, EachComponentIsScaledOnItsOwn) {
  Graph g = graph("abcd", {{'a', 'b', 4, 6, 0}, {'c', 'd', 1, 5, 0}});
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent());
  EXPECT_EQ(q.firings, (std::vector<std::int64_t>{3, 2, 5, 1}));
}

TEST(SdfConsistency, AFlatSingleAppearanceScheduleWhereOneExists) {
  // b is listed first and its 2 initial tokens enable one of its two firings: firing whatever is
  // enabled would give "b a b"; a before b is single-appearance.
  Graph g = graph("ba", {{'a', 'b', 4, 2, 2}});
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent());
  Iteration it = runIteration(g, q.firings);
  EXPECT_TRUE(it.deadlockFree);
  EXPECT_EQ(scheduleText(g, it.schedule), "a 2b");
  EXPECT_EQ(it.maxTokens, (std::vector<std::int64_t>{6}));
  // a and b wait for each other within an iteration (2 firings each, one token each way): no flat
  // single-appearance schedule, but an iteration still runs.
  Graph cycle = graph("cab", {{'c', 'a', 2, 1, 0}, {'a', 'b', 1, 1, 1}, {'b', 'a', 1, 1, 1}});
  q = repetitionVector(cycle);
  ASSERT_EQ(q.firings, (std::vector<std::int64_t>{1, 2, 2}));
  it = runIteration(cycle, q.firings);
  EXPECT_TRUE(it.deadlockFree);
  EXPECT_EQ(scheduleText(cycle, it.schedule), "c a 2b a");
}

TEST(SdfConsistency, CountsPast64BitsAreAnErrorNotAWrapAround) {
  // Each stage multiplies the firings by 10^9: a fires 10^18 times per firing of c, which fits in
  // 64 bits; one more stage (10^27) does not.
  Graph g = graph("abcd", {{'b', 'a', 1000000000, 1, 0}, {'c', 'b', 1000000000, 1, 0}});
  RepetitionVector q = repetitionVector(g);
  ASSERT_TRUE(q.consistent()) << q.error;
  EXPECT_EQ(q.firings[0], 1000000000000000000);
  // The schedule keeps runs, not single firings: 10^18 of them are one entry.
  Iteration it = runIteration(g, q.firings);
  EXPECT_TRUE(it.deadlockFree) << it.error;
  EXPECT_EQ(scheduleText(g, it.schedule), "c 1000000000b 1000000000000000000a d");  // d has no channels
  // a's 10^18 firings producing 10^9 tokens each are refused, not run into an overflow.
  Graph wide = g;
  wide.channels.push_back({"ad", 0, 3, 1000000000, 1000000000, 0, {}});
  wide.channels.push_back({"da", 3, 0, 1, 1, 1, {}});
  RepetitionVector wq = repetitionVector(wide);
  ASSERT_TRUE(wq.consistent()) << wq.error;
  it = runIteration(wide, wq.firings);
  EXPECT_FALSE(it.deadlockFree);
  EXPECT_NE(it.error.find("64 bits"), std::string::npos);
  g.channels.push_back({"dc", 3, 2, 1000000000, 1, 0, {}});
  q = repetitionVector(g);
  EXPECT_FALSE(q.consistent());
  EXPECT_NE(q.error.find("64 bits"), std::string::npos);
}

std::map<std::string, std::int64_t> byName(const Graph& g, const std::vector<std::int64_t>& q) {
  std::map<std::string, std::int64_t> out;
  for (std::size_t a = 0; a < g.actors.size(); ++a) out[g.actors[a].name] = q[a];
  return out;
}

TEST(SdfConsistency, Sdf3BenchmarksHaveSdf3sRepetitionVectors) {
  // specs/benchmarks/sdf3/README.md: the repetition vectors SDF3 computes.
  const std::map<std::string, std::map<std::string, std::int64_t>> expected = {
      {"h263decoder", {{"vld", 1}, {"iq", 594}, {"idct", 594}, {"mc", 1}}},
      {"modem", {{"fork1", 1}, {"biq", 1}, {"bi", 1}, {"add", 1}, {"ac", 1}, {"fork2", 2}, {"conj", 1}, {"mul1", 1},
                 {"in", 16}, {"filt", 16}, {"hil", 2}, {"eq", 1}, {"mul2", 1}, {"deci", 1}, {"deco", 1}, {"out", 1}}},
      {"samplerate", {{"a", 147}, {"b", 147}, {"c", 98}, {"d", 28}, {"e", 32}, {"f", 160}}},
      {"satellite", {{"a", 1056}, {"b", 264}, {"c", 24}, {"d", 1056}, {"e", 264}, {"f", 24}, {"g", 24}, {"h", 24}, {"i", 24},
                     {"j", 240}, {"k", 24}, {"l", 24}, {"m", 24}, {"n", 240}, {"p", 240}, {"q", 1}, {"r", 1}, {"s", 240},
                     {"t", 240}, {"u", 240}, {"v", 1}, {"w", 240}}},
  };
  for (const auto& [name, vector] : expected) {
    SCOPED_TRACE(name);
    Graph g = sdf3Benchmark(name);
    RepetitionVector q = repetitionVector(g);
    ASSERT_TRUE(q.consistent()) << q.error;
    EXPECT_EQ(byName(g, q.firings), vector);
    EXPECT_TRUE(runIteration(g, q.firings).deadlockFree);
  }
  // The mp3 decoder: huffman once, every other actor twice.
  Graph mp3 = sdf3Benchmark("mp3decoder_granule_parallelism");
  RepetitionVector q = repetitionVector(mp3);
  ASSERT_TRUE(q.consistent()) << q.error;
  ASSERT_EQ(mp3.actors.size(), 14u);
  for (std::size_t a = 0; a < mp3.actors.size(); ++a) EXPECT_EQ(q.firings[a], mp3.actors[a].name == "huffman" ? 1 : 2) << mp3.actors[a].name;
  EXPECT_TRUE(runIteration(mp3, q.firings).deadlockFree);
}

TEST(SdfConsistency, Sdf3ExecutionTimesAreRead) {
  Graph g = sdf3Benchmark("samplerate");
  ASSERT_EQ(g.actors.size(), 6u);
  EXPECT_EQ(g.actors[0].name, "a");
  EXPECT_EQ(g.actors[0].executionTime, 5);
  EXPECT_EQ(g.actors[1].executionTime, 2);
  EXPECT_EQ(g.channels.size(), 11u);
  EXPECT_EQ(g.channels[2].production, 2);   // ch3: c -> d, 2 : 7
  EXPECT_EQ(g.channels[2].consumption, 7);
  EXPECT_EQ(g.channels[5].initialTokens, 1);  // _ch6, a's self-loop
}

}  // namespace
}  // namespace semo::sdf
