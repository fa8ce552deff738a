#pragma once
// The store of explored states shared by the search engines: every state once, packed, in the
// order found, with the parent and rule that first reached it (so a path back to the start is a
// walk up the parents; in breadth-first order it is a shortest one).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <stdexcept>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/symmetry.hpp"
#include "semo/checker/trace.hpp"

namespace semo::checker::detail {

constexpr std::uint32_t kNoParent = 0xffffffffu;

// Every reachable state once, packed, in BFS order; with the parent and rule that first reached it.
class StateStore {
 public:
  // `words`: 64-bit words per state (the engines may append words of their own after the model's).
  explicit StateStore(std::size_t words) : words_(words), table_(1u << 16, 0) {
    chunks_.reserve(std::size_t{1} << (32 - kChunkBits));  // never reallocated: see state()
  }

  [[nodiscard]] std::size_t size() const { return parent_.size(); }
  // Stored states never move: another thread may read the first n states (n known to it) while
  // new ones are added.
  [[nodiscard]] const std::uint64_t* state(std::size_t i) const {
    return chunks_[i >> kChunkBits].get() + (i & ((std::size_t{1} << kChunkBits) - 1)) * words_;
  }
  [[nodiscard]] std::uint32_t parent(std::size_t i) const { return parent_[i]; }
  [[nodiscard]] std::uint32_t via(std::size_t i) const { return via_[i]; }
  [[nodiscard]] std::uint64_t bytes() const {
    return chunks_.size() * (std::size_t{1} << kChunkBits) * words_ * 8 + table_.capacity() * 8 + parent_.capacity() * 4 +
           via_.capacity() * 4;
  }
  // data, parent, via, and the hash table (8-byte slots, at most half full)
  [[nodiscard]] std::uint64_t bytesPerState() const { return words_ * 8 + 4 + 4 + 16; }

  [[nodiscard]] bool contains(const std::uint64_t* s) const {
    std::uint64_t h = hash(s);
    std::size_t mask = table_.size() - 1;
    for (std::size_t slot = h & mask;; slot = (slot + 1) & mask) {
      std::uint64_t entry = table_[slot];
      if (entry == 0) return false;
      if ((entry >> 32) == (h >> 32) && same(s, state((entry & 0xffffffffu) - 1))) return true;
    }
  }

  [[nodiscard]] std::uint64_t hashOf(const std::uint64_t* s) const { return hash(s); }
  // Starts loading the slot a state with hash h probes first: the search hashes all successors of a
  // state, prefetches, then inserts them, so that the cache misses overlap.
  void prefetch(std::uint64_t h) const { __builtin_prefetch(&table_[h & (table_.size() - 1)]); }

  // Returns the state's index and whether it is new.
  std::pair<std::uint32_t, bool> insert(const std::uint64_t* s, std::uint32_t parent, std::uint32_t via) {
    return insert(s, hash(s), parent, via);
  }
  std::pair<std::uint32_t, bool> insert(const std::uint64_t* s, std::uint64_t h, std::uint32_t parent, std::uint32_t via) {
    if ((parent_.size() + 1) * 2 > table_.size()) grow();
    std::size_t mask = table_.size() - 1;
    for (std::size_t slot = h & mask;; slot = (slot + 1) & mask) {
      std::uint64_t entry = table_[slot];
      if (entry == 0) {
        auto index = static_cast<std::uint32_t>(parent_.size());
        table_[slot] = (h & ~0xffffffffull) | (static_cast<std::uint64_t>(index) + 1);
        if ((index >> kChunkBits) == chunks_.size()) {
          chunks_.push_back(std::make_unique<std::uint64_t[]>((std::size_t{1} << kChunkBits) * words_));
        }
        std::copy_n(s, words_, chunks_[index >> kChunkBits].get() + (index & ((std::size_t{1} << kChunkBits) - 1)) * words_);
        parent_.push_back(parent);
        via_.push_back(via);
        return {index, true};
      }
      // The slot keeps the upper half of the hash: most other states are told apart without
      // reading their data (a cache miss).
      if ((entry >> 32) == (h >> 32) && same(s, state((entry & 0xffffffffu) - 1))) {
        return {static_cast<std::uint32_t>((entry & 0xffffffffu) - 1), false};
      }
    }
  }

 private:
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

  void grow() {
    std::vector<std::uint64_t> bigger(table_.size() * 2, 0);
    std::size_t mask = bigger.size() - 1;
    for (std::uint32_t i = 0; i < parent_.size(); ++i) {
      std::uint64_t h = hash(state(i));
      std::size_t slot = h & mask;
      while (bigger[slot] != 0) slot = (slot + 1) & mask;
      bigger[slot] = (h & ~0xffffffffull) | (static_cast<std::uint64_t>(i) + 1);
    }
    table_.swap(bigger);
  }

  std::size_t words_;
  static constexpr unsigned kChunkBits = 16;  // states per chunk: 2^16
  std::vector<std::unique_ptr<std::uint64_t[]>> chunks_;
  std::vector<std::uint64_t> table_;  // (upper half of the hash) << 32 | (index + 1); 0: empty
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
