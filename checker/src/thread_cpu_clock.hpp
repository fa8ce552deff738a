#pragma once
// The processor time of the calling thread, as a std::chrono clock. The searches that give up after
// a time (the symbolic search, the random walks) count it rather than the wall clock: on a loaded
// machine (a test suite run two at a time, the other property's search on the second core) the wall
// clock runs on while the search waits for a core, and a proof that fits its budget alone ran out of
// time there. Counted this way, a search does the same work on a busy machine as on an idle one.
#include <chrono>
#include <ctime>

namespace semo::checker::detail {

struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<ThreadCpuClock>;
  static constexpr bool is_steady = true;
  static time_point now() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return time_point(std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec));
  }
};

}  // namespace semo::checker::detail
