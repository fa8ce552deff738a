// The safety search on a model large enough for its parallel parts to matter: blocks of states
// that split BFS levels, several expansion runs per block, the store's partitions shared out among
// threads. Whatever the number of threads, and wherever the search stops within a block, the
// results must be those of one thread, trace for trace.
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <string>
#include <functional>

#include "ir_support.hpp"
#include "semo/checker/explicit_search.hpp"

namespace semo::checker {
namespace {

// 16 switches, each flipped by a rule of its own: 2^16 states; BFS level k holds the states with k
// switches on, C(16, k) of them, up to 12,870 (k = 8): more than one block of the search (8,192).
std::string switches(const std::string& more, bool guarded = false) {
  std::string text = "semo-ir 1;\nvar on[16] : bool;\nvar stuck : bool;\nvar r : 0..0;\n";
  for (int i = 0; i < 16; ++i) {
    const std::string s = "on[" + std::to_string(i) + "]";
    text += "rule flip" + std::to_string(i) + " : " + (guarded ? "!stuck" : "true") + " -> " + s + "' = !" + s + ";\n";
  }
  std::string sum = "(on[0]";
  for (int i = 1; i < 16; ++i) sum += " + on[" + std::to_string(i) + "]";
  sum += ")";
  std::string rest = more;  // SUM: how many are on
  for (std::size_t at = rest.find("SUM"); at != std::string::npos; at = rest.find("SUM", at + sum.size())) rest.replace(at, 3, sum);
  return text + rest;
}

// The search as one thread expanding one state at a time does it, by hand for the switches: BFS
// over the masks of the switches on, successors in rule order. `found` sees each new mask; the
// search stops once `stop` holds after a state's successors are stored. Returns the states stored.
std::size_t statesOfOneByOneSearch(const std::function<void(std::uint32_t)>& found, const std::function<bool(std::size_t)>& stop) {
  std::vector<std::uint32_t> order{0};
  std::vector<bool> seen(1u << 16, false);
  seen[0] = true;
  for (std::size_t i = 0; i < order.size(); ++i) {
    for (int s = 0; s < 16; ++s) {
      const std::uint32_t next = order[i] ^ (1u << s);
      if (seen[next]) continue;
      seen[next] = true;
      order.push_back(next);
      found(next);
    }
    if (stop(order.size())) break;
  }
  return order.size();
}

void expectSameTrace(const Trace& a, const Trace& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.property, b.property);
  EXPECT_EQ(a.initial, b.initial);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].rule, b.steps[k].rule) << "step " << k;
    EXPECT_EQ(a.steps[k].branch, b.steps[k].branch) << "step " << k;
    ASSERT_EQ(a.steps[k].changes.size(), b.steps[k].changes.size()) << "step " << k;
    for (std::size_t c = 0; c < a.steps[k].changes.size(); ++c) {
      EXPECT_EQ(a.steps[k].changes[c].var, b.steps[k].changes[c].var);
      EXPECT_EQ(a.steps[k].changes[c].after, b.steps[k].changes[c].after);
    }
  }
}

// The search on 1, 2 and 3 threads; checks that they agree and returns the one-thread result.
SearchResult checkOnEveryThreadCount(const std::string& text, SearchLimits limits) {
  ir::Model m = test::parseIr(text);
  limits.threads = 1;
  SearchResult one = checkSafety(m, limits);
  for (unsigned threads : {2u, 3u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    limits.threads = threads;
    SearchResult r = checkSafety(m, limits);
    EXPECT_EQ(r.states, one.states);
    EXPECT_EQ(r.transitions, one.transitions);
    EXPECT_EQ(r.depth, one.depth);
    EXPECT_EQ(r.complete, one.complete);
    EXPECT_EQ(r.limitReached, one.limitReached);
    EXPECT_EQ(r.depthBounded, one.depthBounded);
    EXPECT_EQ(r.peakBytes, one.peakBytes) << "the store grows at the same points";
    EXPECT_EQ(r.rangeError.has_value(), one.rangeError.has_value());
    if (r.rangeError && one.rangeError) expectSameTrace(*r.rangeError, *one.rangeError);
    EXPECT_EQ(r.properties.size(), one.properties.size());
    for (std::size_t p = 0; p < std::min(r.properties.size(), one.properties.size()); ++p) {
      EXPECT_EQ(r.properties[p].verdict, one.properties[p].verdict) << r.properties[p].name;
      EXPECT_EQ(r.properties[p].counterexample.has_value(), one.properties[p].counterexample.has_value());
      if (r.properties[p].counterexample && one.properties[p].counterexample) {
        expectSameTrace(*r.properties[p].counterexample, *one.properties[p].counterexample);
      }
    }
  }
  return one;
}

TEST(SearchThreads, StopWhenEveryPropertyIsViolatedWithinABlock) {
  // Both are violated by states of level 9, found while level 8 (two blocks) is expanded: the
  // search stops after the state whose successor violates the second, within a block.
  SearchResult r = checkOnEveryThreadCount(switches("invariant a : SUM < 9 || !on[5] || !on[6];\n"
                                                    "invariant b : SUM < 9 || !on[10] || on[11];\n"),
                                           SearchLimits{});
  EXPECT_EQ(r.limitReached, "every property is violated");
  ASSERT_EQ(r.properties.size(), 2u);
  for (const PropertyResult& p : r.properties) {
    ASSERT_TRUE(p.counterexample.has_value()) << p.name;
    EXPECT_EQ(p.counterexample->steps.size(), 9u) << "shortest: " << p.name;
  }
  // Levels 0..8 hold 39,203 states: it stopped within level 9's discovery, exactly where a search
  // one state at a time stops.
  bool a = false, b = false;
  const std::size_t expected = statesOfOneByOneSearch(
      [&](std::uint32_t on) {
        const bool nine = std::popcount(on) >= 9;
        a = a || (nine && (on >> 5 & 1) && (on >> 6 & 1));
        b = b || (nine && (on >> 10 & 1) && !(on >> 11 & 1));
      },
      [&](std::size_t) { return a && b; });
  EXPECT_EQ(r.states, expected);
  EXPECT_GT(r.states, 39203u);
  EXPECT_LT(r.states, 39203u + 11440u);
}

TEST(SearchThreads, MaxStatesStopsRightAfterTheStateThatReachesIt) {
  SearchLimits limits;
  limits.maxStates = 30001;  // reached while level 7 (11,440 states, two blocks) is expanded
  SearchResult r = checkOnEveryThreadCount(switches("invariant fine : SUM <= 16;\n"), limits);
  EXPECT_EQ(r.limitReached, "--max-states 30001 reached");
  EXPECT_GE(r.states, 30001u);
  EXPECT_EQ(r.states, statesOfOneByOneSearch([](std::uint32_t) {}, [](std::size_t stored) { return stored >= 30001; }));
  EXPECT_EQ(r.properties[0].verdict, Verdict::Unknown);
}

TEST(SearchThreads, RangeErrorWithinABlock) {
  SearchResult r = checkOnEveryThreadCount(switches("rule overflow : SUM == 8 && on[2] && on[9] -> r' = r + 1;\n"), SearchLimits{});
  ASSERT_TRUE(r.rangeError.has_value());
  EXPECT_EQ(r.rangeError->steps.size(), 9u);
  EXPECT_FALSE(r.complete);
  EXPECT_LT(r.states, 65536u);
}

TEST(SearchThreads, DeadlockAndWholeSpace) {
  // Switching stops for good in some states of level 8: deadlocks, 9 steps from the start.
  SearchResult r = checkOnEveryThreadCount(switches("rule stick : !stuck && SUM == 8 && on[3] && on[12] -> stuck' = true;\n"
                                                    "valid_end : !stuck;\n"
                                                    "invariant fine : SUM <= 16;\n",
                                                    true),
                                           SearchLimits{});
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.states, 65536u + 3003u) << "and one stuck copy of each level-8 state with on[3] and on[12]: C(14, 6)";
  const PropertyResult& deadlock = r.properties.back();
  EXPECT_EQ(deadlock.name, "deadlock_freedom");
  ASSERT_TRUE(deadlock.counterexample.has_value());
  EXPECT_EQ(deadlock.counterexample->steps.size(), 9u);
  EXPECT_EQ(r.properties.front().verdict, Verdict::Proven);
}

TEST(SearchThreads, BoundedSearch) {
  SearchLimits limits;
  limits.maxDepth = 9;
  SearchResult r = checkOnEveryThreadCount(switches("invariant a : SUM < 9 || !on[5] || !on[6];\n"
                                                    "invariant never : SUM < 12;\n"),
                                           limits);
  EXPECT_TRUE(r.depthBounded);
  EXPECT_EQ(r.states, 39203u + 11440u) << "levels 0..9";
  EXPECT_EQ(r.properties[0].verdict, Verdict::Violated) << "at the bound: checked when stored";
  EXPECT_EQ(r.properties[1].verdict, Verdict::Unknown);
}

// The default thread count: SEMO_THREADS when it is a count, else the processors this process may
// run on; anything else in SEMO_THREADS is an error the CLI reports (e2e.check_threads_setting).
TEST(SearchThreads, TheDefaultComesFromSemoThreadsOrTheProcessors) {
  const char* saved = std::getenv("SEMO_THREADS");
  const std::string keep = saved != nullptr ? saved : "";
  unsetenv("SEMO_THREADS");
  const unsigned processors = defaultThreads();
  EXPECT_GE(processors, 1u);
  EXPECT_EQ(threadsSettingError(), "");
  setenv("SEMO_THREADS", "3", 1);
  EXPECT_EQ(defaultThreads(), 3u);
  EXPECT_EQ(threadsSettingError(), "");
  for (const char* bad : {"0", "257", "two", "3 ", "-1"}) {
    setenv("SEMO_THREADS", bad, 1);
    EXPECT_EQ(defaultThreads(), processors) << bad;
    EXPECT_NE(threadsSettingError().find("is not a number of threads"), std::string::npos) << bad;
  }
  setenv("SEMO_THREADS", "", 1);
  EXPECT_EQ(threadsSettingError(), "") << "empty is unset";
  if (saved != nullptr) setenv("SEMO_THREADS", keep.c_str(), 1);
  else unsetenv("SEMO_THREADS");
}

}  // namespace
}  // namespace semo::checker
