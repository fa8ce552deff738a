#include "semo/checker/explicit_search.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <future>

#include "semo/checker/compiled_model.hpp"
#include "state_store.hpp"
#include "successors.hpp"

namespace semo::checker {

using detail::kNoParent;
using detail::StateStore;
using detail::traceTo;

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::Proven: return "proven";
    case Verdict::Violated: return "VIOLATED";
    case Verdict::Unknown: return "unknown";
  }
  return "unknown";
}

SearchResult checkSafety(const ir::Model& model, const SearchLimits& limits) {
  auto start = std::chrono::steady_clock::now();
  CompiledModel cm(model);
  const StateLayout& layout = cm.layout();
  SearchResult result;
  for (const ir::Invariant& inv : model.invariants) result.properties.push_back({inv.name, inv.origin, Verdict::Unknown, {}});
  const Program* validEnd = cm.validEnd();
  std::size_t deadlockIndex = SIZE_MAX;
  if (validEnd != nullptr) {
    deadlockIndex = result.properties.size();
    result.properties.push_back({"deadlock_freedom", "", Verdict::Unknown, {}});
  }
  std::size_t open = result.properties.size();  // properties not yet violated

  Symmetry symmetry = limits.symmetry ? Symmetry::find(model) : Symmetry();
  result.symmetry = symmetry.describe(model);
  const Symmetry* sym = symmetry.empty() ? nullptr : &symmetry;
  StateStore store(layout.words());
  result.bytesPerState = store.bytesPerState();
  std::vector<Value> values = cm.initialValues(), next(values.size());
  std::vector<std::uint64_t> packed(layout.words());
  // Two generators: one block is inserted while the next is expanded (with more than one thread).
  std::array<detail::SuccessorGenerator, 2> generators{detail::SuccessorGenerator(cm, sym, limits.threads),
                                                       detail::SuccessorGenerator(cm, sym, limits.threads)};
  std::size_t current = 0;
  std::future<void> ahead;
  const std::size_t block = 4096 * std::max(1u, limits.threads);

  auto checkInvariants = [&](const Value* v, std::size_t index) {
    for (std::size_t p = 0; p < cm.invariants().size(); ++p) {
      if (result.properties[p].verdict == Verdict::Violated || cm.invariants()[p].eval(v) != 0) continue;
      result.properties[p].verdict = Verdict::Violated;
      Trace t = traceTo(cm, store, index, sym);
      t.property = result.properties[p].name;
      t.kind = "invariant";
      result.properties[p].counterexample = std::move(t);
      --open;
    }
  };

  layout.pack(values.data(), packed.data());
  store.insert(packed.data(), kNoParent, 0);
  checkInvariants(values.data(), 0);

  auto judgeDeadlock = [&](const Value* v, std::size_t index) {
    if (deadlockIndex == SIZE_MAX || result.properties[deadlockIndex].verdict == Verdict::Violated) return;
    if (validEnd->eval(v) != 0) return;
    result.properties[deadlockIndex].verdict = Verdict::Violated;
    Trace t = traceTo(cm, store, index, sym);
    t.property = "deadlock_freedom";
    t.kind = "deadlock";
    result.properties[deadlockIndex].counterexample = std::move(t);
    --open;
  };

  std::size_t levelEnd = 1;
  double nextReport = 1.0;
  bool stopped = false, exhausted = false, cutOff = false;
  for (std::size_t i = 0;; ++i) {
    // Before the exhaustion test: a range error in the last queued state leaves its successor
    // unexplored, so the search is not complete.
    if (stopped) break;
    if (i == store.size()) {
      exhausted = true;
      break;
    }
    // Once every property is violated there is nothing left to prove.
    if (open == 0 && !result.properties.empty()) {
      result.limitReached = "every property is violated";
      break;
    }
    if (i == levelEnd) {
      ++result.depth;  // the depth of state i
      levelEnd = store.size();
    }
    if (result.depth >= limits.maxDepth) {
      // States i.. lie at the bound: judged (invariants when stored, deadlock here) but not
      // inserted. The bound cut something off if one of them has a successor not yet stored (or
      // an update out of range).
      if (ahead.valid()) ahead.get();
      detail::SuccessorGenerator& g = generators[current];
      const std::size_t frontierEnd = store.size(), words = layout.words();
      for (std::size_t j = i; j < frontierEnd; j = g.expandedEnd()) {
        g.expand(store, j, std::min(frontierEnd, j + block));
        for (std::size_t k = j; k < g.expandedEnd(); ++k) {
          const detail::Expansion& e = g.of(k);
          const std::size_t local = k - e.firstState;
          for (std::uint32_t n = e.begin[local]; n < e.begin[local + 1] && !cutOff; ++n) cutOff = !store.contains(&e.packed[n * words]);
          cutOff = cutOff || (e.rangeError && e.rangeError->state == k);
          if (e.enabled[local] == 0) {
            layout.unpack(store.state(k), values.data());
            judgeDeadlock(values.data(), k);
          }
        }
      }
      if (cutOff) {
        result.limitReached = "--max-depth " + std::to_string(limits.maxDepth) + " reached";
        result.depthBounded = true;
      }
      exhausted = !cutOff;
      break;
    }
    if (i >= generators[current].expandedEnd()) {
      if (ahead.valid()) {
        ahead.get();  // the block after the one just consumed, expanded meanwhile
        current ^= 1;
      }
      if (i >= generators[current].expandedEnd()) generators[current].expand(store, i, std::min(store.size(), i + block));
      // With more than one thread, the next block is expanded while this one is inserted.
      std::size_t nextFirst = generators[current].expandedEnd(), nextEnd = std::min(store.size(), nextFirst + block);
      if (limits.threads > 1 && nextEnd > nextFirst && !generators[current].of(i).rangeError) {
        ahead = std::async(std::launch::async, [&generators, &store, other = current ^ 1, nextFirst, nextEnd] {
          generators[other].expand(store, nextFirst, nextEnd);
        });
      }
    }
    const detail::Expansion& e = generators[current].of(i);
    const std::size_t local = i - e.firstState, words = layout.words();
    const std::uint32_t from = e.begin[local], to = e.begin[local + 1];
    result.transitions += to - from;
    for (std::uint32_t k = from; k < to && k < from + 8; ++k) store.prefetch(e.hash[k]);
    for (std::uint32_t k = from; k < to; ++k) {
      if (k + 8 < to) store.prefetch(e.hash[k + 8]);
      auto [index, added] = store.insert(&e.packed[k * words], e.hash[k], static_cast<std::uint32_t>(i), e.via[k]);
      if (added && !cm.invariants().empty()) {
        layout.unpack(&e.packed[k * words], next.data());
        checkInvariants(next.data(), index);
      }
    }
    if (e.rangeError && e.rangeError->state == i) {
      // The model is wrong, not the mission: say where, with the path that gets there.
      ++result.transitions;
      Trace t = traceTo(cm, store, i, sym);
      t.steps.push_back(e.rangeError->step);
      t.kind = "range";
      result.rangeError = std::move(t);
      result.limitReached = "an update left a variable's declared range";
      stopped = true;
    }
    bool enabled = e.enabled[local] != 0;
    if (!enabled) layout.unpack(store.state(i), values.data());
    if (!enabled) judgeDeadlock(values.data(), i);
    result.peakBytes = std::max(result.peakBytes, store.bytes());
    if (limits.onProgress && (i & 0x3fffu) == 0) {
      double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (elapsed >= nextReport) {
        limits.onProgress({store.size(), result.transitions, store.bytes(), result.depth, elapsed});
        nextReport = elapsed + 1.0;
      }
    }
    bool more = i + 1 < store.size();  // a limit reached after the last state changes nothing
    if (!stopped && more && store.size() >= limits.maxStates) {
      result.limitReached = "--max-states " + std::to_string(limits.maxStates) + " reached";
      stopped = true;
    }
    if (!stopped && more && store.bytes() >= limits.maxMemoryBytes) {
      result.limitReached = "--max-memory " + std::to_string(limits.maxMemoryBytes >> 20) + " MiB reached";
      stopped = true;
    }
  }
  result.states = store.size();
  result.complete = exhausted;
  for (PropertyResult& p : result.properties) {
    if (p.verdict != Verdict::Violated && result.complete) p.verdict = Verdict::Proven;
  }
  result.peakBytes = std::max(result.peakBytes, store.bytes());
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace semo::checker
