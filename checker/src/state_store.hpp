#pragma once
// The store of explored states shared by the search engines: every state once, packed, in the
// order found, with the parent and rule that first reached it (so a path back to the start is a
// walk up the parents; in breadth-first order it is a shortest one).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/symmetry.hpp"
#include "semo/checker/trace.hpp"

namespace semo::checker::detail {

constexpr std::uint32_t kNoParent = 0xffffffffu;

// Every reachable state once, packed, in BFS order; with the parent and rule that first reached it.
//
// The hash table is split by the top bits of the hash into kPartitions tables of their own, so
// that several threads can insert at once, each into the partitions it owns (block_insertion.hpp).
// The split is fixed, whatever the number of threads: the order of the insertions into one
// partition, and so every result, does not depend on it. A slot holds the upper half of the hash
// and, below it, index + 1 (0: empty): most other states are told apart without reading their data
// (a cache miss); within a partition 24 of the 32 bits differ. During a block insertion a slot may
// hold an index at or above the store's size: a claim by a successor not yet numbered (claim()).
class StateStore {
 public:
  static constexpr unsigned kPartitionBits = 8;
  static constexpr std::size_t kPartitions = std::size_t{1} << kPartitionBits;
  [[nodiscard]] static std::size_t partitionOf(std::uint64_t hash) { return hash >> (64 - kPartitionBits); }

  // `words`: 64-bit words per state (the engines may append words of their own after the model's).
  explicit StateStore(std::size_t words) : words_(words), partitions_(kPartitions) {
    chunks_.reserve(std::size_t{1} << (32 - kChunkBits));  // never reallocated: see state()
    for (Partition& p : partitions_) p.slots.assign(kInitialSlots, 0);
  }

  [[nodiscard]] std::size_t size() const { return parent_.size(); }
  // Stored states never move: another thread may read the first n states (n known to it) while
  // new ones are added.
  [[nodiscard]] const std::uint64_t* state(std::size_t i) const {
    return chunks_[i >> kChunkBits].get() + (i & ((std::size_t{1} << kChunkBits) - 1)) * words_;
  }
  [[nodiscard]] std::uint32_t parent(std::size_t i) const { return parent_[i]; }
  [[nodiscard]] std::uint32_t via(std::size_t i) const { return via_[i]; }
  [[nodiscard]] std::size_t words() const { return words_; }
  [[nodiscard]] std::uint64_t bytes() const {
    std::uint64_t slots = 0;
    for (const Partition& p : partitions_) slots += p.slots.capacity();
    // The states' data as far as states fill it (the rest of the last chunk is never touched).
    return size() * words_ * 8 + slots * 8 + parent_.capacity() * 4 + via_.capacity() * 4;
  }
  // data, parent, via, and the hash table (8-byte slots, at most half full)
  [[nodiscard]] std::uint64_t bytesPerState() const { return words_ * 8 + 4 + 4 + 16; }

  [[nodiscard]] bool contains(const std::uint64_t* s) const {
    const std::uint64_t h = hash(s);
    const Partition& p = partitions_[partitionOf(h)];
    const std::size_t mask = p.slots.size() - 1;
    for (std::size_t slot = h & mask;; slot = (slot + 1) & mask) {
      std::uint64_t entry = p.slots[slot];
      if (entry == 0) return false;
      if ((entry >> 32) == (h >> 32) && same(s, state((entry & 0xffffffffu) - 1))) return true;
    }
  }

  [[nodiscard]] std::uint64_t hashOf(const std::uint64_t* s) const { return hash(s); }
  // Starts loading the slot a state with hash h probes first: the search hashes all successors of a
  // state, prefetches, then inserts them, so that the cache misses overlap.
  void prefetch(std::uint64_t h) const {
    const Partition& p = partitions_[partitionOf(h)];
    __builtin_prefetch(&p.slots[h & (p.slots.size() - 1)]);
  }

  // Returns the state's index and whether it is new. Serial: no other thread may use the store.
  std::pair<std::uint32_t, bool> insert(const std::uint64_t* s, std::uint32_t parent, std::uint32_t via) {
    return insert(s, hash(s), parent, via);
  }
  std::pair<std::uint32_t, bool> insert(const std::uint64_t* s, std::uint64_t h, std::uint32_t parent, std::uint32_t via) {
    const std::size_t partition = partitionOf(h);
    reserve(partition, 1);
    auto index = static_cast<std::uint32_t>(size());
    Claim c = claim(partition, s, h, index, [](std::uint32_t) -> const std::uint64_t* { return nullptr; });
    if (!c.added) return {c.index, false};
    append(1);
    std::copy_n(s, words_, stateToFill(index));
    parent_[index] = parent;
    via_[index] = via;
    return {index, true};
  }

  // The pieces of a block insertion (block_insertion.hpp), safe on several threads at once as long
  // as no two reserve or claim in the same partition, no two settle the same slot, and none
  // appends.
  //
  // Makes room in a partition for `more` entries (keeping it at most half full); only while no
  // claims are pending in it, since growing moves the entries.
  void reserve(std::size_t partition, std::size_t more) {
    while ((partitions_[partition].entries + more) * 2 > partitions_[partition].slots.size()) grow(partitions_[partition]);
  }
  struct Claim {
    bool added;
    std::uint32_t index;  // the stored state's, or the claim's `pending` of the one that claimed it
    std::uint32_t slot;
  };
  // Finds state s (hash h) in its partition, or claims a slot for it under the index `pending`
  // (at least size()). A slot claimed earlier whose index i is at least size() is compared with
  // pendingState(i), the data of the state that claimed it. The partition must have room
  // (reserve()).
  template <typename PendingState>
  Claim claim(std::size_t partition, const std::uint64_t* s, std::uint64_t h, std::uint32_t pending, PendingState pendingState) {
    Partition& p = partitions_[partition];
    const std::size_t mask = p.slots.size() - 1, stored = size();
    for (std::size_t slot = h & mask;; slot = (slot + 1) & mask) {
      const std::uint64_t entry = p.slots[slot];
      if (entry == 0) {
        p.slots[slot] = (h & ~0xffffffffull) | (static_cast<std::uint64_t>(pending) + 1);
        ++p.entries;
        return {true, pending, static_cast<std::uint32_t>(slot)};
      }
      if ((entry >> 32) != (h >> 32)) continue;
      const auto index = static_cast<std::uint32_t>((entry & 0xffffffffu) - 1);
      if (same(s, index < stored ? state(index) : pendingState(index))) return {false, index, static_cast<std::uint32_t>(slot)};
    }
  }
  // Gives a claimed slot the final index of its state.
  void settle(std::size_t partition, std::uint32_t slot, std::uint32_t index) {
    std::uint64_t& entry = partitions_[partition].slots[slot];
    entry = (entry & ~0xffffffffull) | (static_cast<std::uint64_t>(index) + 1);
  }
  // Empties a claimed slot. Only right for claims made after every entry that stays in the
  // partition (the last ones of a block): an entry placed after the claim may have probed past it.
  void release(std::size_t partition, std::uint32_t slot) {
    partitions_[partition].slots[slot] = 0;
    --partitions_[partition].entries;
  }
  // Serial: adds n states (to be filled in: stateToFill, setOrigin) after the stored ones.
  void append(std::size_t n) {
    const std::size_t end = size() + n;
    // Not zeroed: each state is written whole before it is read, and a chunk's pages are then
    // taken from the system only as states fill them, so that a wide state vector with few states
    // (5,000 variables, 4 states) does not cost a whole chunk (410 MB) up front.
    while ((chunks_.size() << kChunkBits) < end) {
      chunks_.push_back(std::make_unique_for_overwrite<std::uint64_t[]>((std::size_t{1} << kChunkBits) * words_));
    }
    parent_.resize(end);
    via_.resize(end);
  }
  [[nodiscard]] std::uint64_t* stateToFill(std::size_t i) {
    return chunks_[i >> kChunkBits].get() + (i & ((std::size_t{1} << kChunkBits) - 1)) * words_;
  }
  void setOrigin(std::size_t i, std::uint32_t parent, std::uint32_t via) {
    parent_[i] = parent;
    via_[i] = via;
  }
  // Serial: forgets the states from n on, whose slots must have been released.
  void truncate(std::size_t n) {
    parent_.resize(n);
    via_.resize(n);
  }

 private:
  static constexpr std::size_t kInitialSlots = (std::size_t{1} << 16) / kPartitions;
  struct alignas(64) Partition {  // one cache line each: threads update neighbouring partitions
    std::vector<std::uint64_t> slots;
    std::size_t entries = 0;
  };

  [[nodiscard]] bool same(const std::uint64_t* a, const std::uint64_t* b) const {
    for (std::size_t i = 0; i < words_; ++i) {
      if (a[i] != b[i]) return false;
    }
    return true;
  }

  [[nodiscard]] std::uint64_t hash(const std::uint64_t* s) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::size_t i = 0; i < words_; ++i) {
      h ^= s[i] + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
      h *= 0xff51afd7ed558ccdull;
      h ^= h >> 33;
    }
    return h;
  }

  // Only stored states may be in the partition (no claims pending): their hashes are recomputed
  // from their data, read ahead since the states of one partition lie all over the store.
  void grow(Partition& p) {
    std::vector<std::uint64_t> bigger(p.slots.size() * 2, 0);
    const std::size_t mask = bigger.size() - 1, n = p.slots.size();
    constexpr std::size_t kAhead = 16;
    for (std::size_t k = 0; k < std::min(n, kAhead); ++k) {
      if (p.slots[k] != 0) __builtin_prefetch(state((p.slots[k] & 0xffffffffu) - 1));
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (k + kAhead < n && p.slots[k + kAhead] != 0) __builtin_prefetch(state((p.slots[k + kAhead] & 0xffffffffu) - 1));
      const std::uint64_t entry = p.slots[k];
      if (entry == 0) continue;
      std::uint64_t h = hash(state((entry & 0xffffffffu) - 1));
      std::size_t slot = h & mask;
      while (bigger[slot] != 0) slot = (slot + 1) & mask;
      bigger[slot] = entry;
    }
    p.slots.swap(bigger);
  }

  std::size_t words_;
  static constexpr unsigned kChunkBits = 16;  // states per chunk: 2^16
  std::vector<std::unique_ptr<std::uint64_t[]>> chunks_;
  std::vector<Partition> partitions_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> via_;  // rule << 8 | branch
};

// The path from the initial state to `target`, as a trace of real steps. With symmetry the store
// holds one state per orbit, and the rule that led to a stored state led from the stored parent:
// the concrete run is replayed, taking at each step a rule whose successor has the stored state
// as its representative.
inline Trace traceTo(const CompiledModel& cm, const StateStore& store, std::size_t target, const Symmetry* symmetry = nullptr) {
  std::vector<std::size_t> path;
  for (std::size_t i = target; i != kNoParent; i = store.parent(i)) path.push_back(i);
  std::reverse(path.begin(), path.end());
  const StateLayout& layout = cm.layout();
  std::vector<Value> before(layout.variables()), after(layout.variables()), stored(layout.variables()), canonical(layout.variables());
  std::vector<std::uint32_t> candidates;
  Trace trace;
  layout.unpack(store.state(path.front()), before.data());
  trace.initial = before;
  for (std::size_t k = 1; k < path.size(); ++k) {
    layout.unpack(store.state(path[k]), stored.data());
    std::uint32_t via = store.via(path[k]);
    if (symmetry == nullptr || symmetry->empty()) {
      after = stored;
    } else {
      bool found = false;
      cm.candidateRules(before.data(), candidates);
      for (std::size_t c = 0; c < candidates.size() && !found; ++c) {
        const CompiledRule& rule = cm.rules()[candidates[c]];
        if (rule.guard.eval(before.data()) == 0) continue;
        for (std::size_t b = 0; b < rule.branches.size() && !found; ++b) {
          cm.step(rule.branches[b], before.data(), after.data());
          canonical = after;
          symmetry->canonicalize(canonical.data());
          if (canonical == stored) {
            found = true;
            via = candidates[c] << 8 | static_cast<std::uint32_t>(b);
          }
        }
      }
      if (!found) throw std::logic_error("symmetry: a stored step has no concrete counterpart");
    }
    Step step{via >> 8, via & 0xffu, {}};
    for (ir::VarId v = 0; v < after.size(); ++v) {
      if (before[v] != after[v]) step.changes.push_back({v, before[v], after[v]});
    }
    trace.steps.push_back(std::move(step));
    before.swap(after);
  }
  return trace;
}

}  // namespace semo::checker::detail
