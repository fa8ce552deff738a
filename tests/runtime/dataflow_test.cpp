// A robot's dataflow as the runtime runs it: a projected scenario becomes a static schedule with the
// same firings and channels (forScenario), and the runner fires one iteration per scenario period,
// switches scenarios between iterations, never runs an unproven scenario, and stops a scenario whose
// channel is too small, saying where.
#include <gtest/gtest.h>

#include <vector>

#include "dataflow_sample.hpp"
#include "semo/runtime/dataflow.hpp"

namespace semo::runtime {
namespace {

TEST(StaticSchedule, ForScenarioKeepsTheProjectedScheduleAndChannels) {
  const ScenarioTable s = sample::chainScenario("RUN", 10000, 3);
  StaticSchedule schedule = StaticSchedule::forScenario(s);
  ASSERT_EQ(schedule.channelCount(), s.channels.size());
  for (Id k = 0; k < s.channels.size(); ++k) {
    const StaticSchedule::Channel& c = schedule.channel(k);
    EXPECT_EQ(c.from, s.channels[k].from);
    EXPECT_EQ(c.to, s.channels[k].to);
    EXPECT_EQ(c.production, s.channels[k].production);
    EXPECT_EQ(c.consumption, s.channels[k].consumption);
    EXPECT_EQ(c.initialTokens, s.channels[k].initialTokens);
    EXPECT_EQ(c.capacity, s.channels[k].capacity);
    EXPECT_EQ(schedule.tokens(k).tokens(), s.channels[k].initialTokens);
  }
  // The firings come out in the table's order, each run repeated.
  std::vector<Id> expected;
  for (const ScenarioTable::Firing& f : s.schedule) expected.insert(expected.end(), static_cast<std::size_t>(f.repetitions), f.task);
  for (int i = 0; i < 3; ++i) {
    std::vector<Id> fired;
    ASSERT_TRUE(schedule.runIteration([&](Id task) { fired.push_back(task); }));
    EXPECT_EQ(fired, expected);
    EXPECT_TRUE(schedule.atInitialTokens());
  }
  // The schedule fills every channel exactly to the capacity the sample gives it.
  for (Id k = 0; k < s.channels.size(); ++k) EXPECT_EQ(schedule.maxTokens(k), s.channels[k].capacity) << k;
}

TEST(DataflowRunner, OneIterationPerPeriodExactly) {
  const DataflowTable table = sample::chainTable();
  DataflowRunner runner(table);
  EXPECT_EQ(runner.selected(), kNone);
  EXPECT_EQ(runner.advance(50000).iterations, 0u);  // nothing selected: nothing runs
  runner.select(0);
  // Period 10/3 ms: iterations start at 0, 3.33, ..., 46.67 ms: 15 in the first 50 ms, 15 more in the next.
  EXPECT_EQ(runner.advance(50000).iterations, 15u);
  EXPECT_EQ(runner.advance(50000).iterations, 15u);
  EXPECT_EQ(runner.advance(1).iterations, 1u);  // the one at exactly 100 ms
  EXPECT_EQ(runner.iterations(0), 31u);
  // Another scenario starts at once and then every 7 ms: 0, 7, ..., 49 (8), then 56, ..., 98 (7).
  runner.select(1);
  EXPECT_EQ(runner.advance(50000).iterations, 8u);
  EXPECT_EQ(runner.advance(50000).iterations, 7u);
  // Selecting the running scenario again changes nothing; coming back restarts the count.
  runner.select(1);
  EXPECT_EQ(runner.advance(5000).iterations, 0u);  // [100 ms, 105 ms): none starts
  EXPECT_EQ(runner.advance(1).iterations, 1u);     // the one at 105 ms
  runner.select(0);
  EXPECT_EQ(runner.advance(1).iterations, 1u);
  EXPECT_TRUE(runner.schedule(0).atInitialTokens());
  for (Id c = 0; c < table.channels.size(); ++c) EXPECT_EQ(runner.maxFill(c), table.channels[c].capacity) << c;
}

TEST(DataflowRunner, NeverRunsAnUnprovenScenario) {
  const DataflowTable table = sample::chainTable();
  DataflowRunner runner(table);
  EXPECT_TRUE(runner.runnable(0));
  EXPECT_FALSE(runner.runnable(2));
  EXPECT_FALSE(runner.runnable(7));
  runner.select(2);
  EXPECT_EQ(runner.advance(1000000).iterations, 0u);
  EXPECT_EQ(runner.iterations(2), 0u);
  for (Id c = 0; c < table.channels.size(); ++c) EXPECT_EQ(runner.maxFill(c), 0) << c;  // nothing ran
}

TEST(DataflowRunner, AChannelBelowTheProvenCapacityStopsItsScenario) {
  DataflowTable table = sample::chainTable();
  table.scenarios[0].channels[1].capacity = 3;  // A -> B needs 4
  DataflowRunner runner(table);
  runner.select(0);
  const DataflowRunner::Advance done = runner.advance(50000);
  EXPECT_EQ(done.iterations, 0u);
  EXPECT_EQ(done.stall, StaticSchedule::Stall::Overflow);
  EXPECT_EQ(done.task, 1u);     // A's second firing
  EXPECT_EQ(done.channel, 1u);  // on A -> B
  EXPECT_TRUE(runner.stopped(0));
  EXPECT_EQ(runner.advance(50000).iterations, 0u);  // it stays stopped
  runner.select(1);                                 // the other scenarios still run
  EXPECT_EQ(runner.advance(7000).iterations, 1u);
}

}  // namespace
}  // namespace semo::runtime
