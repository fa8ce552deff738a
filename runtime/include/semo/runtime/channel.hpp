#pragma once
// The channels of a robot's task graph (taskgraph.md) and the static schedule that runs them. The
// SDF analysis proved each channel's capacity and a schedule that never blocks or overflows within
// it; the runtime allocates exactly that capacity once and never grows it. An overflow is thus
// impossible by proof: when one happens anyway, it is a bug (in the analysis or in the runtime),
// and it is reported rather than silently absorbed.
//
//  - BoundedChannel<T>: a FIFO of values (the dataflow's data), a ring of fixed capacity.
//  - TokenCounter: the same bound on a count of tokens alone, for schedules that only need rates.
//  - StaticSchedule: one iteration of a scenario's static schedule over TokenCounters.
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "semo/runtime/tables.hpp"

namespace semo::runtime {

// T must be default-constructible and copy-assignable: the ring holds `capacity` values from the
// start, so pushing and popping only copy.
template <class T>
class BoundedChannel {
 public:
  explicit BoundedChannel(std::size_t capacity) : ring_(capacity) {}

  bool tryPush(const T& value) {
    if (full()) return false;
    ring_[wrap(head_ + size_)] = value;
    ++size_;
    return true;
  }

  bool tryPop(T& value) {
    if (empty()) return false;
    value = ring_[head_];
    head_ = wrap(head_ + 1);
    --size_;
    return true;
  }

  // A push the capacity proof says always has room. Debug builds stop at the assert; release builds
  // drop the value and record the overflow, for the caller (the simulator's buffer_bounds check)
  // to report.
  void push(const T& value) {
    assert(!full() && "BoundedChannel overflow: the proven capacity was exceeded");
    if (!tryPush(value)) overflowed_ = true;
  }

  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] std::size_t capacity() const { return ring_.size(); }
  [[nodiscard]] bool full() const { return size_ == ring_.size(); }
  [[nodiscard]] bool empty() const { return size_ == 0; }
  // Whether a push ever found the channel full (release builds only; debug builds assert).
  [[nodiscard]] bool overflowed() const { return overflowed_; }

 private:
  // i < 2 * capacity here, so one subtraction wraps it (and a capacity of 0 never divides).
  [[nodiscard]] std::size_t wrap(std::size_t i) const { return i >= ring_.size() ? i - ring_.size() : i; }

  std::vector<T> ring_;
  std::size_t head_ = 0;  // the oldest value
  std::size_t size_ = 0;
  bool overflowed_ = false;
};

// A channel's tokens without their values.
class TokenCounter {
 public:
  explicit TokenCounter(std::int64_t capacity = 0, std::int64_t tokens = 0) : capacity_(capacity), tokens_(tokens) {}

  [[nodiscard]] bool canConsume(std::int64_t n) const { return tokens_ >= n; }
  [[nodiscard]] bool canProduce(std::int64_t n) const { return tokens_ + n <= capacity_; }
  bool tryConsume(std::int64_t n) {
    if (!canConsume(n)) return false;
    tokens_ -= n;
    return true;
  }
  bool tryProduce(std::int64_t n) {
    if (!canProduce(n)) return false;
    tokens_ += n;
    return true;
  }

  [[nodiscard]] std::int64_t tokens() const { return tokens_; }
  [[nodiscard]] std::int64_t capacity() const { return capacity_; }
  [[nodiscard]] std::int64_t space() const { return capacity_ - tokens_; }
  [[nodiscard]] bool full() const { return tokens_ >= capacity_; }
  [[nodiscard]] bool empty() const { return tokens_ <= 0; }

 private:
  std::int64_t capacity_;
  std::int64_t tokens_;
};

// One iteration of an SDF scenario's static schedule (ScenarioTable::schedule): the firings in
// order, each task fired `repetitions` times in a row. A firing needs `consumption` tokens on each
// input channel and, once they are taken, room for `production` tokens on each output; it takes
// and adds them, then runs the task. A schedule the analysis proved never lacks either, and after
// one iteration (the repetition vector) every channel is back at its initial tokens.
class StaticSchedule {
 public:
  struct Firing {
    Id task = 0;
    std::int64_t repetitions = 1;
  };
  struct Channel {
    Id from = 0, to = 0;  // tasks
    std::int64_t production = 1, consumption = 1, initialTokens = 0, capacity = 0;
  };
  // Why a firing could not happen.
  enum class Stall : std::uint8_t {
    None,
    Starved,   // an input channel held fewer tokens than the firing consumes
    Overflow,  // an output channel had no room for what the firing produces
  };

  StaticSchedule(std::vector<Firing> schedule, std::vector<Channel> channels);
  // The schedule of a projected scenario (dataflow_tables.hpp), over its channels with the robot's
  // proven capacities; channel c here is ScenarioTable::channels[c].
  static StaticSchedule forScenario(const ScenarioTable& scenario);

  // Runs one iteration, calling fire(task) after each firing's tokens have moved. Stops at the first
  // firing that would block or overflow and returns false: stall(), stalledTask() and
  // stalledChannel() say where (that firing has moved no token; the ones before it have).
  template <class Fire>
  bool runIteration(Fire&& fire) {
    for (const Firing& firing : schedule_) {
      for (std::int64_t k = 0; k < firing.repetitions; ++k) {
        if (!fireOnce(firing.task)) return false;
        fire(firing.task);
      }
    }
    ++iterations_;
    return true;
  }

  // Every channel back at its initial tokens, and the stall cleared (maxTokens() is kept).
  void reset();

  [[nodiscard]] Stall stall() const { return stall_; }
  [[nodiscard]] Id stalledTask() const { return stalledTask_; }
  [[nodiscard]] Id stalledChannel() const { return stalledChannel_; }
  [[nodiscard]] std::uint64_t iterations() const { return iterations_; }
  [[nodiscard]] std::size_t channelCount() const { return channels_.size(); }
  [[nodiscard]] const Channel& channel(Id c) const { return channels_[c]; }
  [[nodiscard]] const TokenCounter& tokens(Id c) const { return tokens_[c]; }
  // The most tokens channel c has held since the schedule was built (its initial tokens at least).
  [[nodiscard]] std::int64_t maxTokens(Id c) const { return maxTokens_[c]; }
  // Whether every channel holds its initial tokens (true after each complete iteration).
  [[nodiscard]] bool atInitialTokens() const;

 private:
  // Checks, then moves the tokens of one firing of `task`; on a stall records it and moves nothing.
  bool fireOnce(Id task);

  std::vector<Firing> schedule_;
  std::vector<Channel> channels_;
  std::vector<TokenCounter> tokens_;
  std::vector<std::int64_t> maxTokens_;
  // Per task, the channels it touches (as consumer, producer or both): ports_[portStart_[t] ..
  // portStart_[t + 1]). Built once so a firing looks at its own channels only.
  std::vector<std::uint32_t> portStart_;
  std::vector<Id> ports_;
  Stall stall_ = Stall::None;
  Id stalledTask_ = kNone, stalledChannel_ = kNone;
  std::uint64_t iterations_ = 0;
};

}  // namespace semo::runtime
