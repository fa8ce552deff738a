#pragma once
// Successor generation for the explicit search, on several threads. The search takes the stored
// states in blocks; a block is cut into runs of consecutive states (how many depends on the block,
// not on the threads), which the threads expand, each taking the next run not taken. The
// successors are then inserted in the order of the runs, as a single thread would: the state
// numbering, the counts and every counterexample are independent of the threads.
#include <cstdint>
#include <optional>
#include <vector>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/symmetry.hpp"
#include "semo/checker/trace.hpp"
#include "state_store.hpp"
#include "worker_pool.hpp"

namespace semo::checker::detail {

// The successors of a run of consecutive stored states. One cache line apart: threads fill
// neighbouring ones at once.
struct alignas(64) Expansion {
  std::size_t firstState = 0, endState = 0;  // the states [firstState, endState)
  std::vector<std::uint64_t> packed;         // successor k at [k * words, (k + 1) * words)
  std::vector<std::uint64_t> hash;
  std::vector<std::uint32_t> via;      // rule << 8 | branch
  std::vector<std::uint32_t> begin;    // per state: its first successor; one more entry at the end
  std::vector<std::uint8_t> enabled;   // per state: some rule enabled
  // Per state: successors not generated, as a lower rule's image under a swap that leaves the
  // state as it is already gave them (Symmetry::redundant); counted as transitions all the same.
  std::vector<std::uint32_t> skipped;
  // The first update out of its variable's range: the state, the step, and what it changes. The
  // successors of that state before it are listed; later states of the run are not expanded.
  struct RangeError {
    std::size_t state;
    Step step;
  };
  std::optional<RangeError> rangeError;
};

class SuccessorGenerator {
 public:
  SuccessorGenerator(const CompiledModel& cm, const Symmetry* symmetry, unsigned threads);

  // Expands the stored states [first, end) (a block) on the pool's threads; `threads` of the
  // constructor must be the pool's size.
  void expand(const StateStore& store, std::size_t first, std::size_t end, WorkerPool& pool);
  // The runs of the last block, in order; a range error ends the block (no run after it).
  [[nodiscard]] const std::vector<Expansion>& parts() const { return parts_; }
  // The expansion (of the last block) that holds state i.
  [[nodiscard]] const Expansion& of(std::size_t i) const;
  [[nodiscard]] std::size_t expandedEnd() const { return parts_.empty() ? 0 : parts_.back().endState; }

 private:
  // Used by one thread only, which sizes the vectors on first use: allocated by it, from its own
  // malloc arena, they share no cache line with another thread's.
  struct alignas(64) Worker {
    std::vector<Value> values, next, scratch;
    std::vector<std::uint64_t> packed;
    std::vector<std::uint32_t> candidates;
    Symmetry symmetry;  // a copy: canonicalisation keeps scratch space
    std::vector<char> equal;  // Symmetry::equalNeighbours of the state being expanded
    // Per rule, the successors it had in the state being expanded, valid where `seen` is `stamp`.
    std::vector<std::uint32_t> successors;
    std::vector<std::uint64_t> seen;
    std::uint64_t stamp = 0;
  };
  void run(Worker& w, const StateStore& store, Expansion& out) const;

  const CompiledModel& cm_;
  bool useSymmetry_;
  bool pruneEqualRobots_;  // skip the rules Symmetry::redundant names
  std::vector<Worker> workers_;
  std::vector<Expansion> parts_;
};

}  // namespace semo::checker::detail
