#include "worker_pool.hpp"

#include <algorithm>
#include <chrono>

namespace semo::checker::detail {

namespace {

// Tells the core that this thread is spinning (fewer memory-order stalls, and the other thread of a
// hyperthreaded core gets the execution units).
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Waits until `a` no longer holds `old`. Spins first (yielding, for a machine with more threads
// than cores): a thread put to sleep is woken on the waker's core and stays there, so that the
// two run by turns instead of together (Linux wakes a sleeper close to its waker); the phases of
// the search follow each other within microseconds.
void awaitChange(const std::atomic<std::uint32_t>& a, std::uint32_t old) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point giveUp = Clock::now() + std::chrono::milliseconds(2);
  for (unsigned spins = 0; a.load(std::memory_order_acquire) == old; ++spins) {
    if (spins % 64 == 63) {
      if (Clock::now() > giveUp) {
        a.wait(old, std::memory_order_acquire);
        return;
      }
      std::this_thread::yield();
    }
    relax();
  }
}

}  // namespace

WorkerPool::WorkerPool(unsigned threads) {
  for (unsigned t = 1; t < std::max(1u, threads); ++t) helpers_.emplace_back([this, t] { serve(t); });
}

WorkerPool::~WorkerPool() {
  stopping_.store(true, std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& h : helpers_) h.join();
}

void WorkerPool::record(std::exception_ptr error) {
  std::lock_guard<std::mutex> lock(errorMutex_);
  if (!error_) error_ = std::move(error);
}

void WorkerPool::run(const std::function<void(unsigned)>& task) {
  if (helpers_.empty()) {
    task(0);
    return;
  }
  task_ = &task;
  unfinished_.store(static_cast<std::uint32_t>(helpers_.size()), std::memory_order_relaxed);
  // The release publishes task_ (and everything the caller wrote before) to the helpers.
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  try {
    task(0);
  } catch (...) {
    record(std::current_exception());
  }
  // Every helper must be done before the caller reads what they wrote (acquire), even when its
  // own part threw.
  for (std::uint32_t left = unfinished_.load(std::memory_order_acquire); left != 0; left = unfinished_.load(std::memory_order_acquire)) {
    awaitChange(unfinished_, left);
  }
  task_ = nullptr;
  if (error_) {
    std::exception_ptr error = std::move(error_);
    error_ = nullptr;
    std::rethrow_exception(error);
  }
}

void WorkerPool::serve(unsigned thread) {
  std::uint32_t seen = 0;
  for (;;) {
    awaitChange(generation_, seen);
    seen = generation_.load(std::memory_order_acquire);
    if (stopping_.load(std::memory_order_relaxed)) return;
    try {
      (*task_)(thread);
    } catch (...) {
      record(std::current_exception());
    }
    if (unfinished_.fetch_sub(1, std::memory_order_acq_rel) == 1) unfinished_.notify_one();
  }
}

}  // namespace semo::checker::detail
