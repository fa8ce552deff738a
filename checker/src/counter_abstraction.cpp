// The counter abstraction's searches (counter_abstraction.hpp): the abstract states for the
// invariants and deadlock freedom, and per LTL property the product with the automaton of its
// negation, searched for a fair accepting loop under the fairness the abstraction keeps.
#include "semo/checker/counter_abstraction.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "counter_system.hpp"
#include "counter_team.hpp"
#include "semo/checker/buchi.hpp"

namespace semo::checker {

using counter::Label;
using counter::Premise;
using counter::System;
using counter::Team;
using counter::TeamFormula;
using counter::Truth;

namespace {

struct StateHash {
  std::size_t operator()(const System::State& s) const noexcept {
    std::size_t h = 1469598103934665603ull;
    for (std::int32_t v : s) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return h;
  }
};

// The abstract states reachable for one choice of robots kept exactly.
struct Graph {
  std::unique_ptr<System> system;
  std::vector<System::State> states;
  std::vector<std::vector<std::pair<std::uint32_t, Label>>> edges;  // per state, its stutter last
  std::vector<std::vector<Premise>> enabled;
  std::vector<char> knownEnabled;
  std::uint64_t transitions = 0;
  std::string error;  // the system's, or the state limit
};

void explore(Graph& g, std::uint64_t maxStates) {
  std::unordered_map<System::State, std::uint32_t, StateHash> ids;
  g.states.push_back(g.system->initial());
  ids.emplace(g.states[0], 0);
  if (!g.system->error().empty()) {
    g.error = g.system->error();
    return;
  }
  for (std::size_t k = 0; k < g.states.size(); ++k) {
    if (g.states.size() > maxStates) {
      g.error = "the abstraction has more than " + std::to_string(maxStates) + " states";
      return;
    }
    System::Expansion x = g.system->expand(g.states[k]);
    if (!g.system->error().empty()) {
      g.error = g.system->error();
      return;
    }
    std::vector<std::pair<std::uint32_t, Label>> out;
    for (System::Step& step : x.steps) {
      auto [it, fresh] = ids.try_emplace(step.target, static_cast<std::uint32_t>(g.states.size()));
      if (fresh) g.states.push_back(std::move(step.target));
      out.emplace_back(it->second, step.label);
    }
    // A run may stay in any state for ever where no fairness asks for a step (as the explicit
    // search's stutter); the fair loop search rejects the stutter where a group is known enabled.
    out.emplace_back(static_cast<std::uint32_t>(k), Label{});
    g.transitions += out.size();
    g.edges.push_back(std::move(out));
    g.enabled.push_back(std::move(x.enabled));
    g.knownEnabled.push_back(x.someKnownEnabled ? 1 : 0);
  }
}

// The formulas of `exprs` over the team, with the robots they name on their own kept exactly.
struct Formulas {
  std::vector<char> explicitRobots;
  std::vector<TeamFormula> formulas;
  std::string error;
};

Formulas teamFormulas(const ir::Model& model, const Team& team, const std::vector<ir::Expr>& exprs) {
  Formulas out;
  out.explicitRobots.assign(team.robots.size(), 0);
  for (int round = 0; round < 4; ++round) {
    std::size_t representative = 0;
    while (representative < team.robots.size() && out.explicitRobots[representative] != 0) ++representative;
    if (representative == team.robots.size()) break;
    out.formulas.clear();
    std::vector<std::size_t> individual;
    bool ok = true;
    for (const ir::Expr& e : exprs) {
      auto f = counter::teamFormula(model, team, e, out.explicitRobots, representative, individual);
      if (!f) {
        ok = false;
        continue;
      }
      out.formulas.push_back(std::move(*f));
    }
    if (ok) return out;
    for (std::size_t r : individual) out.explicitRobots[r] = 1;
  }
  out.error = "its state formulas name too many robots on their own";
  return out;
}

std::vector<std::string> names(const ir::Model& model, const Team& team, const std::vector<char>& explicitRobots) {
  std::vector<std::string> out;
  for (std::size_t r = 0; r < explicitRobots.size(); ++r) {
    if (explicitRobots[r] != 0) out.push_back(model.robots[static_cast<std::size_t>(team.robots[r])]);
  }
  return out;
}

// The product of a graph with a Büchi automaton, and its search for a fair accepting loop.
class Product {
 public:
  Product(const Graph& g, const Buchi& ba, std::vector<std::uint64_t> mayHold, std::vector<std::uint64_t> mayFail)
      : g_(g), ba_(ba), mayHold_(std::move(mayHold)), mayFail_(std::move(mayFail)) {}

  bool build(std::uint64_t maxStates) {
    std::unordered_map<std::uint64_t, std::uint32_t> ids;
    auto node = [&](std::uint32_t s, std::uint32_t b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(s) << 32) | b;
      auto [it, fresh] = ids.try_emplace(key, static_cast<std::uint32_t>(state_.size()));
      if (fresh) state_.push_back(s), buchi_.push_back(b);
      return it->second;
    };
    for (std::uint32_t b = 0; b < ba_.states.size(); ++b) {
      if (ba_.states[b].initial && matches(0, b)) node(0, b);
    }
    for (std::uint32_t n = 0; n < state_.size(); ++n) {
      if (state_.size() > maxStates) return false;
      begin_.push_back(static_cast<std::uint32_t>(target_.size()));
      const std::uint32_t s = state_[n], b = buchi_[n];
      for (const auto& [t, label] : g_.edges[s]) {
        for (std::uint32_t nb : ba_.states[b].successors) {
          if (!matches(t, nb)) continue;
          target_.push_back(node(t, nb));
          label_.push_back(label);
        }
      }
    }
    begin_.push_back(static_cast<std::uint32_t>(target_.size()));
    off_.assign(target_.size(), 0);
    return true;
  }

  [[nodiscard]] std::size_t size() const { return state_.size(); }

  bool fairLoop() {
    std::vector<std::uint32_t> all(state_.size());
    for (std::uint32_t n = 0; n < all.size(); ++n) all[n] = n;
    inSet_.assign(state_.size(), 0);
    visited_.assign(state_.size(), 0);
    index_.assign(state_.size(), 0);
    low_.assign(state_.size(), 0);
    onStack_.assign(state_.size(), 0);
    return search(all);
  }

 private:
  [[nodiscard]] bool matches(std::uint32_t s, std::uint32_t b) const {
    const BuchiState& q = ba_.states[b];
    return (q.mustHold & ~mayHold_[s]) == 0 && (q.mustFail & ~mayFail_[s]) == 0;
  }

  [[nodiscard]] std::uint32_t groupOf(const Label& l) const { return g_.system->fairness().groupOf[l.rule]; }

  // The strongly connected components of `nodes` over the edges not switched off.
  std::vector<std::vector<std::uint32_t>> components(const std::vector<std::uint32_t>& nodes) {
    const std::uint32_t stamp = ++stamp_;
    for (std::uint32_t n : nodes) inSet_[n] = stamp;
    // Per node, kept across calls: a component searched again (Emerson-Lei's refinement, the
    // finiteness compassion) costs its own size, not the product's.
    const std::uint32_t visit = ++visit_;
    auto seen = [&](std::uint32_t n) { return visited_[n] == visit; };
    auto number = [&](std::uint32_t n, std::uint32_t k) { visited_[n] = visit, index_[n] = low_[n] = k; };
    std::vector<std::uint32_t>& index = index_;
    std::vector<std::uint32_t>& low = low_;
    std::vector<char>& onStack = onStack_;
    std::vector<std::uint32_t> stack;
    std::vector<std::vector<std::uint32_t>> out;
    std::uint32_t next = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> call;  // (node, next edge)
    for (std::uint32_t root : nodes) {
      if (seen(root)) continue;
      number(root, next++);
      stack.push_back(root);
      onStack[root] = 1;
      call.emplace_back(root, begin_[root]);
      while (!call.empty()) {
        auto& [v, e] = call.back();
        if (e < begin_[v + 1]) {
          const std::uint32_t edge = e++;
          const std::uint32_t w = target_[edge];
          if (off_[edge] != 0 || inSet_[w] != stamp) continue;
          if (!seen(w)) {
            number(w, next++);
            stack.push_back(w);
            onStack[w] = 1;
            call.emplace_back(w, begin_[w]);
          } else if (onStack[w] != 0) {
            low[v] = std::min(low[v], index[w]);
          }
          continue;
        }
        const std::uint32_t done = v;
        call.pop_back();
        if (!call.empty()) low[call.back().first] = std::min(low[call.back().first], low[done]);
        if (low[done] != index[done]) continue;
        std::vector<std::uint32_t> component;
        for (;;) {
          const std::uint32_t w = stack.back();
          stack.pop_back();
          onStack[w] = 0;
          component.push_back(w);
          if (w == done) break;
        }
        out.push_back(std::move(component));
      }
    }
    return out;
  }

  bool search(const std::vector<std::uint32_t>& nodes) {
    for (std::vector<std::uint32_t>& component : components(nodes)) {
      if (analyze(component)) return true;
    }
    return false;
  }

  // Whether a fair accepting loop lies within one component.
  bool analyze(std::vector<std::uint32_t>& component) {
    const std::uint32_t stamp = ++stamp_;
    for (std::uint32_t n : component) inSet_[n] = stamp;
    std::vector<std::uint32_t> internal;
    for (std::uint32_t n : component) {
      for (std::uint32_t e = begin_[n]; e < begin_[n + 1]; ++e) {
        if (off_[e] == 0 && inSet_[target_[e]] == stamp) internal.push_back(e);
      }
    }
    if (internal.empty()) return false;
    // What the loop's steps do: groups taken from a local state or by a robot, local states left
    // and entered.
    std::set<Premise> taken;
    std::set<std::int32_t> left, entered;
    for (std::uint32_t e : internal) {
      const Label& l = label_[e];
      if (l.kind == Label::Kind::Stutter) continue;
      const std::uint32_t grp = groupOf(l);
      if (grp != Fairness::kNone) taken.insert({l.kind, l.kind == Label::Kind::Global ? 0 : l.from, grp});
      if (l.kind == Label::Kind::Counted && l.from != l.to) left.insert(l.from), entered.insert(l.to);
    }
    auto satisfied = [&](const Premise& p) {
      return taken.count(p) != 0 || (p.kind == Label::Kind::Counted && left.count(p.where) != 0);
    };
    const Fairness& fairness = g_.system->fairness();
    // Strongly fair groups enabled somewhere in the loop must be taken in it: else the loop lies
    // among the states where they are not enabled.
    for (std::uint32_t n : component) {
      for (const Premise& p : g_.enabled[state_[n]]) {
        if (fairness.strong[p.group] == 0 || satisfied(p)) continue;
        std::vector<std::uint32_t> rest;
        for (std::uint32_t m : component) {
          const auto& en = g_.enabled[state_[m]];
          if (!std::binary_search(en.begin(), en.end(), p)) rest.push_back(m);
        }
        return search(rest);
      }
    }
    // Robots cannot leave a local state again and again unless others enter it again and again.
    for (std::int32_t l : left) {
      if (entered.count(l) != 0) continue;
      std::vector<std::uint32_t> switched;
      for (std::uint32_t e : internal) {
        if (label_[e].kind == Label::Kind::Counted && label_[e].from == l && label_[e].to != l) off_[e] = 1, switched.push_back(e);
      }
      const bool found = search(component);
      for (std::uint32_t e : switched) off_[e] = 0;
      return found;
    }
    std::uint64_t sets = 0;
    for (std::uint32_t n : component) sets |= ba_.states[buchi_[n]].acceptance;
    if (sets != ba_.allSets()) return false;
    // Weakly fair groups enabled in every state of the loop must be taken in it.
    std::vector<Premise> everywhere = g_.enabled[state_[component[0]]];
    for (std::uint32_t n : component) {
      std::vector<Premise> both;
      const auto& en = g_.enabled[state_[n]];
      std::set_intersection(everywhere.begin(), everywhere.end(), en.begin(), en.end(), std::back_inserter(both));
      everywhere = std::move(both);
    }
    return std::all_of(everywhere.begin(), everywhere.end(), [&](const Premise& p) { return fairness.strong[p.group] != 0 || satisfied(p); });
  }

  const Graph& g_;
  const Buchi& ba_;
  std::vector<std::uint64_t> mayHold_, mayFail_;  // per abstract state: atoms that may hold, may fail
  std::vector<std::uint32_t> state_, buchi_;       // per product node
  std::vector<std::uint32_t> begin_, target_;      // edges, by node
  std::vector<Label> label_;
  std::vector<char> off_;
  std::vector<std::uint32_t> inSet_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> visited_, index_, low_;  // Tarjan's numbering, valid where visited_ is visit_
  std::vector<char> onStack_;
  std::uint32_t visit_ = 0;
};

}  // namespace

bool CountingResult::allProven() const {
  if (!applicable) return false;
  auto proven = [](const CountingVerdict& v) { return v.verdict == Verdict::Proven; };
  return std::all_of(invariants.begin(), invariants.end(), proven) && (!deadlockChecked || proven(deadlock)) &&
         std::all_of(properties.begin(), properties.end(), proven);
}

CountingResult checkByCounting(const ir::Model& model, const std::vector<ir::Expr>& countDefinitions, const CountingOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CountingResult out;
  out.threshold = options.threshold;
  std::optional<Team> team = counter::teamOf(model, countDefinitions, out.why);
  if (!team) return out;
  out.robots = team->robots.size();
  for (std::size_t r = 1; r < team->robots.size(); ++r) {
    if (!counter::sameTemplate(model, *team, r, 0, out.why)) return out;
  }
  std::map<std::vector<char>, Graph> graphs;
  auto graphFor = [&](const std::vector<char>& explicitRobots) -> Graph& {
    auto [it, fresh] = graphs.try_emplace(explicitRobots);
    if (fresh) {
      it->second.system = std::make_unique<System>(model, *team, explicitRobots, options.threshold);
      if (!it->second.system->error().empty()) it->second.error = it->second.system->error();
      else explore(it->second, options.maxStates);
    }
    return it->second;
  };

  // The invariants and the valid end, over one abstraction.
  std::vector<ir::Expr> safety;
  for (const ir::Invariant& inv : model.invariants) safety.push_back(inv.holds);
  if (model.validEnd) safety.push_back(*model.validEnd);
  if (options.onPhase) options.onPhase("counting: the invariants and deadlock freedom");
  const Formulas sf = teamFormulas(model, *team, safety);
  if (!sf.error.empty()) {
    out.why = "the invariants: " + sf.error;
    return out;
  }
  Graph& g = graphFor(sf.explicitRobots);
  if (!g.error.empty()) {
    out.why = g.error;
    return out;
  }
  out.applicable = true;
  out.states = g.states.size();
  out.transitions = g.transitions;
  out.localStates = g.system->localStates();
  auto verdict = [&](const std::string& name, const std::vector<char>& explicitRobots) {
    CountingVerdict v;
    v.name = name;
    v.explicitRobots = names(model, *team, explicitRobots);
    return v;
  };
  for (std::size_t i = 0; i < safety.size(); ++i) {
    const bool isEnd = model.validEnd && i + 1 == safety.size();
    CountingVerdict v = verdict(isEnd ? "deadlock_freedom" : model.invariants[i].name, sf.explicitRobots);
    v.verdict = Verdict::Proven;
    for (std::size_t s = 0; s < g.states.size() && v.verdict == Verdict::Proven; ++s) {
      if (isEnd && g.knownEnabled[s] != 0) continue;
      if (g.system->holds(sf.formulas[i], g.states[s]) == Truth::True) continue;
      v.verdict = Verdict::Unknown;
      v.why = isEnd ? "an abstract state may enable no step without being a valid end" : "an abstract state may break it";
    }
    if (isEnd) {
      out.deadlockChecked = true;
      out.deadlock = std::move(v);
    } else {
      out.invariants.push_back(std::move(v));
    }
  }

  for (const ir::Property& prop : model.properties) {
    if (options.onPhase) options.onPhase("counting: " + prop.name);
    CountingVerdict v;
    v.name = prop.name;
    Buchi ba;
    try {
      ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, prop.formula));
    } catch (const std::length_error& e) {
      v.why = e.what();
      out.properties.push_back(std::move(v));
      continue;
    }
    const Formulas pf = teamFormulas(model, *team, ba.atoms);
    if (!pf.error.empty()) {
      v.why = pf.error;
      out.properties.push_back(std::move(v));
      continue;
    }
    v.explicitRobots = names(model, *team, pf.explicitRobots);
    Graph& pg = graphFor(pf.explicitRobots);
    if (!pg.error.empty()) {
      v.why = pg.error;
      out.properties.push_back(std::move(v));
      continue;
    }
    std::vector<std::uint64_t> mayHold(pg.states.size(), 0), mayFail(pg.states.size(), 0);
    for (std::size_t s = 0; s < pg.states.size(); ++s) {
      for (std::size_t a = 0; a < pf.formulas.size(); ++a) {
        const Truth t = pg.system->holds(pf.formulas[a], pg.states[s]);
        if (t != Truth::False) mayHold[s] |= 1ull << a;
        if (t != Truth::True) mayFail[s] |= 1ull << a;
      }
    }
    Product product(pg, ba, std::move(mayHold), std::move(mayFail));
    if (!product.build(options.maxStates)) {
      v.why = "its product has more than " + std::to_string(options.maxStates) + " states";
    } else if (product.fairLoop()) {
      v.why = "the abstraction has a fair loop that breaks it, which a team of exactly this size may not have";
    } else {
      v.verdict = Verdict::Proven;
    }
    v.productStates = product.size();
    if (std::getenv("SEMO_DEBUG_COUNTING") != nullptr) std::fprintf(stderr, "[counting] %s: automaton %zu states, %zu atoms; abstraction %zu states; product %zu\n", prop.name.c_str(), ba.states.size(), ba.atoms.size(), pg.states.size(), product.size());
    out.properties.push_back(std::move(v));
  }
  // Every team size from n0 on: the translation of a counted team is one template at every size
  // (its robots' rules, the counts' terms, the rules of no robot), the robots named on their own
  // are the same, and every count of robots beyond them starts at "K or more".
  // A shared variable's range may come from the team's size: a crash budget larger than the team
  // is cut to it. Past the largest such range the translation no longer depends on the size; a
  // range that reaches the team's size may have been cut, and then no size but this one is claimed.
  std::int64_t shared = 0;
  for (ir::VarId v : team->globals) shared = std::max<std::int64_t>(shared, model.variables[v].max);
  const bool cut = shared >= static_cast<std::int64_t>(team->robots.size());
  auto everySize = [&](CountingVerdict& v) {
    if (v.verdict == Verdict::Proven && options.countedTeamsFrom > 0 && !cut) {
      v.everyTeamFrom = std::max({options.countedTeamsFrom, v.explicitRobots.size() + options.threshold, static_cast<std::size_t>(shared)});
    }
  };
  for (CountingVerdict& v : out.invariants) everySize(v);
  if (out.deadlockChecked) everySize(out.deadlock);
  for (CountingVerdict& v : out.properties) everySize(v);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace semo::checker
