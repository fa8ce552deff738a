#include "semo/checker/explicit_search.hpp"

#include <algorithm>
#include <chrono>

#include "semo/checker/compiled_model.hpp"

namespace semo::checker {

namespace {

constexpr std::uint32_t kNoParent = 0xffffffffu;

// Every reachable state once, packed, in BFS order; with the parent and rule that first reached it.
class StateStore {
 public:
  explicit StateStore(std::size_t words) : words_(words), table_(1u << 16, 0) {}

  [[nodiscard]] std::size_t size() const { return parent_.size(); }
  [[nodiscard]] const std::uint64_t* state(std::size_t i) const { return &data_[i * words_]; }
  [[nodiscard]] std::uint32_t parent(std::size_t i) const { return parent_[i]; }
  [[nodiscard]] std::uint32_t via(std::size_t i) const { return via_[i]; }
  [[nodiscard]] std::uint64_t bytes() const {
    return data_.capacity() * 8 + table_.capacity() * 4 + parent_.capacity() * 4 + via_.capacity() * 4;
  }
  [[nodiscard]] std::uint64_t bytesPerState() const { return words_ * 8 + 4 + 4 + 8; }  // data, parent, via, table

  [[nodiscard]] bool contains(const std::uint64_t* s) const {
    std::size_t mask = table_.size() - 1;
    for (std::size_t slot = hash(s) & mask;; slot = (slot + 1) & mask) {
      std::uint32_t entry = table_[slot];
      if (entry == 0) return false;
      if (std::equal(s, s + words_, state(entry - 1))) return true;
    }
  }

  // Returns the state's index and whether it is new.
  std::pair<std::uint32_t, bool> insert(const std::uint64_t* s, std::uint32_t parent, std::uint32_t via) {
    if ((parent_.size() + 1) * 2 > table_.size()) grow();
    std::size_t mask = table_.size() - 1;
    for (std::size_t slot = hash(s) & mask;; slot = (slot + 1) & mask) {
      std::uint32_t entry = table_[slot];
      if (entry == 0) {
        auto index = static_cast<std::uint32_t>(parent_.size());
        table_[slot] = index + 1;
        data_.insert(data_.end(), s, s + words_);
        parent_.push_back(parent);
        via_.push_back(via);
        return {index, true};
      }
      if (std::equal(s, s + words_, state(entry - 1))) return {entry - 1, false};
    }
  }

 private:
  [[nodiscard]] std::size_t hash(const std::uint64_t* s) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::size_t i = 0; i < words_; ++i) {
      h ^= s[i] + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
      h *= 0xff51afd7ed558ccdull;
      h ^= h >> 33;
    }
    return static_cast<std::size_t>(h);
  }

  void grow() {
    std::vector<std::uint32_t> bigger(table_.size() * 2, 0);
    std::size_t mask = bigger.size() - 1;
    for (std::uint32_t i = 0; i < parent_.size(); ++i) {
      std::size_t slot = hash(state(i)) & mask;
      while (bigger[slot] != 0) slot = (slot + 1) & mask;
      bigger[slot] = i + 1;
    }
    table_.swap(bigger);
  }

  std::size_t words_;
  std::vector<std::uint64_t> data_;
  std::vector<std::uint32_t> table_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> via_;  // rule << 8 | branch
};

Trace traceTo(const CompiledModel& cm, const StateStore& store, std::size_t target) {
  std::vector<std::size_t> path;
  for (std::size_t i = target; i != kNoParent; i = store.parent(i)) path.push_back(i);
  std::reverse(path.begin(), path.end());
  const StateLayout& layout = cm.layout();
  std::vector<Value> before(layout.variables()), after(layout.variables());
  Trace trace;
  layout.unpack(store.state(path.front()), before.data());
  trace.initial = before;
  for (std::size_t k = 1; k < path.size(); ++k) {
    layout.unpack(store.state(path[k]), after.data());
    Step step{store.via(path[k]) >> 8, store.via(path[k]) & 0xffu, {}};
    for (ir::VarId v = 0; v < after.size(); ++v) {
      if (before[v] != after[v]) step.changes.push_back({v, before[v], after[v]});
    }
    trace.steps.push_back(std::move(step));
    before.swap(after);
  }
  return trace;
}

}  // namespace

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

  StateStore store(layout.words());
  result.bytesPerState = store.bytesPerState();
  std::vector<Value> values = cm.initialValues(), next(values.size()), scratch;
  std::vector<std::uint64_t> packed(layout.words());
  std::vector<std::uint32_t> candidates;

  auto checkInvariants = [&](const Value* v, std::size_t index) {
    for (std::size_t p = 0; p < cm.invariants().size(); ++p) {
      if (result.properties[p].verdict == Verdict::Violated || cm.invariants()[p].eval(v) != 0) continue;
      result.properties[p].verdict = Verdict::Violated;
      Trace t = traceTo(cm, store, index);
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
    Trace t = traceTo(cm, store, index);
    t.property = "deadlock_freedom";
    t.kind = "deadlock";
    result.properties[deadlockIndex].counterexample = std::move(t);
    --open;
  };

  // For a state at a --max-depth bound, which is not expanded: whether a rule is enabled, and
  // whether a successor is not yet stored (or out of range), i.e. the bound cut something off.
  struct Frontier {
    bool enabled = false, cutOff = false;
  };
  auto probe = [&](const Value* v) {
    Frontier f;
    cm.candidateRules(v, candidates);
    for (std::uint32_t r : candidates) {
      const CompiledRule& rule = cm.rules()[r];
      if (rule.guard.eval(v) == 0) continue;
      f.enabled = true;
      for (const CompiledBranch& branch : rule.branches) {
        std::copy_n(v, next.size(), next.begin());
        scratch.resize(branch.assignments.size());
        bool inRange = true;
        for (std::size_t a = 0; a < branch.assignments.size(); ++a) {
          scratch[a] = branch.assignments[a].value.eval(v);
          inRange = inRange && cm.inRange(branch.assignments[a].var, scratch[a]);
        }
        if (!inRange) return Frontier{true, true};
        for (std::size_t a = 0; a < branch.assignments.size(); ++a) next[branch.assignments[a].var] = scratch[a];
        layout.pack(next.data(), packed.data());
        if (!store.contains(packed.data())) return Frontier{true, true};
      }
    }
    return f;
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
      // States i.. lie at the bound: judged (invariants when stored, deadlock here) but not expanded.
      for (std::size_t j = i; j < store.size(); ++j) {
        layout.unpack(store.state(j), values.data());
        Frontier f = probe(values.data());
        cutOff = cutOff || f.cutOff;
        if (!f.enabled) judgeDeadlock(values.data(), j);
      }
      if (cutOff) {
        result.limitReached = "--max-depth " + std::to_string(limits.maxDepth) + " reached";
        result.depthBounded = true;
      }
      exhausted = !cutOff;
      break;
    }
    layout.unpack(store.state(i), values.data());
    bool enabled = false;
    cm.candidateRules(values.data(), candidates);
    for (std::size_t k = 0; k < candidates.size() && !stopped; ++k) {
      std::size_t r = candidates[k];
      const CompiledRule& rule = cm.rules()[r];
      if (rule.guard.eval(values.data()) == 0) continue;
      enabled = true;
      for (std::size_t b = 0; b < rule.branches.size(); ++b) {
        const CompiledBranch& branch = rule.branches[b];
        scratch.resize(branch.assignments.size());
        for (std::size_t a = 0; a < branch.assignments.size(); ++a) scratch[a] = branch.assignments[a].value.eval(values.data());
        next = values;
        for (std::size_t a = 0; a < branch.assignments.size(); ++a) next[branch.assignments[a].var] = scratch[a];
        ++result.transitions;
        bool outOfRange = false;
        for (std::size_t a = 0; a < branch.assignments.size(); ++a) {
          outOfRange = outOfRange || !cm.inRange(branch.assignments[a].var, scratch[a]);
        }
        if (outOfRange) {
          // The model is wrong, not the mission: say where, with the path that gets there.
          Trace t = traceTo(cm, store, i);
          std::vector<Change> changes;
          for (std::size_t a = 0; a < branch.assignments.size(); ++a) {
            ir::VarId var = branch.assignments[a].var;
            if (values[var] != scratch[a]) changes.push_back({var, values[var], scratch[a]});
          }
          t.steps.push_back({r, b, std::move(changes)});
          t.kind = "range";
          result.rangeError = std::move(t);
          result.limitReached = "an update left a variable's declared range";
          stopped = true;
          break;
        }
        layout.pack(next.data(), packed.data());
        auto [index, added] = store.insert(packed.data(), static_cast<std::uint32_t>(i),
                                           static_cast<std::uint32_t>(r << 8 | (b & 0xffu)));
        if (added) checkInvariants(next.data(), index);
      }
    }
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
