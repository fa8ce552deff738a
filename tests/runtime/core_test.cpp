// The runtime's building blocks: seeded random streams, loss models, knowledge stores.
#include <gtest/gtest.h>

#include <cmath>

#include "semo/runtime/knowledge.hpp"
#include "semo/runtime/loss.hpp"
#include "semo/runtime/random.hpp"

namespace semo::runtime {
namespace {

TEST(RandomStream, MatchesTheReferenceSequence) {
  // xoshiro256** from the state {1, 2, 3, 4}: the published algorithm's first outputs.
  RandomStream r = RandomStream::fromState(1, 2, 3, 4);
  EXPECT_EQ(r.next(), 11520u);
  EXPECT_EQ(r.next(), 0u);
  EXPECT_EQ(r.next(), 1509978240u);
  EXPECT_EQ(r.next(), 1215971899390074240u);
}

TEST(RandomStream, SameSeedSameDrawsOtherPurposeOtherDraws) {
  RandomStream a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next(), b.next());
  EXPECT_NE(RandomStream(42).next(), c.next());
  RandomStream x = RandomStream::derive(7, "latency", 0), y = RandomStream::derive(7, "loss", 0), z = RandomStream::derive(7, "latency", 1);
  const std::uint64_t vx = x.next(), vy = y.next(), vz = z.next();
  EXPECT_NE(vx, vy);
  EXPECT_NE(vx, vz);
  EXPECT_EQ(RandomStream::derive(7, "latency", 0).next(), vx);
}

TEST(RandomStream, UniformBernoulliAndBelow) {
  RandomStream r(5);
  int hits = 0;
  const int n = 1000000;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    hits += r.bernoulli(0.2) ? 1 : 0;
  }
  EXPECT_NEAR(hits / static_cast<double>(n), 0.2, 0.002);
  // bernoulli always draws once, whatever p, so that streams stay aligned.
  RandomStream p(9), q(9);
  EXPECT_FALSE(p.bernoulli(0));
  EXPECT_TRUE(p.bernoulli(1));
  q.next(), q.next();
  EXPECT_EQ(p.next(), q.next());
  std::vector<int> counts(6, 0);
  for (int i = 0; i < 60000; ++i) ++counts[r.below(6)];
  for (int c : counts) EXPECT_NEAR(c, 10000, 400);
}

TEST(LossModel, ParsesAndRefuses) {
  std::string error;
  auto burst = LossModel::parse("burst:3", error);
  ASSERT_TRUE(burst);
  EXPECT_EQ(burst->kind, LossModel::Kind::Burst);
  EXPECT_EQ(burst->burst, 3);
  auto ge = LossModel::parse("gilbert:0.1,0.5", error);
  ASSERT_TRUE(ge);
  EXPECT_DOUBLE_EQ(ge->goodToBad, 0.1);
  EXPECT_TRUE(LossModel::parse("bernoulli", error));
  for (const char* bad : {"x", "burst:0", "burst:2.5", "gilbert:0.1", "gilbert:2,0.5", "gilbert:0.1,0"}) {
    error.clear();
    EXPECT_FALSE(LossModel::parse(bad, error)) << bad;
    EXPECT_NE(error.find("--loss-model: expected bernoulli, burst:N or gilbert:P,R, got '"), std::string::npos) << error;
  }
}

TEST(LinkLoss, RatesAndBursts) {
  RandomStream r(11);
  LossModel independent;
  independent.p = 0.3;
  LinkLoss link(independent);
  int lost = 0;
  for (int i = 0; i < 200000; ++i) lost += link.lose(r) ? 1 : 0;
  EXPECT_NEAR(lost / 200000.0, 0.3, 0.005);

  LossModel bursts;
  bursts.kind = LossModel::Kind::Burst;
  bursts.p = 0.05;
  bursts.burst = 4;
  LinkLoss b(bursts);
  int run = 0;
  for (int i = 0; i < 100000; ++i) {
    if (b.lose(r)) {
      ++run;
    } else {
      if (run > 0) {
        EXPECT_EQ(run % 4, 0) << "losses come in bursts of exactly 4 (or back-to-back bursts)";
      }
      run = 0;
    }
  }

  LossModel gilbert;
  gilbert.kind = LossModel::Kind::GilbertElliott;
  gilbert.goodToBad = 0.05;
  gilbert.badToGood = 0.2;
  LinkLoss g(gilbert);
  lost = 0;
  for (int i = 0; i < 400000; ++i) lost += g.lose(r) ? 1 : 0;
  EXPECT_NEAR(lost / 400000.0, 0.05 / (0.05 + 0.2), 0.01);  // the chain's stationary share of Bad

  // A message sent four times is lost only if every copy is: p^4.
  LinkLoss again(independent);
  lost = 0;
  for (int i = 0; i < 400000; ++i) lost += again.loseWithRetransmissions(r, 3) ? 1 : 0;
  EXPECT_NEAR(lost / 400000.0, std::pow(0.3, 4), 0.002);
}

TEST(KnowledgeStore, DiscoverCountsDistinctFactsAndStamps) {
  KnowledgeStore s({"red", "yellow", "blue"}, KnowledgeStore::Merge::Newest);
  std::uint64_t clock = 0;
  EXPECT_TRUE(s.discover(0, 3, clock));
  EXPECT_FALSE(s.discover(0, 3, clock));
  EXPECT_EQ(s.count(), 1);
  EXPECT_EQ(clock, 2u);
  EXPECT_EQ(s.stamp(0).lamport, 2u) << "newest: the fresh sighting is kept";
  EXPECT_TRUE(s.holds(0));
  EXPECT_FALSE(s.holds(1));
  EXPECT_FALSE(s.holds(7));
}

TEST(KnowledgeStore, NewestKeepsTheLastWriterUnionTheFirst) {
  for (auto policy : {KnowledgeStore::Merge::Newest, KnowledgeStore::Merge::Union}) {
    KnowledgeStore a({"x"}, policy), b({"x"}, policy);
    std::uint64_t ca = 0, cb = 5;
    a.discover(0, 0, ca);  // stamp (1, 0)
    b.discover(0, 1, cb);  // stamp (6, 1)
    EXPECT_EQ(a.merge(b, ca), 0);
    EXPECT_EQ(a.stamp(0), (policy == KnowledgeStore::Merge::Newest ? FactStamp{6, 1} : FactStamp{1, 0}));
    EXPECT_GE(ca, 6u) << "the clock moves past every stamp seen";
  }
}

TEST(KnowledgeStore, MergeIsCommutativeAssociativeAndIdempotent) {
  RandomStream r(21);
  const std::vector<std::string> facts{"a", "b", "c", "d", "e"};
  for (int round = 0; round < 200; ++round) {
    const auto policy = round % 2 == 0 ? KnowledgeStore::Merge::Newest : KnowledgeStore::Merge::Union;
    std::vector<KnowledgeStore> s(3, KnowledgeStore(facts, policy));
    std::vector<std::uint64_t> clocks(3, 0);
    for (int k = 0; k < 6; ++k) {
      const auto who = static_cast<std::size_t>(r.below(3));
      s[who].discover(static_cast<std::uint32_t>(r.below(5)), static_cast<std::uint32_t>(who), clocks[who]);
    }
    std::uint64_t t = 100;
    KnowledgeStore ab = s[0], ba = s[1];
    ab.merge(s[1], t);
    ba.merge(s[0], t);
    EXPECT_TRUE(ab.sameFactsAs(ba));
    for (std::uint32_t f = 0; f < facts.size(); ++f) {
      if (ab.holds(f)) {
        EXPECT_EQ(ab.stamp(f), ba.stamp(f));
      }
    }
    KnowledgeStore left = ab, right = s[1];
    left.merge(s[2], t);
    right.merge(s[2], t);
    KnowledgeStore right2 = s[0];
    right2.merge(right, t);
    EXPECT_TRUE(left.sameFactsAs(right2));
    const int before = left.count();
    EXPECT_EQ(left.merge(left, t), 0);
    EXPECT_EQ(left.count(), before);
    // The count after merging lies where the model's learn rules allow it: max(a, b) .. a + b.
    EXPECT_GE(ab.count(), std::max(s[0].count(), s[1].count()));
    EXPECT_LE(ab.count(), s[0].count() + s[1].count());
  }
}

}  // namespace
}  // namespace semo::runtime
