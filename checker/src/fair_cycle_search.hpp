#pragma once
// The search for a fair accepting cycle in a product (liveness_product.hpp), the fair loop through
// the cycle found, and the lasso it makes: shared by the liveness search (liveness_search.cpp) and
// the search of a slice lasso's region on the whole model (sliced_liveness.cpp).
#include <algorithm>
#include <deque>
#include <stdexcept>
#include <unordered_set>
#include <vector>

#include "liveness_product.hpp"
#include "semo/checker/fairness.hpp"

namespace semo::checker::detail {

// Searches the product for a fair accepting cycle: Tarjan's algorithm for the strongly connected
// components, then, per component, the acceptance sets and the fairness of every group of rules
// (fairness.hpp); a strongly fair group that is enabled in the component but never taken in it
// removes the states where it is enabled, and the rest is searched again (as in Emerson and Lei's
// algorithm). For a property checked on a settling world (ir::Property::settled), the cycle
// decides each sensed condition one way only: a component whose steps decide one both ways is
// searched again twice, without the steps that decide it one way, then without the others.
class FairCycleSearch {
 public:
  FairCycleSearch(const CompiledModel& cm, const Buchi& ba, const Product& p, bool settled)
      : cm_(cm), ba_(ba), p_(p), fairness_(Fairness::of(cm.model())), sensing_(Sensing::in(cm.model())), settled_(settled),
        allowed_(sensing_.points, -1), index_(p.size(), kUnvisited),
        low_(p.size(), 0), member_(p.size(), 0), enabledCount_(fairness_.groups(), 0), seenIn_(fairness_.groups(), 0),
        taken_(fairness_.groups(), 0), everywhere_(fairness_.groups(), 0), somewhere_(fairness_.groups(), 0),
        orbitTaken_(fairness_.groups(), 0), ignored_(fairness_.groups(), 0), orbit_(fairness_.groups(), 0),
        local_(p.symmetric() ? p.size() : 0, 0) {
  }

  // Whether a cycle may use the edge: on a settling world, its sensed decisions must be the ones
  // the cycle keeps (after find(): those of the cycle found).
  [[nodiscard]] bool usable(const Edge& e) const {
    return !settled_ || ruleOf(e.via) == kStutter || sensing_.agrees(ruleOf(e.via), allowed_);
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

  [[nodiscard]] const Fairness& fairness() const { return fairness_; }

 private:
  static constexpr std::uint32_t kUnvisited = 0xffffffffu;

  bool hasSelfEdge(std::uint32_t n) const {
    for (const Edge* e = p_.edgesBegin(n); e != p_.edgesEnd(n); ++e) {
      if (e->target == n && usable(*e)) return true;
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
          const Edge& e = *f.next++;
          std::uint32_t w = e.target;
          if (member_[w] != stamp || !usable(e)) continue;
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

  // When the component's steps decide a sensed condition both ways, searches it again with each way
  // forbidden in turn (found_ is then set or empty) and returns true; false when none is.
  bool splitOnSensing(const std::vector<std::uint32_t>& component, std::uint32_t stamp) {
    std::vector<std::int8_t> seen(sensing_.points, 0);  // bit 1: decided false, bit 2: decided true
    for (std::uint32_t n : component) {
      for (const Edge* e = p_.edgesBegin(n); e != p_.edgesEnd(n); ++e) {
        if (member_[e->target] != stamp || !usable(*e) || ruleOf(e->via) == kStutter) continue;
        for (const Sensing::Decision& d : sensing_.of[ruleOf(e->via)]) {
          seen[d.point] = static_cast<std::int8_t>(seen[d.point] | (d.holds ? 2 : 1));
          if (seen[d.point] != 3) continue;
          found_.clear();
          for (std::int8_t way : {0, 1}) {
            allowed_[d.point] = way;
            std::uint32_t restStamp = ++stamp_;
            for (std::uint32_t m : component) member_[m] = restStamp;
            for (std::vector<std::uint32_t>& sub : components(component, restStamp)) {
              if (analyze(sub)) return true;  // allowed_ stays as the cycle found needs it
            }
          }
          allowed_[d.point] = -1;
          return true;
        }
      }
    }
    return false;
  }

  bool analyze(const std::vector<std::uint32_t>& component) {
    std::uint32_t stamp = ++stamp_;
    std::uint64_t acc = 0;
    for (std::uint32_t n : component) {
      member_[n] = stamp;
      acc |= p_.acceptance(n);
    }
    if ((acc & ba_.allSets()) != ba_.allSets()) return false;
    if (settled_ && splitOnSensing(component, stamp)) return found_.size() != 0;
    if (p_.symmetric()) liftComponent(component, stamp);
    const std::size_t groups = fairness_.groups();
    std::fill(enabledCount_.begin(), enabledCount_.end(), 0);
    std::fill(taken_.begin(), taken_.end(), 0);
    std::vector<std::uint32_t> on;
    for (std::size_t k = 0; k < component.size(); ++k) {
      std::uint32_t n = component[k];
      enabled(n, on);
      ++visit_;
      for (std::uint32_t r : on) {
        std::uint32_t g = fairness_.groupOf[absolute(k, r)];
        if (g == Fairness::kNone || seenIn_[g] == visit_) continue;
        seenIn_[g] = visit_;
        ++enabledCount_[g];
      }
      for (const Edge* e = p_.edgesBegin(n); e != p_.edgesEnd(n); ++e) {
        if (member_[e->target] != stamp || ruleOf(e->via) == kStutter || !usable(*e)) continue;
        std::uint32_t g = fairness_.groupOf[absolute(k, ruleOf(e->via))];
        if (g != Fairness::kNone) taken_[g] = 1;
      }
    }
    // Per orbit of groups (a single group without symmetry): enabled in every state, in some,
    // taken somewhere.
    for (std::size_t g = 0; g < groups; ++g) everywhere_[g] = 1, somewhere_[g] = 0, orbitTaken_[g] = 0;
    for (std::uint32_t g = 0; g < groups; ++g) {
      std::uint32_t o = orbitOf(g);
      everywhere_[o] = everywhere_[o] && enabledCount_[g] == component.size();
      somewhere_[o] = somewhere_[o] || enabledCount_[g] != 0;
      orbitTaken_[o] = orbitTaken_[o] || taken_[g];
    }
    bool anyIgnored = false;  // strongly fair groups enabled here and never taken here
    for (std::uint32_t g = 0; g < groups; ++g) {
      std::uint32_t o = orbitOf(g);
      if (orbitTaken_[o] || !somewhere_[o]) continue;
      // Weak fairness: enabled in every state of the component and never taken -> no fair cycle.
      if (everywhere_[o]) return false;
      if (fairness_.strong[g]) ignored_[g] = 1, anyIgnored = true;
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
      bool drop = std::any_of(on.begin(), on.end(), [&](std::uint32_t r) {
        std::uint32_t g = fairness_.groupOf[absolute(k, r)];
        return g != Fairness::kNone && ignored_[g] != 0;
      });
      if (!drop) {
        rest.push_back(n);
        member_[n] = restStamp;
      }
    }
    std::fill(ignored_.begin(), ignored_.end(), 0);
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
        if (member_[e->target] != stamp || !usable(*e)) continue;
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
        if (member_[e->target] != stamp || !usable(*e)) continue;
        const Permutation& there = frame[local_[e->target]];
        Permutation arrived = compose(frame[u], perms.inverseOf(p_.permOf(e)));
        if (arrived != there) generators.insert(keyOf(compose(arrived, inverse(there))));
      }
    }
    frameSwaps_.resize(component.size());
    for (std::size_t k = 0; k < component.size(); ++k) frameSwaps_[k] = p_.symmetry().decompose(frame[k]);
    for (std::uint32_t g = 0; g < orbit_.size(); ++g) orbit_[g] = g;
    if (p_.prunesEqualRobots()) liftEqualNeighbours(component);
    for (const std::string& key : generators) {
      Permutation g(key.size() / sizeof(std::uint16_t));
      std::copy(key.begin(), key.end(), reinterpret_cast<char*>(g.data()));
      Symmetry::Swaps swaps = p_.symmetry().decompose(g);
      for (std::uint32_t r = 0; r < fairness_.groupOf.size(); ++r) {
        if (fairness_.groupOf[r] == Fairness::kNone) continue;
        std::uint32_t a = orbitOf(fairness_.groupOf[r]), b = orbitOf(fairness_.groupOf[p_.symmetry().image(r, swaps)]);
        if (a != b) orbit_[std::max(a, b)] = std::min(a, b);
      }
    }
  }

  // The product left out the rules of a robot equal to its neighbour (Product::pruneEqualRobots):
  // their edges, parallel to the lower rule's, would have added to the group the swap of the two
  // robots, seen in that state's frame (it fixes the concrete state, so it maps the concrete
  // component onto itself: it belongs to the group either way). Merged here directly: the orbits
  // of the rules the swap moves, each named in the frame of the first state.
  void liftEqualNeighbours(const std::vector<std::uint32_t>& component) {
    const Symmetry& symmetry = p_.symmetry();
    values_.resize(cm_.layout().variables());
    for (std::size_t k = 0; k < component.size(); ++k) {
      cm_.layout().unpack(p_.store().state(component[k]), values_.data());
      if (!symmetry.equalNeighbours(values_.data(), equal_)) continue;
      for (std::size_t slot = 1; slot < equal_.size(); ++slot) {
        if (equal_[slot] == 0) continue;
        for (std::size_t s : {slot - 1, slot}) {
          for (std::uint32_t r : symmetry.rulesTouching(s)) {
            const std::uint32_t g = fairness_.groupOf[absolute(k, r)];
            const std::uint32_t h = fairness_.groupOf[absolute(k, symmetry.swappedWithPrevious(r, slot))];
            if (g == Fairness::kNone || h == Fairness::kNone) continue;
            const std::uint32_t a = orbitOf(g), b = orbitOf(h);
            if (a != b) orbit_[std::max(a, b)] = std::min(a, b);
          }
        }
      }
    }
  }

  // Rule r of the k-th state of the component under analysis, named in the frame of the first.
  [[nodiscard]] std::uint32_t absolute(std::size_t k, std::uint32_t r) const {
    return p_.symmetric() ? p_.symmetry().image(r, frameSwaps_[k]) : r;
  }
  std::uint32_t orbitOf(std::uint32_t g) {
    if (!p_.symmetric()) return g;
    while (orbit_[g] != g) g = orbit_[g] = orbit_[orbit_[g]];
    return g;
  }

  const CompiledModel& cm_;
  const Buchi& ba_;
  const Product& p_;
  const Fairness fairness_;
  const Sensing sensing_;
  const bool settled_;
  std::vector<std::int8_t> allowed_;  // per sensed condition: how the cycle may decide it (-1: either way)
  std::vector<std::uint32_t> index_, low_, member_;
  std::vector<char> onStack_;
  std::vector<std::uint32_t> enabledCount_, seenIn_;  // per group: states it is enabled in; the last state counted
  std::uint32_t visit_ = 0;
  std::vector<char> taken_, everywhere_, somewhere_, orbitTaken_, ignored_;
  std::vector<std::uint32_t> orbit_, local_;        // union-find over the groups; a state's place in its component
  std::vector<Symmetry::Swaps> frameSwaps_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> found_;
  std::vector<Value> values_;
  std::vector<char> equal_;  // per slot, for liftEqualNeighbours
  std::vector<std::uint32_t> candidates_;
};

// A loop through the fair accepting set `cycleSet` that visits every acceptance set and treats
// every fair rule fairly, starting and ending at `entry`: greedy, to the nearest state or step
// that discharges an obligation still open.
inline std::vector<Edge> fairLoop(const Buchi& ba, const Product& p, FairCycleSearch& search,
                           const std::vector<std::uint32_t>& cycleSet, std::uint32_t entry) {
  std::vector<char> inSet(p.size(), 0);
  for (std::uint32_t n : cycleSet) inSet[n] = 1;
  std::uint64_t accPending = ba.allSets();
  std::vector<std::uint32_t> on;
  // Fair groups enabled somewhere here must be treated fairly on the loop.
  const Fairness& fairness = search.fairness();
  std::vector<char> pending(fairness.groups(), 0);
  for (std::uint32_t n : cycleSet) {
    search.enabled(n, on);
    for (std::uint32_t r : on) {
      if (fairness.groupOf[r] != Fairness::kNone) pending[fairness.groupOf[r]] = 1;
    }
  }
  std::vector<std::uint32_t> open;
  for (std::uint32_t g = 0; g < pending.size(); ++g) {
    if (pending[g]) open.push_back(g);
  }
  std::vector<char> enabledHere(fairness.groups(), 0);
  auto nodeDischarges = [&](std::uint32_t n, bool apply) {
    bool any = (p.acceptance(n) & accPending) != 0;
    if (apply) accPending &= ~p.acceptance(n);
    search.enabled(n, on);
    for (std::uint32_t r : on) {
      if (fairness.groupOf[r] != Fairness::kNone) enabledHere[fairness.groupOf[r]] = 1;
    }
    for (std::uint32_t g : open) {
      if (!pending[g] || fairness.strong[g] || enabledHere[g]) continue;
      any = true;  // a weakly fair group disabled here
      if (apply) pending[g] = 0;
    }
    for (std::uint32_t r : on) {
      if (fairness.groupOf[r] != Fairness::kNone) enabledHere[fairness.groupOf[r]] = 0;
    }
    return any;
  };
  auto edgeDischarges = [&](std::uint32_t via) {
    if (ruleOf(via) == kStutter) return false;
    std::uint32_t g = fairness.groupOf[ruleOf(via)];
    return g != Fairness::kNone && pending[g] != 0;
  };
  auto anyOpen = [&] {
    return accPending != 0 || std::any_of(open.begin(), open.end(), [&](std::uint32_t g) { return pending[g] != 0; });
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
        if (!inSet[e->target] || !search.usable(*e)) continue;
        if (goal(*e)) {
          std::vector<Edge> path{*e};
          for (std::uint32_t v = u; v != current;) {
            const auto& [from, edge] = reached[static_cast<std::size_t>(cameFrom[v])];
            path.push_back(edge);
            v = from;
          }
          std::reverse(path.begin(), path.end());
          for (const Edge& step : path) {
            if (ruleOf(step.via) != kStutter && fairness.groupOf[ruleOf(step.via)] != Fairness::kNone) {
              pending[fairness.groupOf[ruleOf(step.via)]] = 0;
            }
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

inline Trace lasso(const CompiledModel& cm, const Product& p, std::uint32_t entry, const std::vector<Edge>& loop) {
  Trace t = traceTo(cm, p.store(), entry);
  // Time passing on the way in (the automaton moving on while the model stays) is no step.
  t.steps.erase(std::remove_if(t.steps.begin(), t.steps.end(), [](const Step& s) { return s.rule == kStutter; }), t.steps.end());
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


}  // namespace semo::checker::detail
