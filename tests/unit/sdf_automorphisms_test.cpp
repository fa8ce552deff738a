// Symmetries of SDF graphs (automorphisms.hpp): found from the graph, exact, and the front's use of
// them (a distribution and its image have the same period); fronts of generated mp3-like graphs
// (specs/benchmarks/generated) with and without alike branches.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "semo/sdf/automorphisms.hpp"
#include "semo/sdf/buffers.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/cycle_ratio.hpp"
#include "semo/sdf/sdf3_xml.hpp"

#include "sdf_test_support.hpp"

namespace semo::sdf {
namespace {

using test::benchmarkGraph;

ActorId actorNamed(const Graph& g, const std::string& name) {
  for (ActorId a = 0; a < g.actors.size(); ++a) {
    if (g.actors[a].name == name) return a;
  }
  ADD_FAILURE() << name;
  return 0;
}

std::size_t channelNamed(const Graph& g, const std::string& name) {
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (g.channels[c].name == name) return c;
  }
  ADD_FAILURE() << name;
  return 0;
}

// The actors the automorphisms reach from `a` (its orbit under the group they generate).
std::set<ActorId> orbit(const std::vector<Automorphism>& generators, ActorId a) {
  std::set<ActorId> out{a};
  std::vector<ActorId> pending{a};
  while (!pending.empty()) {
    ActorId x = pending.back();
    pending.pop_back();
    for (const Automorphism& s : generators) {
      if (out.insert(s.actor[x]).second) pending.push_back(s.actor[x]);
    }
  }
  return out;
}

TEST(SdfAutomorphisms, TheMp3DecodersGranuleBranchesSwap) {
  // The stereo stage joins the branches, and nothing ties its inputs from branch 0 to its outputs
  // to branch 0 (ports are not part of the graph): the halves before and after it swap on their own.
  Graph g = benchmarkGraph("sdf3/mp3decoder_granule_parallelism.xml");
  std::vector<Automorphism> found = findAutomorphisms(g);
  ASSERT_EQ(found.size(), 2u);
  const Automorphism& before = found[0];
  const Automorphism& after = found[1];
  EXPECT_EQ(before.actor[actorNamed(g, "req0")], actorNamed(g, "req1"));
  EXPECT_EQ(before.actor[actorNamed(g, "reorder1")], actorNamed(g, "reorder0"));
  EXPECT_EQ(before.actor[actorNamed(g, "IMDCT0")], actorNamed(g, "IMDCT0"));
  EXPECT_EQ(before.channel[channelNamed(g, "ch0")], channelNamed(g, "ch1"));    // huffman -> req0 onto huffman -> req1
  EXPECT_EQ(before.channel[channelNamed(g, "ch17")], channelNamed(g, "ch18"));  // req0 -> stereo onto req1 -> stereo
  EXPECT_EQ(after.actor[actorNamed(g, "synth1")], actorNamed(g, "synth0"));
  EXPECT_EQ(after.actor[actorNamed(g, "req0")], actorNamed(g, "req0"));
  EXPECT_EQ(after.channel[channelNamed(g, "ch19")], channelNamed(g, "ch20"));   // stereo -> IMDCT0 onto stereo -> IMDCT1
  for (const Automorphism& sigma : found) {
    EXPECT_EQ(sigma.actor[actorNamed(g, "huffman")], actorNamed(g, "huffman"));
    EXPECT_EQ(sigma.actor[actorNamed(g, "stereo")], actorNamed(g, "stereo"));
    EXPECT_EQ(sigma.channel[channelNamed(g, "ch14")], channelNamed(g, "ch14"));  // huffman's self-loop stays
    // Every permutation returned is exact.
    Automorphism again;
    EXPECT_TRUE(completeAutomorphism(g, sigma.actor, again));
    EXPECT_EQ(again.channel, sigma.channel);
  }
}

TEST(SdfAutomorphisms, NoneWhereTheBranchesDiffer) {
  // One execution time or one token changed after the stereo stage: its halves no longer swap
  // (the halves before it still do).
  Graph base = benchmarkGraph("sdf3/mp3decoder_granule_parallelism.xml");
  Graph slower = base;
  slower.actors[actorNamed(slower, "IMDCT1")].executionTime += 1;
  std::vector<Automorphism> found = findAutomorphisms(slower);
  EXPECT_EQ(orbit(found, actorNamed(slower, "IMDCT0")).size(), 1u);
  EXPECT_EQ(orbit(found, actorNamed(slower, "synth0")).size(), 1u);
  EXPECT_EQ(orbit(found, actorNamed(slower, "req0")).size(), 2u);
  Graph token = base;
  token.channels[channelNamed(token, "ch13")].initialTokens = 1;
  EXPECT_EQ(orbit(findAutomorphisms(token), actorNamed(token, "freqinv1")).size(), 1u);
  Graph rate = base;
  rate.channels[channelNamed(rate, "ch0")].production = 3;  // inconsistent, but the symmetry is gone
  EXPECT_EQ(orbit(findAutomorphisms(rate), actorNamed(rate, "req0")).size(), 1u);
  // A permutation that is not one is refused: req0 with reorder0.
  std::vector<ActorId> image(base.actors.size());
  for (ActorId a = 0; a < image.size(); ++a) image[a] = a;
  std::swap(image[actorNamed(base, "req0")], image[actorNamed(base, "reorder0")]);
  Automorphism none;
  EXPECT_FALSE(completeAutomorphism(base, image, none));
}

TEST(SdfAutomorphisms, ManyAlikeBranchesFormOneOrbit) {
  Graph g = benchmarkGraph("generated/mp3family_b8_g16.xml");
  std::vector<Automorphism> found = findAutomorphisms(g);
  EXPECT_EQ(orbit(found, actorNamed(g, "req0")).size(), 8u);
  EXPECT_EQ(orbit(found, actorNamed(g, "IMDCT3")).size(), 8u);
  EXPECT_EQ(orbit(found, actorNamed(g, "stereo")).size(), 1u);
  Graph skewed = benchmarkGraph("generated/mp3family_b8_g8_skew10.xml");
  EXPECT_TRUE(findAutomorphisms(skewed).empty());
}

TEST(SdfAutomorphisms, ADistributionAndItsImageHaveOnePeriod) {
  // What the front relies on to learn a clause's images: the period is invariant.
  Graph g = benchmarkGraph("generated/mp3family_b4_g16.xml");
  RepetitionVector q = repetitionVector(g);
  HsdfExpansion expansion(g, q.firings);
  std::vector<Automorphism> found = findAutomorphisms(g);
  ASSERT_FALSE(found.empty());
  std::mt19937_64 random(11);
  for (int sample = 0; sample < 20; ++sample) {
    std::vector<std::optional<std::int64_t>> capacities(g.channels.size());
    for (std::size_t c = 0; c < g.channels.size(); ++c) {
      if (!g.channels[c].selfLoop()) capacities[c] = smallestCapacity(g.channels[c]) + static_cast<std::int64_t>(random() % 12);
    }
    const Automorphism& sigma = found[random() % found.size()];
    std::vector<std::optional<std::int64_t>> image(g.channels.size());
    for (std::size_t c = 0; c < g.channels.size(); ++c) image[sigma.channel[c]] = capacities[c];
    CycleRatioResult a = expansion.evaluate(capacities), b = expansion.evaluate(image);
    ASSERT_TRUE(a.error.empty() && b.error.empty());
    EXPECT_EQ(a.deadlock, b.deadlock);
    EXPECT_EQ(a.period, b.period);
  }
}

std::vector<std::pair<std::int64_t, Period>> frontOf(const std::string& path, std::size_t& points) {
  Graph g = benchmarkGraph(path);
  RepetitionVector q = repetitionVector(g);
  ParetoFront f = bufferParetoFront(g, q.firings, 100'000);
  EXPECT_TRUE(f.error.empty()) << f.error;
  points = f.points.size();
  if (f.points.empty()) return {};
  return {{f.points.front().total, f.points.front().period}, {f.points.back().total, f.points.back().period}};
}

TEST(SdfAutomorphisms, GeneratedFronts) {
  // specs/benchmarks/generated/README.md. The SDF3 graph rebuilt by the generator has its front.
  std::size_t points = 0;
  EXPECT_EQ(frontOf("generated/mp3family_b2_g2.xml", points), (std::vector<std::pair<std::int64_t, Period>>{{20, {2180506, 1}}, {76, {278650, 1}}}));
  EXPECT_EQ(points, 29u);
  EXPECT_EQ(frontOf("generated/mp3family_b8_g16.xml", points), (std::vector<std::pair<std::int64_t, Period>>{{192, {17444048, 1}}, {416, {2229200, 1}}}));
  EXPECT_EQ(points, 29u);
  EXPECT_EQ(frontOf("generated/mp3family_b8_g8_skew10.xml", points).back(), (std::pair<std::int64_t, Period>{288, {1894816, 1}}));
  EXPECT_EQ(points, 159u);
}

}  // namespace
}  // namespace semo::sdf
