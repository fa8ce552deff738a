#include "shared_worlds.hpp"

#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <new>

namespace semo::checker::detail {
namespace {

// Every settling world up to SymbolicLimits' six sensed points.
constexpr std::uint64_t kMaxShared = 64;
constexpr std::uint64_t kNone = ~std::uint64_t{0};

enum : std::uint8_t { kUnfinished = 0, kNoFairStates = 1, kFairStates = 2 };

// In memory both processes map (anonymous, shared): lock-free atomics work across processes.
struct Board {
  std::atomic<std::uint64_t> next{0};
  std::atomic<std::uint64_t> lowestViolated{kNone};
  std::atomic<std::uint64_t> helperOn{kNone};  // the world the helper is searching
  std::atomic<std::uint64_t> byHelper{0};
  std::atomic<std::uint8_t> state[kMaxShared];
};
static_assert(std::atomic<std::uint64_t>::is_always_lock_free && std::atomic<std::uint8_t>::is_always_lock_free);

void lowerTo(std::atomic<std::uint64_t>& lowest, std::uint64_t w) {
  std::uint64_t now = lowest.load();
  while (w < now && !lowest.compare_exchange_weak(now, w)) {
  }
}

// Takes the next world nobody has until there is none, or none that could be the lowest violated.
void work(Board& board, std::uint64_t count, const std::function<bool(std::uint64_t)>& searchWorld, bool helper) {
  for (;;) {
    const std::uint64_t w = board.next.fetch_add(1);
    if (w >= count || w > board.lowestViolated.load()) return;
    if (helper) board.helperOn.store(w);
    const bool violated = searchWorld(w);
    board.state[w].store(violated ? kFairStates : kNoFairStates);
    if (violated) lowerTo(board.lowestViolated, w);
    if (helper) board.byHelper.fetch_add(1);
  }
}

void endHelper(pid_t pid, bool kill) {
  if (kill) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
}

}  // namespace

SharedWorlds searchWorldsShared(std::uint64_t count, const std::function<bool(std::uint64_t)>& searchWorld, bool helper,
                                const std::function<void()>& inHelper) {
  SharedWorlds out;
  void* memory = helper && count > 1 && count <= kMaxShared
                     ? ::mmap(nullptr, sizeof(Board), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0)
                     : MAP_FAILED;
  if (memory == MAP_FAILED) {
    for (std::uint64_t w = 0; w < count; ++w) {
      if (searchWorld(w)) {
        out.violatedWorld = w;
        return out;
      }
    }
    return out;
  }
  Board& board = *new (memory) Board;
  for (auto& s : board.state) s.store(kUnfinished);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // The helper: a copy of this process with only this thread, which holds the decision-diagram
    // package (the caller's lock), so the copy of it is whole. It ends with _exit, leaving the
    // parent's buffers and exit handlers alone; whatever stops it leaves its world unfinished.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(4);
    try {
      inHelper();
      work(board, count, searchWorld, true);
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  out.helperStarted = pid > 0;
  try {
    work(board, count, searchWorld, false);
  } catch (...) {
    if (pid > 0) endHelper(pid, true);
    ::munmap(memory, sizeof(Board));
    throw;
  }
  if (pid > 0) {
    // A helper still on a world past the lowest violation found would search for nothing.
    const std::uint64_t on = board.helperOn.load();
    const std::uint64_t lowest = board.lowestViolated.load();
    endHelper(pid, lowest != kNone && on != kNone && on > lowest && board.state[on].load() == kUnfinished);
  }
  out.byHelper = board.byHelper.load();
  // What the helper left unfinished, searched here in order, up to the lowest violation.
  std::uint64_t lowest = board.lowestViolated.load();
  for (std::uint64_t w = 0; w < count && w < lowest; ++w) {
    if (board.state[w].load() != kUnfinished) continue;
    try {
      if (searchWorld(w)) lowest = w;
    } catch (...) {
      ::munmap(memory, sizeof(Board));
      throw;
    }
  }
  ::munmap(memory, sizeof(Board));
  if (lowest != kNone) out.violatedWorld = lowest;
  return out;
}

}  // namespace semo::checker::detail
