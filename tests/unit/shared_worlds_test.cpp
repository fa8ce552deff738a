// The settling worlds shared between this process and a forked helper (shared_worlds.hpp): the
// answer is the lowest world with fair states, whoever searched it and whatever the helper did.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "../../checker/src/shared_worlds.hpp"

namespace semo::checker {
namespace {

using detail::searchWorldsShared;

// A world "costs" a few milliseconds, world 3 and 5 most, so that the two processes interleave.
bool slowly(std::uint64_t w, const std::vector<std::uint64_t>& violated) {
  std::this_thread::sleep_for(std::chrono::milliseconds(w == 3 || w == 5 ? 40 : 5));
  for (std::uint64_t v : violated) {
    if (v == w) return true;
  }
  return false;
}

TEST(SharedWorlds, TheLowestWorldWithFairStatesWhoeverFoundIt) {
  for (const std::vector<std::uint64_t>& violated : std::vector<std::vector<std::uint64_t>>{{}, {0}, {3}, {6, 2}, {15}, {5, 9, 12}}) {
    for (const bool helper : {false, true}) {
      const auto shared = searchWorldsShared(16, [&](std::uint64_t w) { return slowly(w, violated); }, helper, [] {});
      std::optional<std::uint64_t> lowest;
      for (std::uint64_t v : violated) lowest = lowest ? std::min(*lowest, v) : v;
      EXPECT_EQ(shared.violatedWorld, lowest) << "helper " << helper << ", " << violated.size() << " violated";
      EXPECT_EQ(shared.helperStarted, helper);
      if (!helper) {
        EXPECT_EQ(shared.byHelper, 0u);
      }
    }
  }
}

TEST(SharedWorlds, TheHelperTakesWorldsBesideTheCaller) {
  const pid_t caller = ::getpid();
  const auto shared = searchWorldsShared(
      16, [](std::uint64_t w) { return slowly(w, {}); }, true, [] {});
  EXPECT_FALSE(shared.violatedWorld);
  EXPECT_GT(shared.byHelper, 0u);
  EXPECT_LT(shared.byHelper, 16u);
  EXPECT_EQ(::getpid(), caller);
}

TEST(SharedWorlds, WhatTheHelperLeftUnfinishedIsSearchedHere) {
  // The helper gives up on every world it takes (as when its budget runs out), or dies outright:
  // the caller searches those worlds itself and still finds the lowest violation.
  const pid_t caller = ::getpid();
  for (const bool die : {false, true}) {
    std::vector<std::uint64_t> searchedHere;
    const auto shared = searchWorldsShared(
        16,
        [&](std::uint64_t w) {
          if (::getpid() != caller) {
            if (die) ::raise(SIGKILL);
            throw std::runtime_error("out of time");
          }
          searchedHere.push_back(w);
          return slowly(w, {7, 11});
        },
        true, [] {});
    EXPECT_EQ(shared.violatedWorld, std::optional<std::uint64_t>(7));
    EXPECT_EQ(shared.byHelper, 0u);
    for (std::uint64_t w = 0; w <= 7; ++w) {
      EXPECT_NE(std::find(searchedHere.begin(), searchedHere.end(), w), searchedHere.end()) << "world " << w << " was never searched";
    }
  }
}

TEST(SharedWorlds, AnExceptionHereEndsTheHelperAndIsPassedOn) {
  const pid_t caller = ::getpid();
  EXPECT_THROW(searchWorldsShared(
                   16,
                   [&](std::uint64_t w) {
                     if (::getpid() == caller && w > 2) throw std::runtime_error("out of time");
                     return slowly(w, {});
                   },
                   true, [] {}),
               std::runtime_error);
}

}  // namespace
}  // namespace semo::checker
