#pragma once
// Successor generation for the explicit search, on several threads. The search takes the stored
// states in order; ahead of it, blocks of stored states are expanded in parallel (each thread a
// contiguous run), and the search then inserts the successors in the same order as a single thread
// would: the state numbering, the counts and every counterexample are independent of the threads.
#include <cstdint>
#include <optional>
#include <vector>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/symmetry.hpp"
#include "semo/checker/trace.hpp"
#include "state_store.hpp"

namespace semo::checker::detail {

// The successors of a run of consecutive stored states.
struct Expansion {
  std::size_t firstState = 0, endState = 0;  // the states [firstState, endState)
  std::vector<std::uint64_t> packed;         // successor k at [k * words, (k + 1) * words)
  std::vector<std::uint64_t> hash;
  std::vector<std::uint32_t> via;      // rule << 8 | branch
  std::vector<std::uint32_t> begin;    // per state: its first successor; one more entry at the end
  std::vector<std::uint8_t> enabled;   // per state: some rule enabled
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

  // Expands the stored states [first, end) (a block), split over the threads.
  void expand(const StateStore& store, std::size_t first, std::size_t end);
  // The expansion (of the last block) that holds state i.
  [[nodiscard]] const Expansion& of(std::size_t i) const;
  [[nodiscard]] std::size_t expandedEnd() const { return parts_.empty() ? 0 : parts_.back().endState; }
  [[nodiscard]] unsigned threads() const { return static_cast<unsigned>(workers_.size()); }

 private:
  struct Worker {
    std::vector<Value> values, next, scratch;
    std::vector<std::uint64_t> packed;
    std::vector<std::uint32_t> candidates;
    Symmetry symmetry;  // a copy: canonicalisation keeps scratch space
  };
  void run(Worker& w, const StateStore& store, Expansion& out) const;

  const CompiledModel& cm_;
  bool useSymmetry_;
  std::vector<Worker> workers_;
  std::vector<Expansion> parts_;
};

}  // namespace semo::checker::detail
