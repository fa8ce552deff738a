#include "successors.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <stdexcept>

namespace semo::checker::detail {

SuccessorGenerator::SuccessorGenerator(const CompiledModel& cm, const Symmetry* symmetry, unsigned threads)
    : cm_(cm),
      useSymmetry_(symmetry != nullptr),
      // A developers' knob, to measure what the pruning saves (checker/README.md).
      pruneEqualRobots_(useSymmetry_ && std::getenv("SEMO_NO_EQUAL_ROBOT_PRUNING") == nullptr),
      workers_(std::max(1u, threads)) {
  for (Worker& w : workers_) {
    if (symmetry != nullptr) w.symmetry = *symmetry;
  }
}

void SuccessorGenerator::run(Worker& w, const StateStore& store, Expansion& out) const {
  const StateLayout& layout = cm_.layout();
  w.values.resize(layout.variables());
  w.next.resize(layout.variables());
  w.packed.resize(layout.words());
  out.packed.clear();
  out.hash.clear();
  out.via.clear();
  out.begin.clear();
  out.enabled.clear();
  out.skipped.clear();
  out.rangeError.reset();
  if (useSymmetry_ && w.seen.size() != cm_.rules().size()) {
    w.seen.assign(cm_.rules().size(), 0);
    w.successors.assign(cm_.rules().size(), 0);
  }
  for (std::size_t i = out.firstState; i < out.endState; ++i) {
    out.begin.push_back(static_cast<std::uint32_t>(out.via.size()));
    layout.unpack(store.state(i), w.values.data());
    bool enabled = false;
    std::uint32_t skipped = 0;
    // The state is canonical: robots with equal values sit side by side.
    const bool pruning = pruneEqualRobots_ && w.symmetry.equalNeighbours(w.values.data(), w.equal);
    ++w.stamp;
    cm_.candidateRules(w.values.data(), w.candidates);
    for (std::uint32_t r : w.candidates) {
      const CompiledRule& rule = cm_.rules()[r];
      std::uint32_t lower = 0;
      if (pruning && w.symmetry.redundant(r, w.equal, lower)) {
        // Enabled exactly when `lower` is (the swap leaves the state as it is), which came first
        // (candidates ascend); its successors are this rule's, up to that swap.
        const std::uint32_t n = w.seen[lower] == w.stamp ? w.successors[lower] : 0;
        w.seen[r] = w.stamp;
        w.successors[r] = n;
        skipped += n;
        continue;
      }
      if (!rule.guard.holds(w.values.data())) continue;
      enabled = true;
      if (useSymmetry_) {
        w.seen[r] = w.stamp;
        w.successors[r] = static_cast<std::uint32_t>(rule.branches.size());
      }
      for (std::size_t b = 0; b < rule.branches.size(); ++b) {
        const CompiledBranch& branch = rule.branches[b];
        w.scratch.resize(branch.assignments.size());
        bool inRange = true;
        for (std::size_t a = 0; a < branch.assignments.size(); ++a) {
          w.scratch[a] = branch.assignments[a].value.eval(w.values.data());
          inRange = inRange && (!branch.assignments[a].mayLeaveRange || cm_.inRange(branch.assignments[a].var, w.scratch[a]));
        }
        if (!inRange) {
          Step step{r, b, {}};
          for (std::size_t a = 0; a < branch.assignments.size(); ++a) {
            ir::VarId var = branch.assignments[a].var;
            if (w.values[var] != w.scratch[a]) step.changes.push_back({var, w.values[var], w.scratch[a]});
          }
          out.rangeError = Expansion::RangeError{i, std::move(step)};
          out.enabled.push_back(1);
          out.skipped.push_back(skipped);
          out.endState = i + 1;  // the search stops here
          out.begin.push_back(static_cast<std::uint32_t>(out.via.size()));
          return;
        }
        if (useSymmetry_) {
          w.next = w.values;
          for (std::size_t a = 0; a < branch.assignments.size(); ++a) w.next[branch.assignments[a].var] = w.scratch[a];
          w.symmetry.canonicalize(w.next.data());
          layout.pack(w.next.data(), w.packed.data());
        } else {
          // Only the assigned fields differ from the state being expanded.
          std::copy_n(store.state(i), w.packed.size(), w.packed.begin());
          for (std::size_t a = 0; a < branch.assignments.size(); ++a) layout.set(w.packed.data(), branch.assignments[a].var, w.scratch[a]);
        }
        out.packed.insert(out.packed.end(), w.packed.begin(), w.packed.end());
        out.hash.push_back(store.hashOf(w.packed.data()));
        out.via.push_back(r << 8 | static_cast<std::uint32_t>(b));
      }
    }
    out.enabled.push_back(enabled ? 1 : 0);
    out.skipped.push_back(skipped);
  }
  out.begin.push_back(static_cast<std::uint32_t>(out.via.size()));
}

void SuccessorGenerator::expand(const StateStore& store, std::size_t first, std::size_t end, WorkerPool& pool) {
  // Runs of at least 256 states (shorter ones cost more to hand out than to expand), at most 16
  // (more than the threads, so that a thread done early takes another).
  if (pool.size() > workers_.size()) throw std::logic_error("successor generator: more threads than workers");
  const std::size_t n = end - first, runs = std::clamp<std::size_t>(n / 256, 1, 16);
  parts_.resize(runs);
  for (std::size_t k = 0; k < runs; ++k) {
    parts_[k].firstState = first + n * k / runs;
    parts_[k].endState = first + n * (k + 1) / runs;
  }
  std::atomic<std::size_t> nextRun{0};
  pool.run([&](unsigned thread) {
    for (std::size_t k = nextRun.fetch_add(1, std::memory_order_relaxed); k < runs; k = nextRun.fetch_add(1, std::memory_order_relaxed)) {
      run(workers_[thread], store, parts_[k]);
    }
  });
  // A range error ends the block: the runs after it are dropped.
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    if (parts_[k].rangeError) {
      parts_.resize(k + 1);
      break;
    }
  }
}

const Expansion& SuccessorGenerator::of(std::size_t i) const {
  for (const Expansion& e : parts_) {
    if (i >= e.firstState && i < e.endState) return e;
  }
  return parts_.back();
}

}  // namespace semo::checker::detail
