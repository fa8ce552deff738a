#pragma once
// The product of the model with a Büchi automaton, explored breadth-first and kept as a graph for
// the liveness search (liveness_search.cpp); with symmetry, the product of the quotient, whose
// edges remember the permutation that canonicalised their targets.
#include <chrono>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "semo/checker/buchi.hpp"
#include "semo/checker/compiled_model.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/checker/symmetry.hpp"
#include "state_store.hpp"

namespace semo::checker::detail {

using Clock = std::chrono::steady_clock;

// Time passing with no step: allowed where no fair rule is enabled (where one is, staying for ever
// would be unfair to it, and staying a while changes nothing the properties can see). So a run may
// end in a state where only unfair rules (loss, crash, the environment) could move.
constexpr std::uint32_t kStutter = 0xffffffu;

struct Edge {
  std::uint32_t target;
  std::uint32_t via;  // rule << 8 | branch, or kStutter << 8
};

inline std::uint32_t ruleOf(std::uint32_t via) { return via >> 8; }

using Permutation = Symmetry::Permutation;

inline Permutation compose(const Permutation& outer, const Permutation& inner) {  // inner first
  Permutation out(inner.size());
  for (std::size_t i = 0; i < inner.size(); ++i) out[i] = outer[inner[i]];
  return out;
}

inline Permutation inverse(const Permutation& p) {
  Permutation out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) out[p[i]] = static_cast<std::uint16_t>(i);
  return out;
}

inline bool isIdentity(const Permutation& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p[i] != i) return false;
  }
  return true;
}

inline std::string keyOf(const Permutation& p) {
  return {reinterpret_cast<const char*>(p.data()), p.size() * sizeof(p[0])};
}

// FNV-1a over the positions: a permutation is looked up as it is, with no key built per lookup.
struct PermutationHash {
  std::size_t operator()(const Permutation& p) const noexcept {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint16_t x : p) h = (h ^ x) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

// The permutations that canonicalised the product's successors, each stored once (0: identity).
class PermutationTable {
 public:
  explicit PermutationTable(std::size_t slots) {
    Permutation identity(slots);
    for (std::size_t i = 0; i < slots; ++i) identity[i] = static_cast<std::uint16_t>(i);
    perms_.push_back(identity);
    inverses_.push_back(identity);
  }
  std::uint32_t intern(const Permutation& p) {
    if (isIdentity(p)) return 0;
    auto found = ids_.find(p);
    if (found != ids_.end()) return found->second;
    auto [it, added] = ids_.try_emplace(p, static_cast<std::uint32_t>(perms_.size()));
    if (added) {
      perms_.push_back(p);
      inverses_.push_back(inverse(p));
    }
    return it->second;
  }
  [[nodiscard]] const Permutation& operator[](std::uint32_t id) const { return perms_[id]; }
  [[nodiscard]] const Permutation& inverseOf(std::uint32_t id) const { return inverses_[id]; }

 private:
  std::vector<Permutation> perms_, inverses_;
  std::unordered_map<Permutation, std::uint32_t, PermutationHash> ids_;
};

// The product of the model with a Büchi automaton, explored breadth-first and kept as a graph.
class Product {
 public:
  // With `symmetry`, the product of the quotient: one state per orbit, and every edge remembers the
  // permutation that took its target to the orbit's representative (FairCycleSearch needs it).
  Product(const CompiledModel& cm, const Buchi& ba, const Symmetry* symmetry)
      : cm_(cm), ba_(ba), store_(cm.layout().words() + 1), perms_(symmetry != nullptr ? symmetry->slots() : 0) {
    for (const ir::Expr& atom : ba.atoms) atoms_.emplace_back(atom);
    if (symmetry != nullptr) symmetry_ = *symmetry;  // a copy: canonicalisation keeps scratch space
  }

  // From `start` instead of the model's initial state (the search of a region, sliced_liveness.cpp).
  void startFrom(std::vector<Value> start) { start_ = std::move(start); }
  // Expand only the states `region` accepts; the others get no edges, as after closeFrontier(): a
  // fair cycle of what is explored is then one of the whole product.
  void expandOnly(std::function<bool(const Value*)> region) { region_ = std::move(region); }

  // Only the runs of a round-robin scheduler over the fairness groups: in each state, the first
  // group at or after the scheduler's turn (kept in the state) that has a rule enabled takes a
  // step, by any of its enabled rules and branches, and the turn passes to the next group; the
  // rules that no fairness constrains (loss, crashes, the environment) may step in any state. A
  // subset of the runs, whose interleavings it fixes: for a hunt for violations (region_lasso.hpp).
  void roundRobin(const Fairness* fairness) { scheduler_ = fairness; }
  // Rules never taken (per rule, 1: barred), e.g. crashes and losses in a hunt for a violation
  // that needs none: fewer runs still.
  void bar(std::vector<char> barred) { barred_ = std::move(barred); }
  // With symmetry: a rule of a robot whose values equal its neighbour's (a rule the swap of the two
  // maps to a lower one, Symmetry::redundant) leads to the lower rule's targets and is not
  // expanded. The fair cycle search must then count the swaps of equal neighbours in the group it
  // lifts a component with (FairCycleSearch::liftComponent); and a settling world, which keeps
  // cycles to the steps of one reading per robot, must not see the lower rule in place of its image.
  void pruneEqualRobots(bool on) { pruneEqual_ = on; }
  // A step that would leave a declared range is no step (LivenessOptions::slice), not an error.
  void outOfRangeIsNoStep(bool on) { outOfRangeIsNoStep_ = on; }
  [[nodiscard]] bool prunesEqualRobots() const { return pruneEqual_ && symmetric(); }
  // Only the steps that decide each sensed condition as `world` says (per point: -1 either way).
  void senseOnly(const Sensing* sensing, std::vector<std::int8_t> world) {
    sensing_ = sensing;
    world_ = std::move(world);
  }

  // False when a limit stopped the exploration (then `why` says which).
  bool explore(const SearchLimits& limits, Clock::time_point start, std::uint64_t statesBefore, std::string& why) {
    const StateLayout& layout = cm_.layout();
    std::vector<Value> values = start_.empty() ? cm_.initialValues() : start_, next(values.size());
    std::vector<std::uint64_t> packed(layout.words() + 1);
    Permutation moved;
    if (symmetric()) symmetry_.canonicalize(values.data(), moved);
    std::uint64_t initialBits = atomBits(values.data());
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      if (ba_.states[q].initial && labelHolds(q, initialBits)) insert(values.data(), q, kNoParent, 0, packed);
    }
    std::vector<std::uint32_t> candidates;
    std::vector<char> equal;
    // The model successors of the state being expanded: their rules, and their values back to back.
    std::vector<std::uint32_t> vias;
    std::vector<std::uint64_t> turns;  // the scheduler's turn after each successor
    std::vector<Value> successorValues;
    const std::size_t width = values.size();
    double nextReport = 1.0;
    for (std::size_t i = 0; i < store_.size(); ++i) {
      edgeStart_.push_back(edges_.size());
      layout.unpack(store_.state(i), values.data());
      if (region_ && !region_(values.data())) continue;
      std::uint32_t q = automatonState(i);
      const std::uint64_t turn = store_.state(i)[layout.words()] >> 32;
      vias.clear();
      successorValues.clear();
      cm_.candidateRules(values.data(), candidates);
      // Rules left out of a hunt (bar, senseOnly); they still count as enabled for fairness. A
      // plain exploration (hunting false) pays for none of it per rule.
      const bool hunting = scheduler_ != nullptr || !barred_.empty() || sensing_ != nullptr;
      const bool pruning = pruneEqual_ && symmetric() && !hunting && symmetry_.equalNeighbours(values.data(), equal);
      auto leftOut = [&](std::uint32_t r) {
        return (!barred_.empty() && barred_[r] != 0) || (sensing_ != nullptr && !sensing_->agrees(r, world_));
      };
      // With the round-robin scheduler: the group whose turn it is (the first at or after the turn
      // with a rule that may step), and the turn after it.
      std::uint32_t chosen = Fairness::kNone;
      std::uint64_t nextTurn = turn;
      if (scheduler_ != nullptr) {
        const std::uint64_t groups = scheduler_->groups();
        std::uint64_t best = UINT64_MAX;
        for (std::uint32_t r : candidates) {
          const std::uint32_t g = scheduler_->groupOf[r];
          if (g == Fairness::kNone || leftOut(r) || cm_.rules()[r].guard.eval(values.data()) == 0) continue;
          const std::uint64_t distance = (g + groups - turn) % groups;
          if (distance < best) best = distance, chosen = g;
        }
        if (chosen != Fairness::kNone) nextTurn = (chosen + 1) % groups;
      }
      turns.clear();
      bool fairEnabled = false;
      for (std::uint32_t r : candidates) {
        const CompiledRule& rule = cm_.rules()[r];
        std::uint32_t lower = 0;
        // Enabled exactly when `lower` is (the swap leaves the state as it is), and as fair:
        // counted there for the stutter.
        if (pruning && symmetry_.redundant(r, equal, lower)) continue;
        if (rule.guard.eval(values.data()) == 0) continue;
        const bool fair = cm_.model().rules[r].weaklyFair || cm_.model().rules[r].stronglyFair;
        fairEnabled = fairEnabled || fair;
        if (hunting && (leftOut(r) || (scheduler_ != nullptr && fair && scheduler_->groupOf[r] != chosen))) continue;
        for (std::size_t b = 0; b < rule.branches.size(); ++b) {
          if (!cm_.step(rule.branches[b], values.data(), next.data())) {
            if (outOfRangeIsNoStep_) continue;
            why = "an update left a variable's declared range (run 'check' for the trace)";
            return false;
          }
          vias.push_back(r << 8 | static_cast<std::uint32_t>(b));
          if (scheduler_ != nullptr) turns.push_back(fair ? nextTurn : turn);
          successorValues.insert(successorValues.end(), next.begin(), next.end());
        }
      }
      if (!fairEnabled) {
        vias.push_back(kStutter << 8);
        if (scheduler_ != nullptr) turns.push_back(turn);
        successorValues.insert(successorValues.end(), values.begin(), values.end());
      }
      for (std::size_t k = 0; k < vias.size(); ++k) {
        Value* succ = successorValues.data() + k * width;
        std::uint32_t perm = 0;
        if (symmetric()) {
          symmetry_.canonicalize(succ, moved);
          perm = perms_.intern(moved);
        }
        std::uint64_t bits = atomBits(succ);
        for (std::uint32_t target : ba_.states[q].successors) {
          if (!labelHolds(target, bits)) continue;
          const std::uint64_t word = scheduler_ != nullptr ? target | turns[k] << 32 : target;
          std::uint32_t index = insert(succ, word, static_cast<std::uint32_t>(i), vias[k], packed);
          edges_.push_back({index, vias[k]});
          if (symmetric()) edgePerms_.push_back(perm);
        }
      }
      if (store_.size() + statesBefore >= limits.maxStates && i + 1 < store_.size()) {
        why = "--max-states " + std::to_string(limits.maxStates) + " reached";
        return false;
      }
      if (bytes() >= limits.maxMemoryBytes && i + 1 < store_.size()) {
        why = "--max-memory " + std::to_string(limits.maxMemoryBytes >> 20) + " MiB reached";
        return false;
      }
      // The clock is read every 256 states: a large team's state can take a millisecond to expand.
      if (limits.onProgress && (i & 0xffu) == 0) {
        double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        if (elapsed >= nextReport) {
          limits.onProgress({statesBefore + store_.size(), edges_.size(), bytes(), 0, elapsed});
          nextReport = elapsed + 1.0;
        }
      }
    }
    edgeStart_.push_back(edges_.size());
    return true;
  }

  // After a limit stopped explore(): the states not expanded get no edges, so that the graph is
  // the part explored. A fair cycle of it is one of the whole product, since whether a loop is
  // fair and accepting depends on its own states and edges only (and an expanded state has all
  // its edges); a frontier state, without edges, lies on no cycle.
  void closeFrontier() {
    while (edgeStart_.size() < store_.size() + 1) edgeStart_.push_back(edges_.size());
  }

  [[nodiscard]] std::size_t size() const { return store_.size(); }
  [[nodiscard]] std::size_t edgeCount() const { return edges_.size(); }
  [[nodiscard]] std::uint64_t bytes() const {
    return store_.bytes() + edges_.capacity() * sizeof(Edge) + edgeStart_.capacity() * 8 + edgePerms_.capacity() * 4;
  }
  [[nodiscard]] std::uint32_t automatonState(std::size_t n) const {
    return static_cast<std::uint32_t>(store_.state(n)[cm_.layout().words()]);
  }
  [[nodiscard]] std::uint64_t acceptance(std::size_t n) const { return ba_.states[automatonState(n)].acceptance; }
  [[nodiscard]] const Edge* edgesBegin(std::size_t n) const { return edges_.data() + edgeStart_[n]; }
  [[nodiscard]] const Edge* edgesEnd(std::size_t n) const { return edges_.data() + edgeStart_[n + 1]; }
  [[nodiscard]] const StateStore& store() const { return store_; }
  [[nodiscard]] bool symmetric() const { return !symmetry_.empty(); }
  [[nodiscard]] const Symmetry& symmetry() const { return symmetry_; }
  // The permutation that took the target of edge e to its representative.
  [[nodiscard]] std::uint32_t permOf(const Edge* e) const { return edgePerms_[static_cast<std::size_t>(e - edges_.data())]; }
  [[nodiscard]] const PermutationTable& perms() const { return perms_; }

 private:
  std::uint32_t insert(const Value* v, std::uint64_t q, std::uint32_t parent, std::uint32_t via, std::vector<std::uint64_t>& packed) {
    cm_.layout().pack(v, packed.data());
    packed.back() = q;
    return store_.insert(packed.data(), parent, via).first;
  }

  const CompiledModel& cm_;
  const Buchi& ba_;
  StateStore store_;
  std::vector<Program> atoms_;

  // Which atoms hold in a model state (bit k: Buchi::atoms[k]); a label is then two mask tests.
  [[nodiscard]] std::uint64_t atomBits(const Value* v) const {
    std::uint64_t bits = 0;
    for (std::size_t k = 0; k < atoms_.size(); ++k) bits |= static_cast<std::uint64_t>(atoms_[k].eval(v) != 0) << k;
    return bits;
  }
  [[nodiscard]] bool labelHolds(std::uint32_t q, std::uint64_t bits) const {
    const BuchiState& s = ba_.states[q];
    return (bits & s.mustHold) == s.mustHold && (bits & s.mustFail) == 0;
  }
  std::vector<Value> start_;
  std::function<bool(const Value*)> region_;
  const Fairness* scheduler_ = nullptr;
  std::vector<char> barred_;
  const Sensing* sensing_ = nullptr;
  std::vector<std::int8_t> world_;
  bool pruneEqual_ = false, outOfRangeIsNoStep_ = false;
  std::vector<std::uint64_t> edgeStart_;
  std::vector<Edge> edges_;
  Symmetry symmetry_;
  PermutationTable perms_;
  std::vector<std::uint32_t> edgePerms_;  // per edge, with symmetry
};

}  // namespace semo::checker::detail
