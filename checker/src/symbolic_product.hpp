#pragma once
// The product of a model with a Büchi automaton as binary decision diagrams (BuDDy): the relations
// of the rules and of the automaton, images and preimages, the fair accepting states (an
// Emerson-Lei fixpoint), and concrete states and steps for building a lasso. Used by
// symbolic_liveness.cpp, which owns the decision-diagram package while it runs.
#include <bdd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "semo/checker/buchi.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/semantics/ir.hpp"
#include "symbolic_values.hpp"
#include "thread_cpu_clock.hpp"

namespace semo::checker::detail {

// Budgets count the thread's processor time (thread_cpu_clock.hpp).
using CpuClock = ThreadCpuClock;

// BuDDy keeps one package per process (symbolic_liveness.cpp holds a lock for a whole search), and
// its error hook records what went wrong (a full node table) instead of ending the process, as
// BuDDy's default hook does.
inline int packageError = 0;
inline void recordError(int code) {
  if (packageError == 0) packageError = code;
}

// The model and the automaton as decision diagrams. Each variable gets the bits of its offset from
// its minimum (most significant first); each bit has a current and a next copy, side by side in
// the variable order, so that a step's relation stays small. The automaton's state comes first.
class SymbolicProduct {
 public:
  SymbolicProduct(const ir::Model& model, const Buchi& ba, const Fairness& fairness, CpuClock::time_point deadline,
                  std::function<void(const Progress&)> onProgress = nullptr)
      : model_(model), ba_(ba), fairness_(fairness), deadline_(deadline), onProgress_(std::move(onProgress)) {
    int bits = 0;
    auto layOut = [&bits](std::int64_t min, std::int64_t max) {
      BitLayout l{bits, 0, min, max};
      while ((std::int64_t{1} << l.bits) < max - min + 1) ++l.bits;
      bits += l.bits;
      return l;
    };
    automaton_ = layOut(0, static_cast<std::int64_t>(ba.states.size()) - 1);
    // A robot's variables side by side (the team's first): most rules read and write one robot's
    // state, and a relation over nearby bits stays small.
    std::vector<ir::VarId> order(model.variables.size());
    for (ir::VarId v = 0; v < order.size(); ++v) order[v] = v;
    std::stable_sort(order.begin(), order.end(), [&](ir::VarId a, ir::VarId b) { return model.variables[a].robot < model.variables[b].robot; });
    layouts_.resize(model.variables.size());
    for (ir::VarId v : order) layouts_[v] = layOut(model.variables[v].min, model.variables[v].max);
    bdd_setvarnum(std::max(2, 2 * bits));
    check();
    buildAutomaton();
    // An accepted loop stays in one automaton component with a state of every acceptance set.
    const std::vector<char> onLoops = acceptedLoopStates(ba);
    loopAutomaton_ = bddfalse;
    for (std::uint32_t q = 0; q < ba.states.size(); ++q) loopAutomaton_ |= onLoops[q] != 0 ? cube(automaton_, q, false) : bddfalse;
    for (std::uint32_t r = 0; r < model.rules.size(); ++r) rules_.push_back(compileRule(model.rules[r]));
    enabledFair_ = bddfalse;
    for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
      if (model.rules[r].weaklyFair || model.rules[r].stronglyFair) enabledFair_ |= rules_[r].guard;
    }
    groupEnabled_.assign(fairness.groups(), bddfalse);
    for (std::uint32_t g = 0; g < fairness.groups(); ++g) {
      for (std::uint32_t r : fairness.members[g]) groupEnabled_[g] |= rules_[r].guard;
    }
    std::vector<int> all, allNext;
    for (int b = 0; b < bits; ++b) all.push_back(2 * b), allNext.push_back(2 * b + 1);
    currentBits_ = bdd_makeset(all.data(), static_cast<int>(all.size()));
    nextBits_ = bdd_makeset(allNext.data(), static_cast<int>(allNext.size()));
    allToNext_ = bdd_newpair();
    for (int b = 0; b < bits; ++b) bdd_setpair(allToNext_, 2 * b, 2 * b + 1);
    check();
  }

  ~SymbolicProduct() {
    for (Rule& r : rules_) bdd_freepair(r.toCurrent);
    bdd_freepair(automatonToNext_);
    bdd_freepair(automatonToCurrent_);
    bdd_freepair(allToNext_);
  }
  SymbolicProduct(const SymbolicProduct&) = delete;
  SymbolicProduct& operator=(const SymbolicProduct&) = delete;

  // A helper process forked to search beside the caller (shared_worlds.hpp) goes on with the time
  // the caller had left, on a clock of its own (a new process's starts at zero), and reports no
  // progress: only the caller does.
  [[nodiscard]] CpuClock::duration timeLeft() const { return deadline_ - CpuClock::now(); }
  void continueInHelper(CpuClock::duration left) {
    deadline_ = CpuClock::now() + left;
    onProgress_ = nullptr;
  }

  // The product states reachable from the initial ones (forward, chained: closeForward).
  bdd reachable() { return closeForward(initialStates(), bddtrue, std::vector<char>(rules_.size(), 1), true); }

  // The model's initial state (on the model's bits only).
  bdd initialModelState() const {
    bdd initial = bddtrue;
    for (ir::VarId v = 0; v < model_.variables.size(); ++v) initial &= cube(layouts_[v], model_.variables[v].init, false);
    return initial;
  }

  bdd initialStates() {
    const bdd initial = initialModelState();
    bdd start = bddfalse;
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      if (ba_.states[q].initial) start |= cube(automaton_, q, false);
    }
    return initial & start & labels_;
  }

  // The model's reachable states, each with every automaton state its labels allow: the
  // reachable product states and possibly more, as the automaton's state is not followed. The
  // set is closed under the product's steps, so a fair loop outside it is in no reachable part of
  // the product, and a loop in it that the initial states reach is real (specs/ir.md, "Symbolic
  // search"). Without the automaton each image is one operation instead of four, on diagrams
  // without its bits.
  bdd reachableAnyAutomaton() { return reachableModelStates() & labels_; }

  // The model's reachable states (on the model's bits only).
  bdd reachableModelStates() {
    const bdd states = closeForward(initialModelState(), bddtrue, std::vector<char>(rules_.size(), 1), true, false);
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] the model's reachable states: %.0f, %d nodes\n", modelStates(states), bdd_nodecount(states));
    }
    return states;
  }

  // Rule r's step from `states`, on the model's bits (the automaton's left as they are).
  bdd image(const bdd& states, std::uint32_t r) {
    const Rule& rule = rules_[r];
    const bdd out = bdd_replace(bdd_appex(states, rule.relation, bddop_and, rule.currentSet), rule.toCurrent);
    check();
    return out;
  }
  // The current bits of variable v (to quantify it away), and the states where `e` holds.
  bdd variableBits(ir::VarId v) const { return bitSet(layouts_[v], false); }
  bdd holds(const ir::Expr& e) { return truth(values(e)); }
  [[nodiscard]] const bdd& labels() const { return labels_; }

  // How many model states a product set holds (the automaton's state left out).
  double modelStates(const bdd& states) { return count(bdd_exist(states, automatonCurrent_)) / static_cast<double>(1 << automaton_.bits); }

  // One product step from `states`, by any rule or by time passing.
  bdd successors(const bdd& states) {
    bdd out = automatonStep(minus(states, enabledFair_));
    for (const Rule& r : rules_) out |= automatonStep(bdd_replace(bdd_appex(states, r.relation, bddop_and, r.currentSet), r.toCurrent));
    return out;
  }

  // Whether an initial product state reaches `target` inside `within`.
  bool initialReaches(const bdd& within, const bdd& target) {
    return (initialStates() & until(within, target & within, std::vector<char>(rules_.size(), 1))) != bddfalse;
  }

  // The automaton's move on reading the model's new state (the model's step already taken).
  bdd automatonStep(const bdd& moved) {
    const bdd out = bdd_replace(bdd_appex(moved, automatonRelation_, bddop_and, automatonCurrent_), automatonToCurrent_) & labels_;
    check();
    return out;
  }

  [[nodiscard]] double count(const bdd& states) const { return bdd_satcountset(states, currentBits_); }

  // A round of the fixpoint below that leaves more than this fraction of its set cuts little: the
  // strongly fair groups are then taken too.
  static constexpr double kSlowRound = 0.8;

  // The states of `z` on a fair accepting cycle through `z` or leading to one inside it (only
  // those whose automaton state may lie on an accepted loop), the loop using only the rules
  // `allowed` marks (a settled world restricts the loop, not the way to it):
  // the greatest fixpoint of Emerson and Lei. At the fixpoint every state has a successor in the
  // set and reaches, inside it, each acceptance set of the automaton, for each weakly fair group a
  // state where the group is disabled or takes a step, and for each strongly fair rule enabled
  // there a state that takes it (or the rule is never enabled in the set): a bottom strongly
  // connected component of the set is then a fair accepting loop. Conversely the states of any
  // such loop satisfy all of this, so the set is empty exactly when no such loop exists.
  bdd fairStates(bdd z, const std::vector<char>& allowed) {
    z &= loopAutomaton_;
    std::vector<bdd> acceptance;
    for (std::size_t i = 0; i < ba_.acceptanceSets; ++i) acceptance.push_back(acceptanceSet(i));
    // A group found met by a set stays met while the set does not shrink: `version` counts the
    // shrinkings, and a group met at the current version is not looked at again.
    std::uint64_t version = 0;
    std::vector<std::uint64_t> metAt(fairness_.groups(), UINT64_MAX);
    std::uint32_t rounds = 0;
    double shrunkTo = 0;  // what the last round left of the set it began with (a fraction)
    while (true) {
      const bdd old = z;
      const double before = count(z);
      progressOn(z, ++rounds);
      z = predecessors(z, allowed, nullptr, z);
      for (const bdd& set : acceptance) z = until(z, z & set, allowed);
      if (z != old) ++version;
      bdd zAfter = automatonPredecessors(z);  // shared by the groups until z shrinks
      bdd zAfterOf = z;
      // The strongly fair groups only in a round where no weakly fair one shrank the set, or once
      // the rounds cut little (the last left more than kSlowRound of its set): theirs is the dear
      // constraint (a closure per group, on sets of tens of thousands of nodes), best taken on a
      // set the cheap ones have already cut down, but not left waiting while they trim the set a
      // little at a time (scouting's cone: 18 rounds of the weak groups took 1.72 * 10^17 states
      // to 1.70 * 10^17, and the strong ones then cut them to 7 * 10^11). Each operation only
      // removes states the fixpoint cannot hold, so any order ends at the same set
      // (checker/README.md has the figures).
      const bool strongNow = shrunkTo > kSlowRound;
      bool weakShrank = false;
      for (std::uint32_t g = 0; g < fairness_.groups() && z != bddfalse; ++g) {
        if (weakShrank && !strongNow && fairness_.strong[g] != 0) continue;
        if (metAt[g] == version || (z & groupEnabled_[g]) == bddfalse) continue;
        if (zAfterOf != z) zAfter = automatonPredecessors(z), zAfterOf = z;
        const bdd taken = modelPredecessors(zAfter, allowed, &fairness_.members[g], z);
        const bdd before = z;
        if (fairness_.strong[g] != 0) {
          z = minus(z, groupEnabled_[g]) | until(z, taken, allowed);
        } else {
          const bdd good = minus(z, groupEnabled_[g]) | taken;
          if (good != z) z = until(z, good, allowed);
        }
        if (z == before) {
          metAt[g] = version;
        } else {
          ++version;
          weakShrank = weakShrank || fairness_.strong[g] == 0;
        }
      }
      if (z == old) return z;
      shrunkTo = before > 0 ? count(z) / before : 1;
    }
  }

  // Whether rule r steps from a state of `z` to one of `z` (product steps; `zAfter` is
  // automatonPredecessors(z)).
  bool stepsWithin(const bdd& z, const bdd& zAfter, std::uint32_t r) {
    return preimageFrom(rules_[r].frame, z, toNext(zAfter)) != bddfalse;
  }

  // The states of `sources` with a product step into `z`: by the rules `only` lists (all when null)
  // that `allowed` marks, or, with all of them, by time passing.
  bdd predecessors(const bdd& z, const std::vector<char>& allowed, const std::vector<std::uint32_t>* only, const bdd& sources) {
    return modelPredecessors(automatonPredecessors(z), allowed, only, sources);
  }

  // The automaton moves on reading the model's new state: a product step into `z` is a model step
  // into these (the model's new state, the automaton's state before).
  bdd automatonPredecessors(const bdd& z) {
    const bdd out = bdd_appex(automatonRelation_, bdd_replace(z, automatonToNext_), bddop_and, automatonNext_);
    check();
    return out;
  }

  bdd modelPredecessors(const bdd& afterModel, const std::vector<char>& allowed, const std::vector<std::uint32_t>* only, const bdd& sources) {
    bdd out = bddfalse;
    const bdd afterNext = toNext(afterModel);
    if (only != nullptr) {
      for (std::uint32_t r : *only) {
        if (allowed[r] != 0) out |= preimageFrom(rules_[r].frame, sources, afterNext);
      }
      return out;
    }
    for (const bdd& relation : clustersOf(allowed)) out |= preimageFrom(relation, sources, afterNext);
    return out | minus(sources & afterModel, enabledFair_);
  }

  // A set on the next bits (every variable's), for preimageFrom().
  bdd toNext(const bdd& states) {
    const bdd out = bdd_replace(states, allToNext_);
    check();
    return out;
  }

  // The states of `sources` with a step of rule r into `statesNext` (a set on the next bits): one
  // conjunction and quantification with the rule's relation over the whole state, cut to the
  // sources first, so that it walks only the part of the set they can reach. (Renaming the set to
  // each rule's own next bits rebuilt the whole set once per rule, and a preimage of all of it
  // before the cut described states nobody asked about: the fair states of the largest slice of
  // the swarm of 10 without symmetry took 22 s that way, 4.4 s this way; checker/README.md.)
  bdd preimageFrom(const bdd& relation, const bdd& sources, const bdd& statesNext) {
    const bdd out = bdd_appex(relation & sources, statesNext, bddop_and, nextBits_);
    check();
    return out;
  }

  // The whole-state relations of the rules `allowed` marks, neighbouring rules joined (a translated
  // model lists a robot's rules together) while the joined diagram stays under kClusterNodes: fewer,
  // larger preimages. Measured on 2026-11-28 (scouting's leader_reelection[WatchLight], symbolic
  // processor time over its 17 symbolic slices): a rule at a time 77 s; clusters of up to 4,000
  // nodes 44 s, 10,000 54 s, 20,000 48 s, 50,000 76 s.
  const std::vector<bdd>& clustersOf(const std::vector<char>& allowed) {
    auto it = clusters_.find(allowed);
    if (it != clusters_.end()) return it->second;
    constexpr int kClusterNodes = 4000;
    std::vector<bdd> out;
    bdd joined = bddfalse;
    for (std::uint32_t r = 0; r < rules_.size(); ++r) {
      if (allowed[r] == 0) continue;
      const bdd wider = joined | rules_[r].frame;
      check();
      if (joined != bddfalse && bdd_nodecount(wider) > kClusterNodes) {
        out.push_back(joined);
        joined = rules_[r].frame;
      } else {
        joined = wider;
      }
    }
    if (joined != bddfalse) out.push_back(joined);
    return clusters_.emplace(allowed, std::move(out)).first->second;
  }

  // The states of `within` reachable from `from` by product steps of the rules `allowed` marks.
  bdd forwardClosure(const bdd& from, const bdd& within, const std::vector<char>& allowed) {
    return closeForward(from & within, within, allowed, false);
  }

  // E[z U goal]: the states of z from which a path inside z reaches `goal` (a subset of z).
  // Chained on everything reached, as the forward search.
  bdd until(const bdd& z, const bdd& goal, const std::vector<char>& allowed) {
    bdd reached = goal;
    bdd before = bddfalse;
    while (reached != before) {
      before = reached;
      bdd after = automatonPredecessors(reached);
      reached |= minus(z & after, enabledFair_);  // time passing
      bdd afterNext = toNext(after);
      bdd open = minus(z, reached);
      for (const bdd& relation : clustersOf(allowed)) {
        if (open == bddfalse) break;
        const bdd found = preimageFrom(relation, open, afterNext);
        if (found == bddfalse) continue;
        reached |= found;
        open &= !found;
        afterNext = toNext(automatonPredecessors(reached));
      }
    }
    return reached;
  }

  // One state of the product, with every value.
  struct Concrete {
    std::vector<std::int64_t> values;
    std::uint32_t automaton = 0;
    bool operator==(const Concrete&) const = default;
  };
  struct Move {
    std::uint32_t rule;  // kTimePasses: no rule (the state stays, the automaton moves)
    std::uint32_t branch;
    Concrete after;
  };
  static constexpr std::uint32_t kTimePasses = 0xffffffffu;

  Concrete initialState(const bdd& within) {
    Concrete c;
    for (const ir::Variable& v : model_.variables) c.values.push_back(v.init);
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      c.automaton = q;
      if (ba_.states[q].initial && labelHolds(q, c.values) && contains(within, c)) return c;
    }
    throw std::logic_error("symbolic lasso: no initial state in the set");
  }

  Concrete pick(const bdd& set) const {
    const bdd one = bdd_satoneset(set, currentBits_, bddfalse);
    Concrete c;
    auto read = [&](const BitLayout& l) {
      std::int64_t offset = 0;
      for (int i = 0; i < l.bits; ++i) offset = offset << 1 | ((one & bdd_nithvar(bit(l, i, false))) == bddfalse ? 1 : 0);
      return l.min + offset;
    };
    for (const BitLayout& l : layouts_) c.values.push_back(read(l));
    c.automaton = static_cast<std::uint32_t>(read(automaton_));
    return c;
  }

  bdd cubeOf(const Concrete& c) const {
    bdd out = cube(automaton_, c.automaton, false);
    for (std::size_t v = 0; v < layouts_.size(); ++v) out &= cube(layouts_[v], c.values[v], false);
    return out;
  }
  bool contains(const bdd& set, const Concrete& c) const { return (set & cubeOf(c)) != bddfalse; }

  // The product steps from `c` by the rules `allowed` marks (and time passing where it may).
  std::vector<Move> moves(const Concrete& c, const std::vector<char>& allowed) const {
    std::vector<Move> out;
    bool fairEnabled = false;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> vias;
    std::vector<std::vector<std::int64_t>> afters;
    for (std::uint32_t r = 0; r < model_.rules.size(); ++r) {
      const ir::Rule& rule = model_.rules[r];
      if (evaluateOn(rule.guard, c.values) == 0) continue;
      fairEnabled = fairEnabled || rule.weaklyFair || rule.stronglyFair;
      if (allowed[r] == 0) continue;
      for (std::uint32_t b = 0; b < rule.branches.size(); ++b) {
        std::vector<std::int64_t> next = c.values;
        for (const ir::Assignment& a : rule.branches[b].assignments) next[a.var] = evaluateOn(a.value, c.values);
        vias.push_back({r, b});
        afters.push_back(std::move(next));
      }
    }
    if (!fairEnabled) {
      vias.push_back({kTimePasses, 0});
      afters.push_back(c.values);
    }
    for (std::size_t k = 0; k < vias.size(); ++k) {
      for (std::uint32_t q : ba_.states[c.automaton].successors) {
        if (labelHolds(q, afters[k])) out.push_back({vias[k].first, vias[k].second, {afters[k], q}});
      }
    }
    return out;
  }

  [[nodiscard]] const Fairness& fairness() const { return fairness_; }
  [[nodiscard]] const bdd& groupEnabled(std::uint32_t g) const { return groupEnabled_[g]; }
  bdd acceptanceSet(std::size_t i) const {
    bdd set = bddfalse;
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      if ((ba_.states[q].acceptance >> i & 1) != 0) set |= cube(automaton_, q, false);
    }
    return set;
  }
  [[nodiscard]] std::size_t acceptanceSets() const { return ba_.acceptanceSets; }
  [[nodiscard]] std::size_t rules() const { return rules_.size(); }

 private:
  std::int64_t evaluateOn(const ir::Expr& e, const std::vector<std::int64_t>& values) const {
    switch (e.op) {
      case ir::Op::Const: return e.value;
      case ir::Op::Var: return values[static_cast<std::size_t>(e.value)];
      case ir::Op::Not: return evaluateOn(e.args[0], values) == 0;
      case ir::Op::Neg: return -evaluateOn(e.args[0], values);
      case ir::Op::Ite: return evaluateOn(e.args[0], values) != 0 ? evaluateOn(e.args[1], values) : evaluateOn(e.args[2], values);
      default: return evaluate(e.op, evaluateOn(e.args[0], values), evaluateOn(e.args[1], values));
    }
  }

  bool labelHolds(std::uint32_t q, const std::vector<std::int64_t>& values) const {
    const BuchiState& s = ba_.states[q];
    for (std::size_t k = 0; k < ba_.atoms.size(); ++k) {
      const bool holds = evaluateOn(ba_.atoms[k], values) != 0;
      if ((s.mustHold >> k & 1) != 0 && !holds) return false;
      if ((s.mustFail >> k & 1) != 0 && holds) return false;
    }
    return true;
  }

  // `reached` closed under the product steps of the rules `allowed` marks, and time passing where
  // nothing fair can step, inside `within` (`product` false: the model's states alone, the rules'
  // steps only; `within` is then not looked at): chaining with a frontier per rule. The rules are taken
  // deepest first in the variable order (by the first variable their relation reads or writes),
  // each only from the states it has not stepped from yet; after a rule adds states, the next is
  // again the deepest rule with states new to it, so the steps of the robots deep in the order are
  // closed over before those above them move. The set is that of breadth-first rounds, with smaller
  // diagrams on the way, and found sooner (checker/README.md, "Forward closure", has the figures).
  bdd closeForward(bdd reached, const bdd& within, const std::vector<char>& allowed, bool report, bool product = true) {
    const std::vector<std::uint32_t>& order = deepestFirst(allowed);
    // The states each rule has not stepped from yet: what was added since it last stepped, kept
    // as it is added, so that no step of the closure works on the whole set (`reached` minus what
    // a rule had seen cost a pass over both at every image).
    std::vector<bdd> pending(order.size(), reached);
    std::size_t waiting = reached == bddfalse ? 0 : order.size();  // rules with pending states
    std::uint32_t passes = 0;
    std::uint64_t images = 0;
    const auto addToAll = [&](const bdd& added) {
      reached |= added;
      for (bdd& p : pending) {
        if (p == bddfalse) ++waiting;
        p |= added;
      }
    };
    for (;;) {
      std::size_t i = 0;
      if (waiting > 0) {
        while (pending[i] == bddfalse) ++i;
      } else {
        if (report) progressOn(reached, ++passes, product);
        if (!product) return reached;
        const bdd idle = minus(automatonStep(minus(reached, enabledFair_)) & within, reached);  // time passing
        if (idle == bddfalse) return reached;
        addToAll(idle);
        continue;
      }
      const bdd fresh = pending[i];
      pending[i] = bddfalse;
      --waiting;
      const Rule& rule = rules_[order[i]];
      const bdd image = bdd_replace(bdd_appex(fresh, rule.relation, bddop_and, rule.currentSet), rule.toCurrent);
      const bdd added = minus(product ? automatonStep(image) & within : image, reached);
      check();
      if (added == bddfalse) continue;
      addToAll(added);
      if (report && ++images % 1024 == 0) progressOn(reached, passes + 1, product);
      if (report && images % 4096 == 0 && std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
        std::fprintf(stderr, "[symbolic] %llu images: %.0f states, %d nodes, %.1f s\n", static_cast<unsigned long long>(images), count(reached), bdd_nodecount(reached),
                     std::chrono::duration<double>(CpuClock::now() - started_).count());
      }
    }
  }

  // The rules `allowed` marks that can step, deepest first: by the first variable their relation
  // reads or writes, a relation over none (true: the automaton alone moves) counting as the deepest.
  const std::vector<std::uint32_t>& deepestFirst(const std::vector<char>& allowed) {
    auto it = orders_.find(allowed);
    if (it != orders_.end()) return it->second;
    std::vector<std::uint32_t> order;
    for (std::uint32_t r = 0; r < rules_.size(); ++r) {
      if (allowed[r] != 0 && rules_[r].relation != bddfalse) order.push_back(r);
    }
    const auto top = [this](std::uint32_t r) { return rules_[r].relation == bddtrue ? bdd_varnum() : bdd_var(rules_[r].relation); };
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return top(a) > top(b); });
    return orders_.emplace(allowed, std::move(order)).first->second;
  }

  struct Rule {
    bdd guard;       // enabled, on the current state
    bdd relation;    // guard and outcomes, on the current bits and the next bits of what it assigns
    bdd frame;       // the relation with every other variable kept (its next bits equal to its current)
    bdd currentSet;  // the bits of what it assigns
    bddPair* toCurrent = nullptr;
  };

  void check() {
    if (packageError != 0) throw GiveUp(std::string("the decision diagrams: ") + bdd_errstring(packageError));
    const auto now = CpuClock::now();
    if (now > deadline_) throw GiveUp("the time given to the symbolic search ran out");
    if (onProgress_ && now - lastProgress_ >= std::chrono::seconds(1)) {
      lastProgress_ = now;
      Progress p;
      p.states = static_cast<std::uint64_t>(std::min(progressStates_, 1.8e19));
      p.depth = progressRound_;
      p.bytes = static_cast<std::uint64_t>(bdd_getnodenum()) * 20;
      p.seconds = std::chrono::duration<double>(now - started_).count();
      p.counted = true;
      onProgress_(p);
    }
  }
  // What the progress reports say: the states of the set being computed, and its round.
  void progressOn(const bdd& states, std::uint32_t round, bool product = true) {
    if (!onProgress_) return;
    progressStates_ = product ? count(states) : modelStates(states);
    progressRound_ = round;
  }

  // An expression's value table (valuesOf, symbolic_values.hpp), the budget checked as it grows.
  Values values(const ir::Expr& e) {
    return valuesOf(e, layouts_, [this] { check(); });
  }

  void buildAutomaton() {
    automatonRelation_ = bddfalse;
    labels_ = bddfalse;
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      const BuchiState& s = ba_.states[q];
      for (std::uint32_t t : s.successors) automatonRelation_ |= cube(automaton_, q, false) & cube(automaton_, t, true);
      bdd label = bddtrue;
      for (std::size_t k = 0; k < ba_.atoms.size(); ++k) {
        if ((s.mustHold >> k & 1) != 0) label &= truth(values(ba_.atoms[k]));
        if ((s.mustFail >> k & 1) != 0) label &= !truth(values(ba_.atoms[k]));
      }
      labels_ |= cube(automaton_, q, false) & label;
    }
    automatonCurrent_ = bitSet(automaton_, false);
    automatonNext_ = bitSet(automaton_, true);
    automatonToNext_ = bdd_newpair();
    automatonToCurrent_ = bdd_newpair();
    addPairs(automatonToNext_, automaton_, true);
    addPairs(automatonToCurrent_, automaton_, false);
    check();
  }

  Rule compileRule(const ir::Rule& rule) {
    Rule r;
    r.guard = truth(values(rule.guard));
    std::vector<ir::VarId> assigned;
    for (const ir::Branch& b : rule.branches) {
      for (const ir::Assignment& a : b.assignments) assigned.push_back(a.var);
    }
    std::sort(assigned.begin(), assigned.end());
    assigned.erase(std::unique(assigned.begin(), assigned.end()), assigned.end());
    r.toCurrent = bdd_newpair();
    r.currentSet = bddtrue;
    for (ir::VarId v : assigned) {
      addPairs(r.toCurrent, layouts_[v], false);
      r.currentSet &= bitSet(layouts_[v], false);
    }
    bdd outcomes = bddfalse;
    for (const ir::Branch& b : rule.branches) {
      bdd outcome = bddtrue;
      for (ir::VarId v : assigned) {
        const BitLayout& l = layouts_[v];
        const ir::Assignment* a = nullptr;
        for (const ir::Assignment& x : b.assignments) {
          if (x.var == v) a = &x;  // the last one counts, as in the explicit engine
        }
        bdd next = bddfalse;
        if (a == nullptr) {
          for (std::int64_t k = l.min; k <= l.max; ++k) next |= cube(l, k, false) & cube(l, k, true);
        } else {
          for (const auto& [value, when] : values(a->value)) {
            // An outcome leaving the range is none (LivenessOptions::slice).
            if (value >= l.min && value <= l.max) next |= when & cube(l, value, true);
          }
        }
        outcome &= next;
      }
      outcomes |= outcome;
      check();
    }
    r.relation = r.guard & outcomes;
    // The variables kept: an equivalence per bit, three nodes each as a bit's current and next copy
    // are neighbours in the order.
    r.frame = r.relation;
    for (ir::VarId v = 0; v < layouts_.size(); ++v) {
      if (std::binary_search(assigned.begin(), assigned.end(), v)) continue;
      for (int i = 0; i < layouts_[v].bits; ++i) r.frame &= bdd_biimp(bdd_ithvar(bit(layouts_[v], i, false)), bdd_ithvar(bit(layouts_[v], i, true)));
    }
    for (int i = 0; i < automaton_.bits; ++i) r.frame &= bdd_biimp(bdd_ithvar(bit(automaton_, i, false)), bdd_ithvar(bit(automaton_, i, true)));
    check();
    return r;
  }

  const ir::Model& model_;
  const Buchi& ba_;
  const Fairness& fairness_;
  CpuClock::time_point deadline_;
  std::function<void(const Progress&)> onProgress_;
  const CpuClock::time_point started_ = CpuClock::now();
  CpuClock::time_point lastProgress_ = CpuClock::now();
  double progressStates_ = 0;
  std::uint32_t progressRound_ = 0;
  BitLayout automaton_;
  std::vector<BitLayout> layouts_;
  std::vector<Rule> rules_;
  bdd automatonRelation_, labels_, automatonCurrent_, automatonNext_, enabledFair_, currentBits_, nextBits_;
  bddPair* allToNext_ = nullptr;
  bdd loopAutomaton_;  // the automaton states that may lie on an accepted loop
  std::map<std::vector<char>, std::vector<bdd>> clusters_;  // by the rules allowed
  std::map<std::vector<char>, std::vector<std::uint32_t>> orders_;  // by the rules allowed
  bddPair* automatonToNext_ = nullptr;
  bddPair* automatonToCurrent_ = nullptr;
  std::vector<bdd> groupEnabled_;
};

}  // namespace semo::checker::detail
