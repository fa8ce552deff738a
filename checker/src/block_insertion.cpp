#include "block_insertion.hpp"

#include <array>
#include <atomic>
#include <bit>
#include <stdexcept>

namespace semo::checker::detail {

void BlockInserter::insert(StateStore& store, const std::vector<Expansion>& runs, WorkerPool& pool, const NewStates& onNewStates) {
  const unsigned threads = pool.size();
  if (owners_.size() != threads) {
    owners_.assign(threads, Owner{});
    ownerOf_.resize(StateStore::kPartitions);
    for (std::size_t p = 0; p < ownerOf_.size(); ++p) ownerOf_[p] = static_cast<unsigned>(p % threads);
  }
  firstSource_ = runs.front().firstState;
  sizeAfter_.assign(runs.back().endState - firstSource_, 0);
  firstOfRun_.assign(runs.size() + 1, 0);
  for (std::size_t r = 0; r < runs.size(); ++r) firstOfRun_[r + 1] = firstOfRun_[r] + runs[r].via.size();
  // Claims are numbered from size() on, and every number + 1 must fit in a slot's 32 bits.
  if (store.size() + firstOfRun_.back() >= 0xffffffffu) throw std::length_error("the state store holds at most 2^32 - 2 states");

  pool.run([&](unsigned thread) { claim(thread, store, runs); });

  newBeforeRun_.assign(runs.size() + 1, 0);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    std::size_t added = 0;
    for (const Owner& o : owners_) added += o.claimedBefore[r + 1] - o.claimedBefore[r];
    newBeforeRun_[r + 1] = newBeforeRun_[r] + added;
  }
  store.append(newBeforeRun_.back());

  // Runs have about as many successors, not as many new states: taken one by one, as they come.
  std::atomic<std::size_t> nextRun{0};
  pool.run([&](unsigned thread) {
    for (std::size_t r = nextRun.fetch_add(1, std::memory_order_relaxed); r < runs.size(); r = nextRun.fetch_add(1, std::memory_order_relaxed)) {
      number(thread, r, store, runs[r], onNewStates);
    }
  });
}

void BlockInserter::claim(unsigned thread, StateStore& store, const std::vector<Expansion>& runs) {
  Owner& own = owners_[thread];
  const std::size_t words = store.words(), successors = firstOfRun_.back();
  if (own.candidates.size() < successors) own.candidates.resize(successors);
  // Every successor is written, and kept when it is ours: no branch to mispredict on half of them.
  std::size_t mine = 0, k = 0;
  std::array<std::size_t, StateStore::kPartitions> wanted{};
  for (const Expansion& e : runs) {
    for (std::size_t n = 0; n < e.hash.size(); ++n, ++k) {
      const std::size_t p = StateStore::partitionOf(e.hash[n]);
      const bool ours = ownerOf_[p] == thread;
      own.candidates[mine] = {e.hash[n], &e.packed[n * words], static_cast<std::uint32_t>(k)};
      mine += ours ? 1 : 0;
      wanted[p] += ours ? 1 : 0;
    }
  }
  // Room for all, new or not: no partition may grow while claims are pending in it (growing moves
  // the entries, so the claims' slots would change, and rehashes from stored data).
  for (std::size_t p = 0; p < wanted.size(); ++p) {
    if (wanted[p] != 0) store.reserve(p, wanted[p]);
  }

  own.isNew.assign((successors + 63) / 64, 0);
  own.claimed.clear();
  own.claimedBefore.assign(runs.size() + 1, 0);
  const std::size_t base = store.size();
  auto pendingState = [&](std::uint32_t index) { return own.candidates[index - base].data; };
  constexpr std::size_t kAhead = 8;  // table slots loaded ahead, so that the cache misses overlap
  for (std::size_t c = 0; c < std::min(mine, kAhead); ++c) store.prefetch(own.candidates[c].hash);
  std::size_t run = 0;
  for (std::size_t c = 0; c < mine; ++c) {
    if (c + kAhead < mine) store.prefetch(own.candidates[c + kAhead].hash);
    const Candidate& candidate = own.candidates[c];
    const std::size_t partition = StateStore::partitionOf(candidate.hash);
    StateStore::Claim result = store.claim(partition, candidate.data, candidate.hash, static_cast<std::uint32_t>(base + c), pendingState);
    if (!result.added) continue;
    own.isNew[candidate.number / 64] |= std::uint64_t{1} << (candidate.number % 64);
    own.claimed.push_back({static_cast<std::uint32_t>(partition), result.slot, 0});
    for (; candidate.number >= firstOfRun_[run + 1]; ++run) own.claimedBefore[run + 2] = own.claimedBefore[run + 1];
    ++own.claimedBefore[run + 1];
  }
  for (; run + 1 < runs.size(); ++run) own.claimedBefore[run + 2] = own.claimedBefore[run + 1];
}

void BlockInserter::number(unsigned thread, std::size_t run, StateStore& store, const Expansion& e, const NewStates& onNewStates) {
  const std::size_t words = store.words(), first = store.size() - newBeforeRun_.back() + newBeforeRun_[run];
  std::size_t next = first;
  std::vector<std::size_t>& cursor = owners_[thread].cursor;
  cursor.resize(owners_.size());
  for (std::size_t o = 0; o < owners_.size(); ++o) cursor[o] = owners_[o].claimedBefore[run];
  std::size_t source = e.firstState;  // of the successors from here on
  auto passSourcesBefore = [&](std::size_t successor) {
    for (; source < e.endState && e.begin[source - e.firstState + 1] <= successor; ++source) sizeAfter_[source - firstSource_] = next;
  };
  const std::size_t from = firstOfRun_[run], to = firstOfRun_[run + 1];
  for (std::size_t word = from / 64; word * 64 < to; ++word) {
    std::uint64_t bits = 0;
    for (const Owner& o : owners_) bits |= o.isNew[word];
    // Only this run's successors: the runs next to it may share the word.
    if (word == from / 64) bits &= ~std::uint64_t{0} << (from % 64);
    if ((word + 1) * 64 > to) bits &= ~std::uint64_t{0} >> ((word + 1) * 64 - to);
    for (; bits != 0; bits &= bits - 1) {
      const std::size_t k = word * 64 + static_cast<std::size_t>(std::countr_zero(bits)), local = k - from;
      passSourcesBefore(local);
      std::size_t owner = 0;
      while ((owners_[owner].isNew[word] >> (k % 64) & 1) == 0) ++owner;
      Claimed& c = owners_[owner].claimed[cursor[owner]++];
      c.index = static_cast<std::uint32_t>(next);
      std::copy_n(&e.packed[local * words], words, store.stateToFill(next));
      store.setOrigin(next, static_cast<std::uint32_t>(source), e.via[local]);
      store.settle(c.partition, c.slot, c.index);
      ++next;
    }
  }
  passSourcesBefore(to - from);
  if (onNewStates && next > first) onNewStates(thread, first, next);
}

void BlockInserter::truncate(StateStore& store, std::size_t n) {
  // Within a partition the claims were made in the order of their numbers: those dropped were made
  // after every entry that stays, so no probe for one of those runs through their slots, and
  // emptying them leaves the table as it was before them. (No partition grows during a block.)
  for (Owner& own : owners_) {
    for (auto c = own.claimed.rbegin(); c != own.claimed.rend(); ++c) {
      if (c->index >= n) store.release(c->partition, c->slot);
    }
  }
  store.truncate(n);
}

}  // namespace semo::checker::detail
