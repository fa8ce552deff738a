#pragma once
// Threads kept for the whole search. The safety search alternates short parallel phases (expand a
// block of states, insert its successors) with serial steps, about a thousand times a second:
// starting threads for each phase would cost more than some phases take.
#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace semo::checker::detail {

class WorkerPool {
 public:
  explicit WorkerPool(unsigned threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  [[nodiscard]] unsigned size() const { return static_cast<unsigned>(helpers_.size()) + 1; }
  // Runs task(t) for every t in [0, size()), t = 0 on the calling thread, and returns when all
  // are done. An exception thrown by a task is rethrown here (the first one, if several).
  void run(const std::function<void(unsigned)>& task);

 private:
  void serve(unsigned thread);
  void record(std::exception_ptr error);

  std::vector<std::thread> helpers_;
  const std::function<void(unsigned)>* task_ = nullptr;
  // Bumped to start a task (or to stop, with stopping_ set); helpers sleep on it.
  std::atomic<std::uint32_t> generation_{0};
  std::atomic<std::uint32_t> unfinished_{0};  // helpers still in the current task
  std::atomic<bool> stopping_{false};
  std::mutex errorMutex_;
  std::exception_ptr error_;
};

}  // namespace semo::checker::detail
