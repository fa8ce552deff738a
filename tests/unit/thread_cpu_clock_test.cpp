// The clock the searches' time budgets count (thread_cpu_clock.hpp): it runs while the thread
// works and stands still while the thread waits, which is what keeps a budget from running out
// on a busy machine while the search is not running.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "../../checker/src/thread_cpu_clock.hpp"

namespace semo::checker::detail {
namespace {

TEST(ThreadCpuClock, StandsStillWhileTheThreadSleeps) {
  const auto before = ThreadCpuClock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto slept = ThreadCpuClock::now() - before;
  // Waking up costs microseconds; a wall clock would show 300 ms.
  EXPECT_LT(slept, std::chrono::milliseconds(100));
}

TEST(ThreadCpuClock, RunsWhileTheThreadWorks) {
  const auto before = ThreadCpuClock::now();
  volatile std::uint64_t sink = 0;
  // Work until the clock has moved 20 ms (or, should it stand still, 10 s have passed).
  const auto wallStart = std::chrono::steady_clock::now();
  while (ThreadCpuClock::now() - before < std::chrono::milliseconds(20) &&
         std::chrono::steady_clock::now() - wallStart < std::chrono::seconds(10)) {
    for (int i = 0; i < 10000; ++i) sink = sink + static_cast<std::uint64_t>(i);
  }
  EXPECT_GE(ThreadCpuClock::now() - before, std::chrono::milliseconds(20));
}

TEST(ThreadCpuClock, CountsOnlyItsOwnThread) {
  // Another thread's work is not this thread's time.
  const auto before = ThreadCpuClock::now();
  std::thread busy([] {
    const auto start = ThreadCpuClock::now();
    volatile std::uint64_t sink = 0;
    while (ThreadCpuClock::now() - start < std::chrono::milliseconds(200)) sink = sink + 1;
  });
  busy.join();
  EXPECT_LT(ThreadCpuClock::now() - before, std::chrono::milliseconds(100));
}

}  // namespace
}  // namespace semo::checker::detail
