// The state store's parallel block insertion against the plain one: on any number of threads it
// must number, link and find the states exactly as one thread inserting them in order does.
#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <random>

#include "../../checker/src/block_insertion.hpp"
#include "../../checker/src/state_store.hpp"
#include "../../checker/src/successors.hpp"
#include "../../checker/src/worker_pool.hpp"

namespace semo::checker::detail {
namespace {

constexpr std::size_t kWords = 2;

// Runs of made-up successors for the stored states [first, end): values from a small range, so
// that many are already stored or repeat within the block.
std::vector<Expansion> makeRuns(const StateStore& store, std::size_t first, std::size_t end, std::size_t runs, std::mt19937& random) {
  std::vector<Expansion> out(runs);
  std::uniform_int_distribution<std::uint64_t> value(0, 40000), successors(0, 12);
  for (std::size_t r = 0; r < runs; ++r) {
    Expansion& e = out[r];
    e.firstState = first + (end - first) * r / runs;
    e.endState = first + (end - first) * (r + 1) / runs;
    for (std::size_t s = e.firstState; s < e.endState; ++s) {
      e.begin.push_back(static_cast<std::uint32_t>(e.via.size()));
      e.enabled.push_back(1);
      for (std::uint64_t n = s == 0 ? 12 : successors(random); n > 0; --n) {  // some without any
        const std::uint64_t v = value(random);
        const std::uint64_t state[kWords] = {v, v % 7};
        e.packed.insert(e.packed.end(), state, state + kWords);
        e.hash.push_back(store.hashOf(state));
        e.via.push_back(static_cast<std::uint32_t>(n << 8 | s % 3));
      }
    }
    e.begin.push_back(static_cast<std::uint32_t>(e.via.size()));
  }
  return out;
}

void expectSameStore(const StateStore& a, const StateStore& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.state(i)[0], b.state(i)[0]) << "state " << i;
    ASSERT_EQ(a.state(i)[1], b.state(i)[1]) << "state " << i;
    ASSERT_EQ(a.parent(i), b.parent(i)) << "state " << i;
    ASSERT_EQ(a.via(i), b.via(i)) << "state " << i;
  }
}

TEST(BlockInsertion, NumbersAndLinksStatesAsOneThreadInsertingInOrder) {
  for (unsigned threads : {1u, 2u, 3u, 4u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    std::mt19937 random(7);
    StateStore serial(kWords), parallel(kWords);
    WorkerPool pool(threads);
    BlockInserter inserter;
    const std::uint64_t root[kWords] = {40001, 0};
    serial.insert(root, kNoParent, 0);
    parallel.insert(root, kNoParent, 0);
    // Blocks of 1 to 3000 states, in 1 to 16 runs: the table grows between and within them.
    for (std::size_t first = 0, block = 1; first < serial.size() && first < 20000; first += block, block = std::min<std::size_t>(3000, block * 3)) {
      const std::size_t end = std::min(serial.size(), first + block);
      std::vector<Expansion> runs = makeRuns(serial, first, end, std::min<std::size_t>(16, end - first), random);
      const std::size_t sizeBefore = parallel.size();
      std::vector<std::size_t> checked;
      std::mutex checkedMutex;
      inserter.insert(parallel, runs, pool, [&](unsigned, std::size_t from, std::size_t to) {
        std::lock_guard<std::mutex> lock(checkedMutex);
        for (std::size_t i = from; i < to; ++i) checked.push_back(i);
      });
      for (const Expansion& e : runs) {
        for (std::size_t s = e.firstState; s < e.endState; ++s) {
          for (std::uint32_t k = e.begin[s - e.firstState]; k < e.begin[s - e.firstState + 1]; ++k) {
            serial.insert(&e.packed[k * kWords], e.hash[k], static_cast<std::uint32_t>(s), e.via[k]);
          }
          ASSERT_EQ(inserter.sizeAfter(s), serial.size()) << "after state " << s;
        }
      }
      expectSameStore(serial, parallel);
      // Every new state is offered to the check once.
      std::sort(checked.begin(), checked.end());
      ASSERT_EQ(checked.size(), parallel.size() - sizeBefore);
      for (std::size_t k = 0; k < checked.size(); ++k) ASSERT_EQ(checked[k], sizeBefore + k);
    }
    EXPECT_GT(serial.size(), 20000u);
  }
}

TEST(BlockInsertion, TruncationLeavesTheStoreAsBeforeTheDroppedStates) {
  for (unsigned threads : {1u, 3u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    std::mt19937 random(11);
    StateStore serial(kWords), parallel(kWords);
    WorkerPool pool(threads);
    BlockInserter inserter;
    const std::uint64_t root[kWords] = {40001, 0};
    serial.insert(root, kNoParent, 0);
    parallel.insert(root, kNoParent, 0);
    std::size_t first = 0;
    for (std::size_t block : {1, 8, 64, 300}) {
      const std::size_t end = std::min(parallel.size(), first + block), middle = first + (end - first) / 2;
      std::vector<Expansion> runs = makeRuns(parallel, first, end, std::min<std::size_t>(8, end - first), random);
      inserter.insert(parallel, runs, pool, nullptr);
      // The serial store takes the same states, but for the last block only those of its first
      // half of sources.
      for (const Expansion& e : runs) {
        for (std::size_t s = e.firstState; s < e.endState; ++s) {
          if (block == 300 && s >= middle) continue;
          for (std::uint32_t k = e.begin[s - e.firstState]; k < e.begin[s - e.firstState + 1]; ++k) {
            serial.insert(&e.packed[k * kWords], e.hash[k], static_cast<std::uint32_t>(s), e.via[k]);
          }
        }
      }
      if (block == 300) {
        ASSERT_EQ(end - first, 300u);
        inserter.truncate(parallel, inserter.sizeAfter(middle - 1));
      }
      first = end;
    }
    expectSameStore(serial, parallel);
    // The dropped states are gone from the table, the kept ones found, and inserting goes on from
    // the truncated end.
    std::uniform_int_distribution<std::uint64_t> value(0, 40000);
    for (int n = 0; n < 20000; ++n) {
      const std::uint64_t v = value(random);
      const std::uint64_t state[kWords] = {v, v % 7};
      ASSERT_EQ(parallel.contains(state), serial.contains(state)) << v;
      auto [index, added] = parallel.insert(state, 0, 0);
      auto [serialIndex, serialAdded] = serial.insert(state, 0, 0);
      ASSERT_EQ(index, serialIndex);
      ASSERT_EQ(added, serialAdded);
    }
  }
}

}  // namespace
}  // namespace semo::checker::detail
