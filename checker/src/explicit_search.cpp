#include "semo/checker/explicit_search.hpp"

#include <sched.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "semo/checker/compiled_model.hpp"
#include "block_insertion.hpp"
#include "state_store.hpp"
#include "successors.hpp"
#include "worker_pool.hpp"

namespace semo::checker {

namespace {

// SEMO_THREADS as a count, 0 when unset or not one.
unsigned threadsSetting() {
  const char* text = std::getenv("SEMO_THREADS");
  if (text == nullptr || *text == '\0') return 0;
  unsigned value = 0;
  const char* end = text + std::strlen(text);
  const auto [at, error] = std::from_chars(text, end, value);
  return error == std::errc() && at == end && value >= 1 && value <= 256 ? value : 0;
}

}  // namespace

unsigned defaultThreads() {
  if (unsigned set = threadsSetting(); set != 0) return set;
  cpu_set_t mask;
  if (sched_getaffinity(0, sizeof mask, &mask) == 0) return std::max(1, CPU_COUNT(&mask));
  return std::max(1u, std::thread::hardware_concurrency());
}

std::string threadsSettingError() {
  const char* text = std::getenv("SEMO_THREADS");
  if (text == nullptr || *text == '\0' || threadsSetting() != 0) return {};
  return std::string("SEMO_THREADS='") + text + "' is not a number of threads (a whole number from 1 to 256)";
}

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

  if (limits.onPhase && limits.symmetry) limits.onPhase("symmetry: which of the " + std::to_string(model.robots.size()) + " robots are interchangeable");
  // The LTL properties play no part in this search: robots only they set apart stay interchangeable.
  Symmetry symmetry = limits.symmetry ? Symmetry::find(model, SymmetryScope::safety()) : Symmetry();
  result.symmetry = symmetry.describe(model);
  if (limits.onPhase) limits.onPhase("safety search");
  const Symmetry* sym = symmetry.empty() ? nullptr : &symmetry;
  StateStore store(layout.words());
  result.bytesPerState = store.bytesPerState();
  std::vector<Value> values = cm.initialValues();
  std::vector<std::uint64_t> packed(layout.words());
  detail::WorkerPool pool(limits.threads);
  detail::SuccessorGenerator generator(cm, sym, pool.size());
  detail::BlockInserter inserter;
  // States expanded and inserted together. Fixed, not a multiple of the threads: where the blocks
  // end decides when the store grows, hence --max-memory's cut.
  constexpr std::size_t kBlock = 8192;

  auto violate = [&](std::size_t property, std::size_t index, const char* kind) {
    result.properties[property].verdict = Verdict::Violated;
    Trace t = traceTo(cm, store, index, sym);
    t.property = result.properties[property].name;
    t.kind = kind;
    result.properties[property].counterexample = std::move(t);
    --open;
  };
  const std::size_t invariants = cm.invariants().size();
  auto isOpen = [&](std::size_t property) { return result.properties[property].verdict != Verdict::Violated; };

  layout.pack(values.data(), packed.data());
  store.insert(packed.data(), kNoParent, 0);
  for (std::size_t p = 0; p < invariants; ++p) {
    if (cm.invariants()[p].eval(values.data()) == 0) violate(p, 0, "invariant");
  }

  auto judgeDeadlock = [&](std::size_t index) {
    if (deadlockIndex == SIZE_MAX || !isOpen(deadlockIndex)) return;
    layout.unpack(store.state(index), values.data());
    if (validEnd->eval(values.data()) == 0) violate(deadlockIndex, index, "deadlock");
  };

  // The invariants on the new states of a block, on every thread: per thread and invariant, the
  // first state (in the numbering) that violates it. Only those open when the block starts.
  std::vector<std::uint8_t> checked(invariants);
  // Sized by its thread on first use, so that no cache line holds two threads' scratch (see the
  // generator's Worker).
  struct alignas(64) InvariantScratch {
    std::vector<Value> values;
    std::vector<std::size_t> firstViolation;  // per invariant, checked or not
  };
  std::vector<InvariantScratch> scratch(pool.size());
  auto checkNewStates = [&](unsigned thread, std::size_t first, std::size_t end) {
    InvariantScratch& own = scratch[thread];
    own.values.resize(layout.variables());
    own.firstViolation.resize(invariants, SIZE_MAX);
    for (std::size_t i = first; i < end; ++i) {
      layout.unpack(store.state(i), own.values.data());
      for (std::size_t p = 0; p < invariants; ++p) {
        if (checked[p] != 0 && i < own.firstViolation[p] && cm.invariants()[p].eval(own.values.data()) == 0) own.firstViolation[p] = i;
      }
    }
  };

  std::size_t levelEnd = 1;
  double nextReport = 1.0;
  bool stopped = false, exhausted = false, cutOff = false;
  for (std::size_t first = 0;;) {
    // Before the exhaustion test: a range error in the last queued state leaves its successor
    // unexplored, so the search is not complete.
    if (stopped) break;
    if (first == store.size()) {
      exhausted = true;
      break;
    }
    // Once every property is violated there is nothing left to prove.
    if (open == 0 && !result.properties.empty()) {
      result.limitReached = "every property is violated";
      break;
    }
    if (first == levelEnd) {
      ++result.depth;  // the depth of state `first`
      levelEnd = store.size();
    }
    if (result.depth >= limits.maxDepth) {
      // States first.. lie at the bound: judged (invariants when stored, deadlock here) but not
      // inserted. The bound cut something off if one of them has a successor not yet stored (or
      // an update out of range).
      const std::size_t frontierEnd = store.size(), words = layout.words();
      for (std::size_t j = first; j < frontierEnd; j = generator.expandedEnd()) {
        generator.expand(store, j, std::min(frontierEnd, j + kBlock), pool);
        for (std::size_t k = j; k < generator.expandedEnd(); ++k) {
          const detail::Expansion& e = generator.of(k);
          const std::size_t local = k - e.firstState;
          for (std::uint32_t n = e.begin[local]; n < e.begin[local + 1] && !cutOff; ++n) cutOff = !store.contains(&e.packed[n * words]);
          cutOff = cutOff || (e.rangeError && e.rangeError->state == k);
          if (e.enabled[local] == 0) judgeDeadlock(k);
        }
      }
      if (cutOff) {
        result.limitReached = "--max-depth " + std::to_string(limits.maxDepth) + " reached";
        result.depthBounded = true;
      }
      exhausted = !cutOff;
      break;
    }

    // A block never spans two levels: the depth bound falls between blocks.
    generator.expand(store, first, std::min(levelEnd, first + kBlock), pool);
    const std::size_t sizeBefore = store.size();
    bool anyChecked = false;
    for (std::size_t p = 0; p < invariants; ++p) {
      checked[p] = isOpen(p) ? 1 : 0;
      anyChecked = anyChecked || checked[p] != 0;
    }
    for (InvariantScratch& own : scratch) std::fill(own.firstViolation.begin(), own.firstViolation.end(), SIZE_MAX);
    inserter.insert(store, generator.parts(), pool, anyChecked ? detail::BlockInserter::NewStates(checkNewStates) : nullptr);
    std::vector<std::size_t> violation(invariants, SIZE_MAX);
    for (const InvariantScratch& own : scratch) {
      for (std::size_t p = 0; p < own.firstViolation.size(); ++p) violation[p] = std::min(violation[p], own.firstViolation[p]);
    }

    // The block again, state by state, for what a search expanding one state at a time would do
    // after each: its verdicts, and where it stops (the states it would not have stored are
    // dropped).
    std::size_t stored = sizeBefore;  // the store's size before state i's successors
    // The store's memory only changes per block: a block that passes the limit stops the search
    // after its first state.
    const std::uint64_t bytes = store.bytes();
    std::size_t i = first;
    for (const detail::Expansion& e : generator.parts()) {
      for (; i < e.endState && !stopped; ++i) {
        if (i > first && open == 0 && !result.properties.empty()) {
          result.limitReached = "every property is violated";
          stopped = true;
          break;
        }
        const std::size_t local = i - e.firstState, storedAfter = inserter.sizeAfter(i);
        result.transitions += e.begin[local + 1] - e.begin[local] + e.skipped[local];
        result.transitionsSkipped += e.skipped[local];
        for (std::size_t p = 0; p < invariants; ++p) {
          if (isOpen(p) && violation[p] >= stored && violation[p] < storedAfter) violate(p, violation[p], "invariant");
        }
        stored = storedAfter;
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
        if (e.enabled[local] == 0) judgeDeadlock(i);
        bool more = i + 1 < stored;  // a limit reached after the last state changes nothing
        if (!stopped && more && stored >= limits.maxStates) {
          result.limitReached = "--max-states " + std::to_string(limits.maxStates) + " reached";
          stopped = true;
        }
        if (!stopped && more && bytes >= limits.maxMemoryBytes) {
          result.limitReached = "--max-memory " + std::to_string(limits.maxMemoryBytes >> 20) + " MiB reached";
          stopped = true;
        }
      }
    }
    if (stopped) inserter.truncate(store, stored);
    first = i;
    result.peakBytes = std::max(result.peakBytes, store.bytes());
    if (limits.onProgress) {
      double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (elapsed >= nextReport) {
        limits.onProgress({store.size(), result.transitions, store.bytes(), result.depth, elapsed});
        nextReport = elapsed + 1.0;
      }
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
