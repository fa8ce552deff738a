#include "semo/checker/liveness_search.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <deque>
#include <stdexcept>
#include <unordered_set>

#include "liveness_product.hpp"

namespace semo::checker {

namespace {

using detail::Clock;
using detail::Edge;
using detail::compose;
using detail::inverse;
using detail::keyOf;
using detail::kStutter;
using detail::Permutation;
using detail::PermutationTable;
using detail::Product;
using detail::ruleOf;

// Searches the product for a fair accepting cycle: Tarjan's algorithm for the strongly connected
// components, then, per component, the acceptance sets and the fairness of every rule; a strongly
// fair rule that is enabled in the component but never taken in it removes the states where it is
// enabled, and the rest is searched again (as in Emerson and Lei's algorithm).
class FairCycleSearch {
 public:
  FairCycleSearch(const CompiledModel& cm, const Buchi& ba, const Product& p)
      : cm_(cm), ba_(ba), p_(p), index_(p.size(), kUnvisited), low_(p.size(), 0), member_(p.size(), 0),
        enabledCount_(cm.rules().size(), 0), taken_(cm.rules().size(), 0), everywhere_(cm.rules().size(), 0),
        somewhere_(cm.rules().size(), 0), orbitTaken_(cm.rules().size(), 0), ignored_(cm.rules().size(), 0),
        orbit_(cm.rules().size(), 0), local_(p.symmetric() ? p.size() : 0, 0) {
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
    if (p_.symmetric()) liftComponent(component, stamp);
    for (std::uint32_t r : fairRules_) enabledCount_[r] = 0, taken_[r] = 0;
    std::vector<std::uint32_t> on;
    for (std::size_t k = 0; k < component.size(); ++k) {
      std::uint32_t n = component[k];
      enabled(n, on);
      for (std::uint32_t r : on) ++enabledCount_[absolute(k, r)];
      for (const Edge* e = p_.edgesBegin(n); e != p_.edgesEnd(n); ++e) {
        if (member_[e->target] == stamp && ruleOf(e->via) != kStutter) taken_[absolute(k, ruleOf(e->via))] = 1;
      }
    }
    // Per orbit of fair rules (a single rule without symmetry): enabled in every state, in some,
    // taken somewhere.
    for (std::uint32_t r : fairRules_) everywhere_[r] = 1, somewhere_[r] = 0, orbitTaken_[r] = 0;
    for (std::uint32_t r : fairRules_) {
      std::uint32_t o = orbitOf(r);
      everywhere_[o] = everywhere_[o] && enabledCount_[r] == component.size();
      somewhere_[o] = somewhere_[o] || enabledCount_[r] != 0;
      orbitTaken_[o] = orbitTaken_[o] || taken_[r];
    }
    bool anyIgnored = false;  // strongly fair rules enabled here and never taken here
    for (std::uint32_t r : fairRules_) {
      std::uint32_t o = orbitOf(r);
      if (orbitTaken_[o] || !somewhere_[o]) continue;
      // Weak fairness: enabled in every state of the component and never taken -> no fair cycle.
      if (everywhere_[o]) return false;
      if (cm_.model().rules[r].stronglyFair) ignored_[r] = 1, anyIgnored = true;
    }
    if (!anyIgnored) {
      found_ = component;
      return true;
    }
    std::vector<std::uint32_t> rest;
    std::uint32_t restStamp = ++stamp_;
    for (std::size_t k = 0; k < component.size(); ++k) {
      std::uint32_t n = component[k];
      enabled(n, on);
      bool drop = std::any_of(on.begin(), on.end(), [&](std::uint32_t r) { return ignored_[absolute(k, r)] != 0; });
      if (!drop) {
        rest.push_back(n);
        member_[n] = restStamp;
      }
    }
    for (std::uint32_t r : fairRules_) ignored_[r] = 0;
    for (std::vector<std::uint32_t>& sub : components(rest, restStamp)) {
      if (analyze(sub)) return true;
    }
    return false;
  }

  // The concrete states a component of the quotient stands for (see checkLiveness's comment): the
  // k-th state of the component is frame[k] applied to its representative, where frame[0] is the
  // identity and an edge u -> w that canonicalised with p gives frame[w] = frame[u] p^-1. Edges
  // whose frames disagree close a cycle that permutes the robots; those permutations generate the
  // group G whose orbits on the rules are what fairness sees: a rule of the concrete component is
  // enabled everywhere only if its whole orbit is, in every frame.
  void liftComponent(const std::vector<std::uint32_t>& component, std::uint32_t stamp) {
    const PermutationTable& perms = p_.perms();
    std::vector<Permutation> frame(component.size());
    std::vector<char> placed(component.size(), 0);
    for (std::size_t k = 0; k < component.size(); ++k) local_[component[k]] = static_cast<std::uint32_t>(k);
    frame[0] = perms[0];
    placed[0] = 1;
    std::vector<std::uint32_t> queue{0};
    for (std::size_t head = 0; head < queue.size(); ++head) {
      std::uint32_t u = queue[head];
      for (const Edge* e = p_.edgesBegin(component[u]); e != p_.edgesEnd(component[u]); ++e) {
        if (member_[e->target] != stamp) continue;
        std::uint32_t w = local_[e->target];
        if (placed[w]) continue;
        placed[w] = 1;
        frame[w] = compose(frame[u], perms.inverseOf(p_.permOf(e)));
        queue.push_back(w);
      }
    }
    std::unordered_set<std::string> generators;
    for (std::size_t u = 0; u < component.size(); ++u) {
      for (const Edge* e = p_.edgesBegin(component[u]); e != p_.edgesEnd(component[u]); ++e) {
        if (member_[e->target] != stamp) continue;
        const Permutation& there = frame[local_[e->target]];
        Permutation arrived = compose(frame[u], perms.inverseOf(p_.permOf(e)));
        if (arrived != there) generators.insert(keyOf(compose(arrived, inverse(there))));
      }
    }
    frameSwaps_.resize(component.size());
    for (std::size_t k = 0; k < component.size(); ++k) frameSwaps_[k] = p_.symmetry().decompose(frame[k]);
    for (std::uint32_t r : fairRules_) orbit_[r] = r;
    for (const std::string& key : generators) {
      Permutation g(key.size() / sizeof(std::uint16_t));
      std::copy(key.begin(), key.end(), reinterpret_cast<char*>(g.data()));
      Symmetry::Swaps swaps = p_.symmetry().decompose(g);
      for (std::uint32_t r : fairRules_) {
        std::uint32_t a = orbitOf(r), b = orbitOf(p_.symmetry().image(r, swaps));
        if (a != b) orbit_[std::max(a, b)] = std::min(a, b);
      }
    }
  }

  // Rule r of the k-th state of the component under analysis, named in the frame of the first.
  [[nodiscard]] std::uint32_t absolute(std::size_t k, std::uint32_t r) const {
    return p_.symmetric() ? p_.symmetry().image(r, frameSwaps_[k]) : r;
  }
  std::uint32_t orbitOf(std::uint32_t r) {
    if (!p_.symmetric()) return r;
    while (orbit_[r] != r) r = orbit_[r] = orbit_[orbit_[r]];
    return r;
  }

  const CompiledModel& cm_;
  const Buchi& ba_;
  const Product& p_;
  std::vector<std::uint32_t> index_, low_, member_;
  std::vector<char> onStack_;
  std::vector<std::uint32_t> enabledCount_;
  std::vector<char> taken_, everywhere_, somewhere_, orbitTaken_, ignored_;
  std::vector<std::uint32_t> orbit_, local_;        // union-find over the rules; a state's place in its component
  std::vector<Symmetry::Swaps> frameSwaps_;
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
  bool reduced = false;  // searched up to symmetry
  std::string note;
};

// With `symmetry` (non-null only when every atom of the property is invariant), the product of
// the quotient is searched; it decides the property exactly (see FairCycleSearch::liftComponent).
// A violation found there is searched again without symmetry for a concrete lasso.
Outcome checkProperty(const CompiledModel& cm, const ir::Property& prop, const SearchLimits& limits, Clock::time_point start,
                      const Symmetry* symmetry) {
  Outcome out{{prop.name, prop.origin, Verdict::Unknown, {}}, 0, 0, true, {}, false, {}};
  Buchi ba;
  try {
    ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, prop.formula));
  } catch (const std::length_error& e) {
    out.whole = false;
    out.why = prop.name + ": " + e.what();
    return out;
  }
  if (symmetry != nullptr &&
      !std::all_of(ba.atoms.begin(), ba.atoms.end(), [&](const ir::Expr& a) { return symmetry->invariant(a); })) {
    symmetry = nullptr;
  }
  out.reduced = symmetry != nullptr;
  Product product(cm, ba, symmetry);
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
  if (symmetry != nullptr) {
    Outcome concrete = checkProperty(cm, prop, limits, start, nullptr);
    concrete.states += out.states;
    concrete.transitions += out.transitions;
    concrete.reduced = true;
    if (concrete.property.verdict == Verdict::Violated) return concrete;
    // The quotient's verdict is exact; only the lasso is missing.
    out.property.verdict = Verdict::Violated;
    out.note = "violated up to symmetry; no concrete lasso: ";
    out.note += concrete.whole ? "none found" : concrete.why;
    out.states = concrete.states;
    out.transitions = concrete.transitions;
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
  const Symmetry symmetry = limits.symmetry ? Symmetry::find(model) : Symmetry();
  const Symmetry* reduce = symmetry.empty() ? nullptr : &symmetry;
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
    for (std::size_t k = next++; k < n; k = next++) outcomes[k] = checkProperty(cm, model.properties[k], mine, start, reduce);
  };
  std::vector<std::thread> helpers;
  for (std::size_t w = 1; w < workers; ++w) helpers.emplace_back(work, w);
  work(0);
  for (std::thread& h : helpers) h.join();
  // A product that outgrew its share of the memory gets the whole budget, alone.
  if (workers > 1) {
    for (std::size_t k = 0; k < n; ++k) {
      if (!outcomes[k].whole && outcomes[k].why.rfind("--max-memory", 0) == 0) {
        outcomes[k] = checkProperty(cm, model.properties[k], limits, start, reduce);
      }
    }
  }
  for (Outcome& o : outcomes) {
    result.states += o.states;
    result.transitions += o.transitions;
    result.reducedProperties += o.reduced ? 1 : 0;
    if (!o.whole) {
      result.complete = false;
      if (result.limitReached.empty()) result.limitReached = o.why;
    }
    result.properties.push_back(std::move(o.property));
    result.notes.push_back(std::move(o.note));
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace semo::checker
