#include "semo/checker/liveness_search.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <deque>
#include <stdexcept>

#include "semo/checker/buchi.hpp"
#include "semo/checker/compiled_model.hpp"
#include "state_store.hpp"

namespace semo::checker {

namespace {

using detail::kNoParent;
using detail::StateStore;
using Clock = std::chrono::steady_clock;

// Time passing with no step: allowed where no fair rule is enabled (where one is, staying for ever
// would be unfair to it, and staying a while changes nothing the properties can see). So a run may
// end in a state where only unfair rules (loss, crash, the environment) could move.
constexpr std::uint32_t kStutter = 0xffffffu;

struct Edge {
  std::uint32_t target;
  std::uint32_t via;  // rule << 8 | branch, or kStutter << 8
};

std::uint32_t ruleOf(std::uint32_t via) { return via >> 8; }

// The product of the model with a Büchi automaton, explored breadth-first and kept as a graph.
class Product {
 public:
  Product(const CompiledModel& cm, const Buchi& ba) : cm_(cm), ba_(ba), store_(cm.layout().words() + 1) {
    for (const ir::Expr& atom : ba.atoms) atoms_.emplace_back(atom);
  }

  // False when a limit stopped the exploration (then `why` says which).
  bool explore(const SearchLimits& limits, Clock::time_point start, std::uint64_t statesBefore, std::string& why) {
    const StateLayout& layout = cm_.layout();
    std::vector<Value> values = cm_.initialValues(), next(values.size());
    std::vector<std::uint64_t> packed(layout.words() + 1);
    std::uint64_t initialBits = atomBits(values.data());
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      if (ba_.states[q].initial && labelHolds(q, initialBits)) insert(values.data(), q, kNoParent, 0, packed);
    }
    std::vector<std::uint32_t> candidates;
    // The model successors of the state being expanded: their rules, and their values back to back.
    std::vector<std::uint32_t> vias;
    std::vector<Value> successorValues;
    const std::size_t width = values.size();
    double nextReport = 1.0;
    for (std::size_t i = 0; i < store_.size(); ++i) {
      edgeStart_.push_back(edges_.size());
      layout.unpack(store_.state(i), values.data());
      std::uint32_t q = automatonState(i);
      vias.clear();
      successorValues.clear();
      cm_.candidateRules(values.data(), candidates);
      bool fairEnabled = false;
      for (std::uint32_t r : candidates) {
        const CompiledRule& rule = cm_.rules()[r];
        if (rule.guard.eval(values.data()) == 0) continue;
        fairEnabled = fairEnabled || cm_.model().rules[r].weaklyFair || cm_.model().rules[r].stronglyFair;
        for (std::size_t b = 0; b < rule.branches.size(); ++b) {
          if (!cm_.step(rule.branches[b], values.data(), next.data())) {
            why = "an update left a variable's declared range (run 'check' for the trace)";
            return false;
          }
          vias.push_back(r << 8 | static_cast<std::uint32_t>(b));
          successorValues.insert(successorValues.end(), next.begin(), next.end());
        }
      }
      if (!fairEnabled) {
        vias.push_back(kStutter << 8);
        successorValues.insert(successorValues.end(), values.begin(), values.end());
      }
      for (std::size_t k = 0; k < vias.size(); ++k) {
        const Value* succ = successorValues.data() + k * width;
        std::uint64_t bits = atomBits(succ);
        for (std::uint32_t target : ba_.states[q].successors) {
          if (!labelHolds(target, bits)) continue;
          std::uint32_t index = insert(succ, target, static_cast<std::uint32_t>(i), vias[k], packed);
          edges_.push_back({index, vias[k]});
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
      if (limits.onProgress && (i & 0x3fffu) == 0) {
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

  [[nodiscard]] std::size_t size() const { return store_.size(); }
  [[nodiscard]] std::size_t edgeCount() const { return edges_.size(); }
  [[nodiscard]] std::uint64_t bytes() const { return store_.bytes() + edges_.capacity() * sizeof(Edge) + edgeStart_.capacity() * 8; }
  [[nodiscard]] std::uint32_t automatonState(std::size_t n) const {
    return static_cast<std::uint32_t>(store_.state(n)[cm_.layout().words()]);
  }
  [[nodiscard]] std::uint64_t acceptance(std::size_t n) const { return ba_.states[automatonState(n)].acceptance; }
  [[nodiscard]] const Edge* edgesBegin(std::size_t n) const { return edges_.data() + edgeStart_[n]; }
  [[nodiscard]] const Edge* edgesEnd(std::size_t n) const { return edges_.data() + edgeStart_[n + 1]; }
  [[nodiscard]] const StateStore& store() const { return store_; }

 private:
  std::uint32_t insert(const Value* v, std::uint32_t q, std::uint32_t parent, std::uint32_t via, std::vector<std::uint64_t>& packed) {
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
  std::vector<std::uint64_t> edgeStart_;
  std::vector<Edge> edges_;
};

// Searches the product for a fair accepting cycle: Tarjan's algorithm for the strongly connected
// components, then, per component, the acceptance sets and the fairness of every rule; a strongly
// fair rule that is enabled in the component but never taken in it removes the states where it is
// enabled, and the rest is searched again (as in Emerson and Lei's algorithm).
class FairCycleSearch {
 public:
  FairCycleSearch(const CompiledModel& cm, const Buchi& ba, const Product& p)
      : cm_(cm), ba_(ba), p_(p), index_(p.size(), kUnvisited), low_(p.size(), 0), member_(p.size(), 0),
        enabledCount_(cm.rules().size(), 0), taken_(cm.rules().size(), 0) {
    for (std::uint32_t r = 0; r < cm.rules().size(); ++r) {
      if (cm.model().rules[r].weaklyFair || cm.model().rules[r].stronglyFair) fairRules_.push_back(r);
    }
  }

  // A fair accepting strongly connected set of product states, or empty. Of several, the one that
  // a breadth-first prefix reaches first, for the shortest way into the loop.
  std::vector<std::uint32_t> find() {
    std::vector<std::uint32_t> all(p_.size());
    for (std::uint32_t n = 0; n < all.size(); ++n) all[n] = n;
    std::uint32_t stamp = ++stamp_;
    for (std::uint32_t n : all) member_[n] = stamp;
    std::vector<std::vector<std::uint32_t>> candidates = components(all, stamp);
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
      return *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end());
    });
    for (std::vector<std::uint32_t>& component : candidates) {
      if (analyze(component)) return found_;
    }
    return {};
  }

  // The rules enabled in product state n.
  void enabled(std::uint32_t n, std::vector<std::uint32_t>& out) {
    values_.resize(cm_.layout().variables());
    cm_.layout().unpack(p_.store().state(n), values_.data());
    cm_.candidateRules(values_.data(), candidates_);
    out.clear();
    for (std::uint32_t r : candidates_) {
      if (cm_.rules()[r].guard.eval(values_.data()) != 0) out.push_back(r);
    }
  }

  [[nodiscard]] const std::vector<std::uint32_t>& fairRules() const { return fairRules_; }

 private:
  static constexpr std::uint32_t kUnvisited = 0xffffffffu;

  bool hasSelfEdge(std::uint32_t n) const {
    for (const Edge* e = p_.edgesBegin(n); e != p_.edgesEnd(n); ++e) {
      if (e->target == n) return true;
    }
    return false;
  }

  // The strongly connected components of the states marked `stamp` (iterative Tarjan), keeping
  // only those that can hold a cycle.
  std::vector<std::vector<std::uint32_t>> components(const std::vector<std::uint32_t>& nodes, std::uint32_t stamp) {
    std::vector<std::vector<std::uint32_t>> out;
    std::vector<std::uint32_t> stack;
    std::vector<char> onStack;
    struct Frame {
      std::uint32_t node;
      const Edge* next;
    };
    std::vector<Frame> call;
    std::uint32_t counter = 0;
    std::vector<std::uint32_t> touched;
    std::vector<char>& on = onStack_;
    if (on.size() < p_.size()) on.assign(p_.size(), 0);
    for (std::uint32_t root : nodes) {
      if (index_[root] != kUnvisited) continue;
      call.push_back({root, p_.edgesBegin(root)});
      index_[root] = low_[root] = counter++;
      touched.push_back(root);
      stack.push_back(root);
      on[root] = 1;
      while (!call.empty()) {
        Frame& f = call.back();
        if (f.next != p_.edgesEnd(f.node)) {
          std::uint32_t w = (f.next++)->target;
          if (member_[w] != stamp) continue;
          if (index_[w] == kUnvisited) {
            index_[w] = low_[w] = counter++;
            touched.push_back(w);
            stack.push_back(w);
            on[w] = 1;
            call.push_back({w, p_.edgesBegin(w)});
          } else if (on[w]) {
            low_[f.node] = std::min(low_[f.node], index_[w]);
          }
          continue;
        }
        std::uint32_t v = f.node;
        call.pop_back();
        if (!call.empty()) low_[call.back().node] = std::min(low_[call.back().node], low_[v]);
        if (low_[v] != index_[v]) continue;
        std::vector<std::uint32_t> component;
        std::uint32_t w;
        do {
          w = stack.back();
          stack.pop_back();
          on[w] = 0;
          component.push_back(w);
        } while (w != v);
        if (component.size() > 1 || hasSelfEdge(v)) out.push_back(std::move(component));
      }
    }
    for (std::uint32_t n : touched) index_[n] = kUnvisited;
    return out;
  }

  bool analyze(const std::vector<std::uint32_t>& component) {
    std::uint32_t stamp = ++stamp_;
    std::uint64_t acc = 0;
    for (std::uint32_t n : component) {
      member_[n] = stamp;
      acc |= p_.acceptance(n);
    }
    if ((acc & ba_.allSets()) != ba_.allSets()) return false;
    for (std::uint32_t r : fairRules_) enabledCount_[r] = 0, taken_[r] = 0;
    std::vector<std::uint32_t> on;
    for (std::uint32_t n : component) {
      enabled(n, on);
      for (std::uint32_t r : on) ++enabledCount_[r];
      for (const Edge* e = p_.edgesBegin(n); e != p_.edgesEnd(n); ++e) {
        if (member_[e->target] == stamp && ruleOf(e->via) != kStutter) taken_[ruleOf(e->via)] = 1;
      }
    }
    std::vector<std::uint32_t> unfairlyIgnored;  // strongly fair, enabled here, never taken here
    for (std::uint32_t r : fairRules_) {
      if (taken_[r] || enabledCount_[r] == 0) continue;
      // Weak fairness: enabled in every state of the component and never taken -> no fair cycle.
      if (enabledCount_[r] == component.size()) return false;
      if (cm_.model().rules[r].stronglyFair) unfairlyIgnored.push_back(r);
    }
    if (unfairlyIgnored.empty()) {
      found_ = component;
      return true;
    }
    std::vector<std::uint32_t> rest;
    std::uint32_t restStamp = ++stamp_;
    for (std::uint32_t n : component) {
      enabled(n, on);
      bool drop = std::any_of(on.begin(), on.end(), [&](std::uint32_t r) {
        return std::find(unfairlyIgnored.begin(), unfairlyIgnored.end(), r) != unfairlyIgnored.end();
      });
      if (!drop) {
        rest.push_back(n);
        member_[n] = restStamp;
      }
    }
    for (std::vector<std::uint32_t>& sub : components(rest, restStamp)) {
      if (analyze(sub)) return true;
    }
    return false;
  }

  const CompiledModel& cm_;
  const Buchi& ba_;
  const Product& p_;
  std::vector<std::uint32_t> index_, low_, member_;
  std::vector<char> onStack_;
  std::vector<std::uint32_t> enabledCount_;
  std::vector<char> taken_;
  std::vector<std::uint32_t> fairRules_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> found_;
  std::vector<Value> values_;
  std::vector<std::uint32_t> candidates_;
};

// A loop through the fair accepting set `cycleSet` that visits every acceptance set and treats
// every fair rule fairly, starting and ending at `entry`: greedy, to the nearest state or step
// that discharges an obligation still open.
std::vector<Edge> fairLoop(const CompiledModel& cm, const Buchi& ba, const Product& p, FairCycleSearch& search,
                           const std::vector<std::uint32_t>& cycleSet, std::uint32_t entry) {
  std::vector<char> inSet(p.size(), 0);
  for (std::uint32_t n : cycleSet) inSet[n] = 1;
  std::uint64_t accPending = ba.allSets();
  std::vector<std::uint32_t> on;
  // Fair rules enabled somewhere here must be treated fairly on the loop.
  std::vector<char> pending(cm.rules().size(), 0);
  for (std::uint32_t n : cycleSet) {
    search.enabled(n, on);
    for (std::uint32_t r : on) pending[r] = 1;
  }
  std::vector<std::uint32_t> open;
  std::vector<char> fair(cm.rules().size(), 0);
  for (std::uint32_t r : search.fairRules()) fair[r] = 1;
  for (std::uint32_t r = 0; r < pending.size(); ++r) {
    pending[r] = pending[r] && fair[r];
    if (pending[r]) open.push_back(r);
  }
  auto nodeDischarges = [&](std::uint32_t n, bool apply) {
    bool any = (p.acceptance(n) & accPending) != 0;
    if (apply) accPending &= ~p.acceptance(n);
    search.enabled(n, on);
    for (std::uint32_t r : open) {
      if (!pending[r] || cm.model().rules[r].stronglyFair) continue;
      if (std::find(on.begin(), on.end(), r) == on.end()) {
        any = true;
        if (apply) pending[r] = 0;
      }
    }
    return any;
  };
  auto edgeDischarges = [&](std::uint32_t via) {
    return ruleOf(via) != kStutter && pending[ruleOf(via)] != 0;
  };
  auto anyOpen = [&] {
    return accPending != 0 || std::any_of(open.begin(), open.end(), [&](std::uint32_t r) { return pending[r] != 0; });
  };

  std::vector<Edge> loop;
  std::uint32_t current = entry;
  nodeDischarges(current, true);
  // Breadth-first from `current` to the first step that satisfies `goal(edge)`; appends the path.
  auto walk = [&](auto goal) {
    std::deque<std::uint32_t> queue{current};
    std::vector<std::pair<std::uint32_t, Edge>> reached;  // (from, edge), in discovery order
    std::vector<std::int64_t> cameFrom(p.size(), -1);    // index into reached
    std::vector<char> seen(p.size(), 0);
    seen[current] = 1;
    while (!queue.empty()) {
      std::uint32_t u = queue.front();
      queue.pop_front();
      for (const Edge* e = p.edgesBegin(u); e != p.edgesEnd(u); ++e) {
        if (!inSet[e->target]) continue;
        if (goal(*e)) {
          std::vector<Edge> path{*e};
          for (std::uint32_t v = u; v != current;) {
            const auto& [from, edge] = reached[static_cast<std::size_t>(cameFrom[v])];
            path.push_back(edge);
            v = from;
          }
          std::reverse(path.begin(), path.end());
          for (const Edge& step : path) {
            if (ruleOf(step.via) != kStutter) pending[ruleOf(step.via)] = 0;
            nodeDischarges(step.target, true);
            loop.push_back(step);
          }
          current = path.back().target;
          return;
        }
        if (seen[e->target]) continue;
        seen[e->target] = 1;
        cameFrom[e->target] = static_cast<std::int64_t>(reached.size());
        reached.push_back({u, *e});
        queue.push_back(e->target);
      }
    }
    throw std::logic_error("fair loop: an obligation cannot be met inside its component");
  };
  while (anyOpen()) {
    walk([&](const Edge& e) { return edgeDischarges(e.via) || nodeDischarges(e.target, false); });
  }
  if (current != entry || loop.empty()) walk([&](const Edge& e) { return e.target == entry; });
  return loop;
}

Trace lasso(const CompiledModel& cm, const Product& p, std::uint32_t entry, const std::vector<Edge>& loop) {
  Trace t = detail::traceTo(cm, p.store(), entry);
  t.loopStart = t.steps.size();
  const StateLayout& layout = cm.layout();
  std::vector<Value> before(layout.variables()), after(layout.variables());
  layout.unpack(p.store().state(entry), before.data());
  for (const Edge& e : loop) {
    if (ruleOf(e.via) == kStutter) continue;  // the run has ended; it stays in its last state
    layout.unpack(p.store().state(e.target), after.data());
    Step step{ruleOf(e.via), e.via & 0xffu, {}};
    for (ir::VarId v = 0; v < after.size(); ++v) {
      if (before[v] != after[v]) step.changes.push_back({v, before[v], after[v]});
    }
    t.steps.push_back(std::move(step));
    before.swap(after);
  }
  return t;
}

}  // namespace

namespace {

struct Outcome {
  PropertyResult property;
  std::uint64_t states = 0, transitions = 0;
  bool whole = true;
  std::string why;
};

Outcome checkProperty(const CompiledModel& cm, const ir::Property& prop, const SearchLimits& limits, Clock::time_point start) {
  Outcome out{{prop.name, prop.origin, Verdict::Unknown, {}}, 0, 0, true, {}};
  Buchi ba;
  try {
    ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, prop.formula));
  } catch (const std::length_error& e) {
    out.whole = false;
    out.why = prop.name + ": " + e.what();
    return out;
  }
  Product product(cm, ba);
  out.whole = product.explore(limits, start, 0, out.why);
  out.states = product.size();
  out.transitions = product.edgeCount();
  if (!out.whole) return out;
  FairCycleSearch search(cm, ba, product);
  std::vector<std::uint32_t> cycle = search.find();
  if (cycle.empty()) {
    out.property.verdict = Verdict::Proven;
    return out;
  }
  std::uint32_t entry = *std::min_element(cycle.begin(), cycle.end());  // breadth-first: the shortest way in
  Trace t = lasso(cm, product, entry, fairLoop(cm, ba, product, search, cycle, entry));
  t.property = prop.name;
  t.kind = "lasso";
  out.property.verdict = Verdict::Violated;
  out.property.counterexample = std::move(t);
  return out;
}

}  // namespace

LivenessResult checkLiveness(const ir::Model& model, const SearchLimits& limits) {
  auto start = Clock::now();
  CompiledModel cm(model);
  LivenessResult result;
  // The properties' products are independent: up to `threads` are searched at once, each within
  // --max-states and its share of --max-memory; only the first worker reports progress.
  const std::size_t n = model.properties.size();
  const std::size_t workers = std::min<std::size_t>(n, std::max(1u, limits.threads));
  std::vector<Outcome> outcomes(n);
  std::atomic<std::size_t> next{0};
  auto work = [&](std::size_t worker) {
    SearchLimits mine = limits;
    mine.maxMemoryBytes = limits.maxMemoryBytes / std::max<std::size_t>(1, workers);
    if (worker != 0) mine.onProgress = nullptr;
    for (std::size_t k = next++; k < n; k = next++) outcomes[k] = checkProperty(cm, model.properties[k], mine, start);
  };
  std::vector<std::thread> helpers;
  for (std::size_t w = 1; w < workers; ++w) helpers.emplace_back(work, w);
  work(0);
  for (std::thread& h : helpers) h.join();
  // A product that outgrew its share of the memory gets the whole budget, alone.
  if (workers > 1) {
    for (std::size_t k = 0; k < n; ++k) {
      if (!outcomes[k].whole && outcomes[k].why.rfind("--max-memory", 0) == 0) {
        outcomes[k] = checkProperty(cm, model.properties[k], limits, start);
      }
    }
  }
  for (Outcome& o : outcomes) {
    result.states += o.states;
    result.transitions += o.transitions;
    if (!o.whole) {
      result.complete = false;
      if (result.limitReached.empty()) result.limitReached = o.why;
    }
    result.properties.push_back(std::move(o.property));
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace semo::checker
