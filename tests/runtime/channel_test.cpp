// Bounded channels, token counters and the static schedule runner: FIFO order across the ring's
// wrap-around, the proven capacity never exceeded (and an overflow reported when it would be), and
// SDF schedules that come back to their initial tokens after one iteration.
#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "semo/runtime/channel.hpp"
#include "semo/runtime/random.hpp"

namespace semo::runtime {
namespace {

TEST(BoundedChannel, WrapsAroundInFifoOrder) {
  BoundedChannel<int> channel(3);
  EXPECT_EQ(channel.capacity(), 3u);
  EXPECT_TRUE(channel.empty());
  int value = 0;
  EXPECT_FALSE(channel.tryPop(value));
  for (int round = 0; round < 5; ++round) {  // head moves past the end of the ring each round
    EXPECT_TRUE(channel.tryPush(10 * round + 1));
    EXPECT_TRUE(channel.tryPush(10 * round + 2));
    ASSERT_TRUE(channel.tryPop(value));
    EXPECT_EQ(value, 10 * round + 1);
    ASSERT_TRUE(channel.tryPop(value));
    EXPECT_EQ(value, 10 * round + 2);
  }
  EXPECT_TRUE(channel.tryPush(1));
  EXPECT_TRUE(channel.tryPush(2));
  EXPECT_TRUE(channel.tryPush(3));
  EXPECT_TRUE(channel.full());
  EXPECT_FALSE(channel.tryPush(4));
  EXPECT_EQ(channel.size(), 3u);
  for (int expected : {1, 2, 3}) {
    ASSERT_TRUE(channel.tryPop(value));
    EXPECT_EQ(value, expected);
  }
  EXPECT_FALSE(channel.overflowed());  // tryPush refusing is no overflow
}

TEST(BoundedChannel, KeepsFifoOrderAndItsCapacityOverManyOperations) {
  RandomStream rng(12);
  BoundedChannel<std::uint64_t> channel(7);
  std::deque<std::uint64_t> model;
  std::uint64_t next = 0;
  for (int i = 0; i < 100000; ++i) {
    if (rng.bernoulli(0.55)) {
      const bool pushed = channel.tryPush(next);
      EXPECT_EQ(pushed, model.size() < 7);
      if (pushed) model.push_back(next);
      ++next;
    } else {
      std::uint64_t value = 0;
      const bool popped = channel.tryPop(value);
      ASSERT_EQ(popped, !model.empty());
      if (popped) {
        ASSERT_EQ(value, model.front());
        model.pop_front();
      }
    }
    ASSERT_LE(channel.size(), channel.capacity());
    ASSERT_EQ(channel.size(), model.size());
  }
}

TEST(BoundedChannel, ZeroCapacityIsAlwaysFull) {
  BoundedChannel<int> channel(0);
  EXPECT_TRUE(channel.full());
  EXPECT_TRUE(channel.empty());
  EXPECT_FALSE(channel.tryPush(1));
}

TEST(BoundedChannel, PushPastTheProvenCapacityIsReported) {
  BoundedChannel<int> channel(2);
  channel.push(1);
  channel.push(2);
  EXPECT_FALSE(channel.overflowed());
#ifdef NDEBUG
  channel.push(3);  // release: dropped and recorded
  EXPECT_TRUE(channel.overflowed());
  EXPECT_EQ(channel.size(), 2u);
  int value = 0;
  ASSERT_TRUE(channel.tryPop(value));
  EXPECT_EQ(value, 1);
#else
  EXPECT_DEATH(channel.push(3), "overflow");  // debug: the assert stops the program
#endif
}

TEST(TokenCounter, CountsWithinItsCapacity) {
  TokenCounter counter(5, 2);
  EXPECT_EQ(counter.tokens(), 2);
  EXPECT_EQ(counter.space(), 3);
  EXPECT_TRUE(counter.tryProduce(3));
  EXPECT_TRUE(counter.full());
  EXPECT_FALSE(counter.tryProduce(1));
  EXPECT_FALSE(counter.tryConsume(6));
  EXPECT_EQ(counter.tokens(), 5);
  EXPECT_TRUE(counter.tryConsume(5));
  EXPECT_TRUE(counter.empty());
}

using Firing = StaticSchedule::Firing;
using Channel = StaticSchedule::Channel;

// Runs `iterations` iterations and checks that each completes and ends at the initial tokens,
// with every channel within its capacity after every firing.
void expectPeriodic(StaticSchedule& schedule, int iterations, const std::vector<Id>& expectedOrder) {
  for (int i = 0; i < iterations; ++i) {
    std::vector<Id> order;
    const bool ok = schedule.runIteration([&](Id task) {
      order.push_back(task);
      for (Id c = 0; c < schedule.channelCount(); ++c) {
        ASSERT_LE(schedule.tokens(c).tokens(), schedule.channel(c).capacity);
        ASSERT_GE(schedule.tokens(c).tokens(), 0);
      }
    });
    ASSERT_TRUE(ok) << "stalled at task " << schedule.stalledTask() << " channel " << schedule.stalledChannel();
    EXPECT_EQ(order, expectedOrder);
    EXPECT_TRUE(schedule.atInitialTokens());
  }
  EXPECT_EQ(schedule.iterations(), static_cast<std::uint64_t>(iterations));
}

TEST(StaticSchedule, ChainWithRatesTwoAndThree) {
  // A -2-> B -3-> ... : A produces 2, B consumes 3 and produces 1, C consumes 2.
  // Repetitions: A 3, B 2, C 1. Capacities: what the schedule A A B A B C needs.
  StaticSchedule schedule({{0, 2}, {1, 1}, {0, 1}, {1, 1}, {2, 1}},
                          {{0, 1, 2, 3, 0, 4}, {1, 2, 1, 2, 0, 2}});
  expectPeriodic(schedule, 5, {0, 0, 1, 0, 1, 2});
}

TEST(StaticSchedule, CycleWithInitialTokens) {
  // A -> B -> A with 2 initial tokens on the back edge (B -> A), and a self-loop on B holding its
  // state (one token, capacity one).
  StaticSchedule schedule({{0, 2}, {1, 2}},
                          {{0, 1, 1, 1, 0, 2}, {1, 0, 1, 1, 2, 2}, {1, 1, 1, 1, 1, 1}});
  expectPeriodic(schedule, 3, {0, 0, 1, 1});
  EXPECT_EQ(schedule.tokens(1).tokens(), 2);
}

TEST(StaticSchedule, CapacityExactlyTheMinimum) {
  // A produces 3, B consumes 2: repetitions A 2, B 3. Schedule A B A B B needs 4 on the channel
  // (3, then 1 + 3); capacity 4 runs, capacity 3 overflows on the second firing of A.
  StaticSchedule tight({{0, 1}, {1, 1}, {0, 1}, {1, 2}}, {{0, 1, 3, 2, 0, 4}});
  expectPeriodic(tight, 4, {0, 1, 0, 1, 1});

  StaticSchedule tooSmall({{0, 1}, {1, 1}, {0, 1}, {1, 2}}, {{0, 1, 3, 2, 0, 3}});
  std::vector<Id> fired;
  EXPECT_FALSE(tooSmall.runIteration([&](Id task) { fired.push_back(task); }));
  EXPECT_EQ(tooSmall.stall(), StaticSchedule::Stall::Overflow);
  EXPECT_EQ(tooSmall.stalledTask(), 0u);
  EXPECT_EQ(tooSmall.stalledChannel(), 0u);
  EXPECT_EQ(fired, (std::vector<Id>{0, 1}));
  EXPECT_EQ(tooSmall.tokens(0).tokens(), 1);  // the stalled firing moved nothing
  EXPECT_EQ(tooSmall.iterations(), 0u);
  tooSmall.reset();
  EXPECT_TRUE(tooSmall.atInitialTokens());
  EXPECT_EQ(tooSmall.stall(), StaticSchedule::Stall::None);
}

TEST(StaticSchedule, ReportsAStarvedFiring) {
  // B fires before A has produced anything: not a valid schedule.
  StaticSchedule schedule({{1, 1}, {0, 1}}, {{0, 1, 1, 1, 0, 1}});
  EXPECT_FALSE(schedule.runIteration([](Id) {}));
  EXPECT_EQ(schedule.stall(), StaticSchedule::Stall::Starved);
  EXPECT_EQ(schedule.stalledTask(), 1u);
  EXPECT_EQ(schedule.stalledChannel(), 0u);
}

}  // namespace
}  // namespace semo::runtime
