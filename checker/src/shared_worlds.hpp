#pragma once
// The settling worlds of an exact cone searched by two processes (shared_worlds.cpp). Each world's
// fair states are a fixpoint of their own on the same reachable set, and the dear ones take minutes
// (checker/README.md, "The exact cone"): a forked helper takes worlds beside the caller, each process
// taking the next world nobody has, so that the two cores share them however unevenly they cost.
#include <cstdint>
#include <functional>
#include <optional>

namespace semo::checker::detail {

// How the worlds were shared: the lowest world with a fair violation (the one the sequential
// search would have stopped at, whoever found it, so that the verdict and its lasso do not depend
// on timing), and how many worlds the helper process searched.
struct SharedWorlds {
  std::optional<std::uint64_t> violatedWorld;
  std::uint64_t byHelper = 0;
  bool helperStarted = false;
};

// Searches worlds 0 .. count-1 with `searchWorld` (true: the world has fair states). With
// `helper`, a forked child searches beside this process; `inHelper` runs first in the child (to
// restart its clock and silence its progress: only this process reports). A world the helper took
// and did not finish (it gave up, ran out of memory or was killed) is searched here afterwards, so
// the answer is the same as one process's, only sooner; an exception from `searchWorld` here (a
// budget spent) ends the helper and is passed on. Without `helper`, or when no process can be
// forked, every world is searched here in order.
SharedWorlds searchWorldsShared(std::uint64_t count, const std::function<bool(std::uint64_t)>& searchWorld, bool helper,
                                const std::function<void()>& inHelper);

}  // namespace semo::checker::detail
