#include "symbolic_liveness.hpp"

#include <bdd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "semo/checker/buchi.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/checker/trace.hpp"

namespace semo::checker::detail {
namespace {

using Clock = std::chrono::steady_clock;

// BuDDy keeps one package per process: one search at a time, and its error hook records what went
// wrong (a full node table) instead of ending the process, as BuDDy's default hook does.
std::mutex packageLock;
int packageError = 0;
void recordError(int code) {
  if (packageError == 0) packageError = code;
}

struct GiveUp : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The values an expression may take, each with the condition on the current state under which it
// takes it (the conditions are disjoint). Variables have small ranges, so an expression is carried
// as this table rather than as bit vectors: every operator is then evaluated exactly as the
// explicit engine evaluates it, value by value.
using Values = std::map<std::int64_t, bdd>;
constexpr std::size_t kMaxValues = 4096;

std::int64_t evaluate(ir::Op op, std::int64_t a, std::int64_t b) {
  switch (op) {
    case ir::Op::Add: return a + b;
    case ir::Op::Sub: return a - b;
    case ir::Op::Mul: return a * b;
    case ir::Op::Div: return b == 0 ? 0 : a / b;  // total, as in the explicit and SMT engines
    case ir::Op::Mod: return b == 0 ? 0 : a % b;
    case ir::Op::Min: return std::min(a, b);
    case ir::Op::Max: return std::max(a, b);
    case ir::Op::Eq: return a == b;
    case ir::Op::Ne: return a != b;
    case ir::Op::Lt: return a < b;
    case ir::Op::Le: return a <= b;
    case ir::Op::Gt: return a > b;
    case ir::Op::Ge: return a >= b;
    case ir::Op::And: return a != 0 && b != 0;
    case ir::Op::Or: return a != 0 || b != 0;
    case ir::Op::Implies: return a == 0 || b != 0;
    default: return 0;
  }
}

// The model and the automaton as decision diagrams. Each variable gets the bits of its offset from
// its minimum (most significant first); each bit has a current and a next copy, side by side in
// the variable order, so that a step's relation stays small. The automaton's state comes first.
class SymbolicProduct {
 public:
  SymbolicProduct(const ir::Model& model, const Buchi& ba, const Fairness& fairness, Clock::time_point deadline)
      : model_(model), ba_(ba), fairness_(fairness), deadline_(deadline) {
    int bits = 0;
    auto layOut = [&bits](std::int64_t min, std::int64_t max) {
      Layout l{bits, 0, min, max};
      while ((std::int64_t{1} << l.bits) < max - min + 1) ++l.bits;
      bits += l.bits;
      return l;
    };
    automaton_ = layOut(0, static_cast<std::int64_t>(ba.states.size()) - 1);
    for (const ir::Variable& v : model.variables) layouts_.push_back(layOut(v.min, v.max));
    bdd_setvarnum(std::max(2, 2 * bits));
    check();
    buildAutomaton();
    for (std::uint32_t r = 0; r < model.rules.size(); ++r) rules_.push_back(compileRule(model.rules[r]));
    enabledFair_ = bddfalse;
    for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
      if (model.rules[r].weaklyFair || model.rules[r].stronglyFair) enabledFair_ |= rules_[r].guard;
    }
    groupEnabled_.assign(fairness.groups(), bddfalse);
    for (std::uint32_t g = 0; g < fairness.groups(); ++g) {
      for (std::uint32_t r : fairness.members[g]) groupEnabled_[g] |= rules_[r].guard;
    }
    std::vector<int> all;
    for (int b = 0; b < bits; ++b) all.push_back(2 * b);
    currentBits_ = bdd_makeset(all.data(), static_cast<int>(all.size()));
    check();
  }

  ~SymbolicProduct() {
    for (Rule& r : rules_) bdd_freepair(r.toNext), bdd_freepair(r.toCurrent);
    bdd_freepair(automatonToNext_);
    bdd_freepair(automatonToCurrent_);
  }
  SymbolicProduct(const SymbolicProduct&) = delete;
  SymbolicProduct& operator=(const SymbolicProduct&) = delete;

  // The product states reachable from the initial ones (forward, breadth-first).
  bdd reachable() {
    bdd initial = bddtrue;
    for (ir::VarId v = 0; v < model_.variables.size(); ++v) initial &= cube(layouts_[v], model_.variables[v].init, false);
    bdd start = bddfalse;
    for (std::uint32_t q = 0; q < ba_.states.size(); ++q) {
      if (ba_.states[q].initial) start |= cube(automaton_, q, false);
    }
    bdd reach = initial & start & labels_;
    bdd frontier = reach;
    // Chaining: each rule's product steps are added to the frontier before the next rule is
    // applied, so a round covers many interleavings of independent robots at once.
    int rounds = 0;
    while (frontier != bddfalse) {
      bdd grown = frontier | automatonStep(frontier & !enabledFair_);  // time passing where nothing fair can step
      for (const Rule& r : rules_) {
        grown |= automatonStep(bdd_replace(bdd_appex(grown, r.relation, bddop_and, r.currentSet), r.toCurrent));
        check();
      }
      frontier = grown & !reach;
      reach |= frontier;
      if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) std::fprintf(stderr, "[symbolic] round %d: %.0f states, %d nodes\n", ++rounds, count(reach), bdd_nodecount(reach));
    }
    return reach;
  }

  // The automaton's move on reading the model's new state (the model's step already taken).
  bdd automatonStep(const bdd& moved) {
    const bdd out = bdd_replace(bdd_appex(moved, automatonRelation_, bddop_and, automatonCurrent_), automatonToCurrent_) & labels_;
    check();
    return out;
  }

  // Whether a step leaves a variable's declared range from one of `states` (the explicit engine
  // stops with an error there; this search then gives up instead of deciding).
  bool overflowsFrom(const bdd& states) const {
    for (const Rule& r : rules_) {
      if ((states & r.overflow) != bddfalse) return true;
    }
    return false;
  }

  [[nodiscard]] double count(const bdd& states) const { return bdd_satcountset(states, currentBits_); }

  // The states of `within` from which a fair accepting cycle through `within` exists, the loop
  // using only the rules `allowed` marks (a settled world restricts the loop, not the way to it):
  // the greatest fixpoint of Emerson and Lei. At the fixpoint every state has a successor in the
  // set and reaches, inside it, each acceptance set of the automaton, for each weakly fair group a
  // state where the group is disabled or takes a step, and for each strongly fair rule enabled
  // there a state that takes it (or the rule is never enabled in the set): a bottom strongly
  // connected component of the set is then a fair accepting loop. Conversely the states of any
  // such loop satisfy all of this, so the set is empty exactly when no such loop exists.
  bdd fairStates(bdd z, const std::vector<char>& allowed) {
    std::vector<bdd> acceptance;
    for (std::size_t i = 0; i < ba_.acceptanceSets; ++i) acceptance.push_back(acceptanceSet(i));
    // A group found met by a set stays met while the set does not shrink: `version` counts the
    // shrinkings, and a group met at the current version is not looked at again.
    std::uint64_t version = 0;
    std::vector<std::uint64_t> metAt(fairness_.groups(), UINT64_MAX);
    while (true) {
      const bdd old = z;
      z &= predecessors(z, allowed, nullptr);
      for (const bdd& set : acceptance) z = until(z, z & set, allowed);
      if (z != old) ++version;
      bdd zAfter = automatonPredecessors(z);  // shared by the groups until z shrinks
      bdd zAfterOf = z;
      for (std::uint32_t g = 0; g < fairness_.groups() && z != bddfalse; ++g) {
        if (metAt[g] == version || (z & groupEnabled_[g]) == bddfalse) continue;
        if (zAfterOf != z) zAfter = automatonPredecessors(z), zAfterOf = z;
        const bdd taken = z & modelPredecessors(zAfter, allowed, &fairness_.members[g]);
        const bdd before = z;
        if (fairness_.strong[g] != 0) {
          z = (z & !groupEnabled_[g]) | until(z, taken, allowed);
        } else {
          const bdd good = (z & !groupEnabled_[g]) | taken;
          if (good != z) z = until(z, good, allowed);
        }
        if (z == before) metAt[g] = version;
        else ++version;
      }
      if (z == old) return z;
    }
  }

  // Whether rule r steps from a state of `z` to one of `z` (product steps; `zAfter` is
  // automatonPredecessors(z)).
  bool stepsWithin(const bdd& z, const bdd& zAfter, std::uint32_t r) {
    const bdd from = bdd_appex(rules_[r].relation, bdd_replace(zAfter, rules_[r].toNext), bddop_and, rules_[r].nextSet);
    check();
    return (z & from) != bddfalse;
  }

  // The states with a product step into `z`: by the rules `only` lists (all when null) that
  // `allowed` marks, or, with all of them, by time passing.
  bdd predecessors(const bdd& z, const std::vector<char>& allowed, const std::vector<std::uint32_t>* only) {
    return modelPredecessors(automatonPredecessors(z), allowed, only);
  }

  // The automaton moves on reading the model's new state: a product step into `z` is a model step
  // into these (the model's new state, the automaton's state before).
  bdd automatonPredecessors(const bdd& z) {
    const bdd out = bdd_appex(automatonRelation_, bdd_replace(z, automatonToNext_), bddop_and, automatonNext_);
    check();
    return out;
  }

  bdd modelPredecessors(const bdd& afterModel, const std::vector<char>& allowed, const std::vector<std::uint32_t>* only) {
    bdd out = bddfalse;
    auto back = [&](std::uint32_t r) {
      if (allowed[r] == 0) return;
      out |= bdd_appex(rules_[r].relation, bdd_replace(afterModel, rules_[r].toNext), bddop_and, rules_[r].nextSet);
      check();
    };
    if (only != nullptr) {
      for (std::uint32_t r : *only) back(r);
      return out;
    }
    for (std::uint32_t r = 0; r < rules_.size(); ++r) back(r);
    return out | (afterModel & !enabledFair_);
  }

  // The states of `within` reachable from `from` by product steps of the rules `allowed` marks.
  bdd forwardClosure(const bdd& from, const bdd& within, const std::vector<char>& allowed) {
    bdd reached = from & within;
    bdd frontier = reached;
    while (frontier != bddfalse) {  // chained, as the reachable states
      bdd grown = frontier | (automatonStep(frontier & !enabledFair_) & within);
      for (std::uint32_t r = 0; r < rules_.size(); ++r) {
        if (allowed[r] == 0) continue;
        grown |= automatonStep(bdd_replace(bdd_appex(grown, rules_[r].relation, bddop_and, rules_[r].currentSet), rules_[r].toCurrent)) & within;
        check();
      }
      frontier = grown & !reached;
      reached |= frontier;
    }
    return reached;
  }

  // E[z U goal]: the states of z from which a path inside z reaches `goal` (a subset of z).
  // Chained, as the forward search: what one rule finds is looked back from by the next.
  bdd until(const bdd& z, const bdd& goal, const std::vector<char>& allowed) {
    bdd reached = goal;
    bdd frontier = goal;
    while (frontier != bddfalse) {
      bdd after = automatonPredecessors(frontier);
      bdd fresh = z & after & !enabledFair_ & !reached;  // time passing
      reached |= fresh;
      after |= automatonPredecessors(fresh);
      for (std::uint32_t r = 0; r < rules_.size(); ++r) {
        if (allowed[r] == 0) continue;
        const bdd found = z & bdd_appex(rules_[r].relation, bdd_replace(after, rules_[r].toNext), bddop_and, rules_[r].nextSet) & !reached;
        check();
        if (found == bddfalse) continue;
        reached |= found;
        fresh |= found;
        after |= automatonPredecessors(found);
      }
      frontier = fresh;
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
    auto read = [&](const Layout& l) {
      std::int64_t offset = 0;
      for (int i = 0; i < l.bits; ++i) offset = offset << 1 | ((one & bdd_nithvar(bit(l, i, false))) == bddfalse ? 1 : 0);
      return l.min + offset;
    };
    for (const Layout& l : layouts_) c.values.push_back(read(l));
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

  struct Layout {
    int first = 0, bits = 0;
    std::int64_t min = 0, max = 0;
  };
  struct Rule {
    bdd guard;       // enabled, on the current state
    bdd relation;    // guard and outcomes, on the current bits and the next bits of what it assigns
    bdd currentSet, nextSet;  // the bits of what it assigns
    bddPair* toNext = nullptr;
    bddPair* toCurrent = nullptr;
    bdd overflow;    // current states where an outcome leaves a declared range
  };

  void check() const {
    if (packageError != 0) throw GiveUp(std::string("the decision diagrams: ") + bdd_errstring(packageError));
    if (Clock::now() > deadline_) throw GiveUp("the time given to the symbolic search ran out");
  }

  static int bit(const Layout& l, int i, bool next) { return 2 * (l.first + i) + (next ? 1 : 0); }

  static bdd cube(const Layout& l, std::int64_t value, bool next) {
    bdd c = bddtrue;
    const std::int64_t offset = value - l.min;
    for (int i = 0; i < l.bits; ++i) {
      const bool one = (offset >> (l.bits - 1 - i) & 1) != 0;
      c &= one ? bdd_ithvar(bit(l, i, next)) : bdd_nithvar(bit(l, i, next));
    }
    return c;
  }

  static bdd bitSet(const Layout& l, bool next) {
    std::vector<int> v;
    for (int i = 0; i < l.bits; ++i) v.push_back(bit(l, i, next));
    return bdd_makeset(v.data(), static_cast<int>(v.size()));
  }

  static void addPairs(bddPair* pair, const Layout& l, bool toNext) {
    for (int i = 0; i < l.bits; ++i) bdd_setpair(pair, bit(l, i, !toNext), bit(l, i, toNext));
  }

  static bdd truth(const Values& v) {
    bdd t = bddfalse;
    for (const auto& [value, when] : v) {
      if (value != 0) t |= when;
    }
    return t;
  }

  static void add(Values& to, std::int64_t value, const bdd& when) {
    if (when == bddfalse) return;
    auto [it, added] = to.try_emplace(value, when);
    if (!added) it->second |= when;
    if (to.size() > kMaxValues) throw GiveUp("an expression takes more than 4,096 values");
  }

  Values values(const ir::Expr& e) {
    Values out;
    switch (e.op) {
      case ir::Op::Const: add(out, e.value, bddtrue); return out;
      case ir::Op::Var: {
        const Layout& l = layouts_[static_cast<ir::VarId>(e.value)];
        for (std::int64_t k = l.min; k <= l.max; ++k) add(out, k, cube(l, k, false));
        return out;
      }
      case ir::Op::Not:
        add(out, 1, !truth(values(e.args[0])));
        add(out, 0, truth(values(e.args[0])));
        return out;
      case ir::Op::Neg:
        for (const auto& [value, when] : values(e.args[0])) add(out, -value, when);
        return out;
      case ir::Op::Ite: {
        const bdd c = truth(values(e.args[0]));
        for (const auto& [value, when] : values(e.args[1])) add(out, value, c & when);
        for (const auto& [value, when] : values(e.args[2])) add(out, value, (!c) & when);
        return out;
      }
      default: {
        const Values a = values(e.args[0]);
        const Values b = values(e.args[1]);
        for (const auto& [x, wx] : a) {
          for (const auto& [y, wy] : b) add(out, evaluate(e.op, x, y), wx & wy);
        }
        check();
        return out;
      }
    }
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
    r.toNext = bdd_newpair();
    r.toCurrent = bdd_newpair();
    r.currentSet = bddtrue;
    r.nextSet = bddtrue;
    for (ir::VarId v : assigned) {
      addPairs(r.toNext, layouts_[v], true);
      addPairs(r.toCurrent, layouts_[v], false);
      r.currentSet &= bitSet(layouts_[v], false);
      r.nextSet &= bitSet(layouts_[v], true);
    }
    bdd outcomes = bddfalse;
    r.overflow = bddfalse;
    for (const ir::Branch& b : rule.branches) {
      bdd outcome = bddtrue;
      for (ir::VarId v : assigned) {
        const Layout& l = layouts_[v];
        const ir::Assignment* a = nullptr;
        for (const ir::Assignment& x : b.assignments) {
          if (x.var == v) a = &x;  // the last one counts, as in the explicit engine
        }
        bdd next = bddfalse;
        if (a == nullptr) {
          for (std::int64_t k = l.min; k <= l.max; ++k) next |= cube(l, k, false) & cube(l, k, true);
        } else {
          for (const auto& [value, when] : values(a->value)) {
            if (value < l.min || value > l.max) r.overflow |= when;
            else next |= when & cube(l, value, true);
          }
        }
        outcome &= next;
      }
      outcomes |= outcome;
      check();
    }
    r.relation = r.guard & outcomes;
    r.overflow &= r.guard;
    check();
    return r;
  }

  const ir::Model& model_;
  const Buchi& ba_;
  const Fairness& fairness_;
  const Clock::time_point deadline_;
  Layout automaton_;
  std::vector<Layout> layouts_;
  std::vector<Rule> rules_;
  bdd automatonRelation_, labels_, automatonCurrent_, automatonNext_, enabledFair_, currentBits_;
  bddPair* automatonToNext_ = nullptr;
  bddPair* automatonToCurrent_ = nullptr;
  std::vector<bdd> groupEnabled_;
};

// A loop on a settling world decides each sensed condition one way only. The fair states are
// first found with every rule allowed in the loop; where their steps decide a condition both ways,
// the search splits in two (the loop decides it one way, or the other), each from the states found,
// as the explicit engine splits a strongly connected component.
constexpr std::uint32_t kMaxWorlds = 512;

class SettledSearch {
 public:
  SettledSearch(SymbolicProduct& product, const Sensing& sensing, std::size_t rules)
      : product_(product), sensing_(sensing), rules_(rules) {}

  bool violated(const bdd& reach, bool settled) {
    std::vector<std::int8_t> world(settled ? sensing_.points : 0, -1);
    return search(reach, world);
  }
  [[nodiscard]] std::uint32_t worlds() const { return worlds_; }
  // After a violation: the fair states of the world it was found in, and the rules its loop may use.
  [[nodiscard]] const bdd& fairStates() const { return found_; }
  [[nodiscard]] const std::vector<char>& loopRules() const { return foundAllowed_; }

 private:
  bool search(const bdd& from, std::vector<std::int8_t>& world) {
    if (++worlds_ > kMaxWorlds) throw GiveUp("more than 512 ways the world may settle had to be searched");
    std::vector<char> allowed(rules_, 1);
    for (std::uint32_t r = 0; r < rules_; ++r) allowed[r] = world.empty() || sensing_.agrees(r, world) ? 1 : 0;
    const bdd z = product_.fairStates(from, allowed);
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) std::fprintf(stderr, "[symbolic] world %u: %.0f fair states\n", worlds_, product_.count(z));
    if (z == bddfalse) return false;
    found_ = z;
    foundAllowed_ = allowed;
    const bdd zAfter = product_.automatonPredecessors(z);
    for (std::uint32_t p = 0; p < world.size(); ++p) {
      if (world[p] >= 0) continue;
      bool decides[2] = {false, false};
      for (std::uint32_t r = 0; r < rules_ && !(decides[0] && decides[1]); ++r) {
        if (allowed[r] == 0) continue;
        for (const Sensing::Decision& d : sensing_.of[r]) {
          if (d.point == p && !decides[d.holds ? 1 : 0] && product_.stepsWithin(z, zAfter, r)) decides[d.holds ? 1 : 0] = true;
        }
      }
      if (!(decides[0] && decides[1])) continue;
      for (std::int8_t way : {std::int8_t{1}, std::int8_t{0}}) {
        world[p] = way;
        const bool found = search(z, world);
        world[p] = -1;
        if (found) return true;
      }
      return false;
    }
    return true;  // no step inside decides a condition both ways
  }

  SymbolicProduct& product_;
  const Sensing& sensing_;
  const std::size_t rules_;
  std::uint32_t worlds_ = 0;
  bdd found_;
  std::vector<char> foundAllowed_;
};

// A lasso through the fair states a search found, as the explicit engine prints one: the shortest
// way in, then (inside a bottom component of the fair states, where every way stays fair) a loop
// that meets each obligation in turn: each acceptance set, each weakly fair group disabled or
// taken, each strongly fair rule enabled there taken. Each step is taken concretely, the decision
// diagrams only saying which states lead on.
class SymbolicLasso {
 public:
  using Concrete = SymbolicProduct::Concrete;
  using Move = SymbolicProduct::Move;

  explicit SymbolicLasso(SymbolicProduct& product) : p_(product), all_(product.rules(), 1) {}

  Trace build(const bdd& reach, const bdd& fair, const std::vector<char>& loopRules) {
    // From an initial state that leads to the fair states (the automaton may have several).
    current_ = p_.initialState(p_.until(reach, fair, all_));
    initial_ = current_.values;
    walkTo(fair, reach, all_);
    // Into a bottom component: one from which nothing else of the fair states is reached. The
    // bottom components reached from a state that is not in one are among the states it reaches
    // but that do not reach it back (a set no step leaves): the search narrows to them.
    bdd region = p_.forwardClosure(p_.cubeOf(current_), fair, loopRules);
    bdd here = p_.cubeOf(current_);
    bdd component;
    while (true) {
      component = p_.forwardClosure(here, region, loopRules);
      const bdd beyond = component & !p_.until(region, here, loopRules);
      if (beyond == bddfalse) break;
      region = beyond;
      here = p_.cubeOf(p_.pick(beyond));
    }
    walkTo(component, fair, loopRules);
    const std::size_t loopStart = moves_.size();
    const Concrete entry = current_;
    for (std::size_t i = 0; i < p_.acceptanceSets(); ++i) walkTo(component & p_.acceptanceSet(i), component, loopRules);
    const Fairness& f = p_.fairness();
    for (std::uint32_t g = 0; g < f.groups(); ++g) {
      const bdd enabled = component & p_.groupEnabled(g);
      if (enabled == bddfalse) continue;
      if (f.strong[g] == 0 && (component & !p_.groupEnabled(g)) != bddfalse) {
        walkTo(component & !p_.groupEnabled(g), component, loopRules);
        continue;
      }
      // Taken: to a state that takes the group's step inside the component, then that step.
      walkTo(component & p_.predecessors(component, loopRules, &f.members[g]), component, loopRules);
      std::vector<char> only(p_.rules(), 0);
      for (std::uint32_t r : f.members[g]) only[r] = loopRules[r];
      take(component, only);
    }
    if (moves_.size() == loopStart) take(component, loopRules);  // a loop has at least one step
    walkTo(p_.cubeOf(entry), component, loopRules);
    return trace(loopStart);
  }

 private:
  // Along a shortest path inside `within` to a state of `goal` (which it reaches).
  void walkTo(const bdd& goal, const bdd& within, const std::vector<char>& allowed) {
    std::vector<bdd> rings{goal & within};
    bdd covered = rings.back();
    while (!p_.contains(covered, current_)) {
      bdd next = within & p_.predecessors(rings.back(), allowed, nullptr) & !covered;
      if (next == bddfalse) throw std::logic_error("symbolic lasso: the goal is out of reach");
      rings.push_back(next);
      covered |= next;
    }
    std::size_t k = rings.size() - 1;
    while (!p_.contains(rings[k], current_)) --k;
    for (; k > 0; --k) take(rings[k - 1], allowed);
  }

  // One step to a state of `into`.
  void take(const bdd& into, const std::vector<char>& allowed) {
    for (Move& m : p_.moves(current_, allowed)) {
      if (!p_.contains(into, m.after)) continue;
      current_ = m.after;
      moves_.push_back(std::move(m));
      return;
    }
    throw std::logic_error("symbolic lasso: no step into the next ring");
  }

  // Time passing is no step of the trace (the run has ended, or the automaton alone moved).
  Trace trace(std::size_t loopStart) const {
    Trace t;
    t.kind = "lasso";
    for (std::int64_t v : initial_) t.initial.push_back(static_cast<std::int32_t>(v));
    std::vector<std::int64_t> before = initial_;
    for (std::size_t k = 0; k < moves_.size(); ++k) {
      if (k == loopStart) t.loopStart = t.steps.size();
      const Move& m = moves_[k];
      if (m.rule == SymbolicProduct::kTimePasses) continue;
      Step step{m.rule, m.branch, {}};
      for (ir::VarId v = 0; v < before.size(); ++v) {
        if (before[v] != m.after.values[v]) step.changes.push_back({v, static_cast<std::int32_t>(before[v]), static_cast<std::int32_t>(m.after.values[v])});
      }
      t.steps.push_back(std::move(step));
      before = m.after.values;
    }
    if (loopStart >= moves_.size()) t.loopStart = t.steps.size();
    return t;
  }

  SymbolicProduct& p_;
  const std::vector<char> all_;
  Concrete current_;
  std::vector<std::int64_t> initial_;
  std::vector<Move> moves_;
};

}  // namespace

SymbolicOutcome decideSymbolically(const ir::Model& model, std::size_t property, const SymbolicLimits& limits) {
  SymbolicOutcome out;
  const ir::Property& prop = model.properties.at(property);
  Buchi ba;
  try {
    ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, prop.formula));
  } catch (const std::length_error& e) {
    out.why = e.what();
    return out;
  }
  const Fairness fairness = Fairness::of(model);
  const Sensing sensing = Sensing::in(model);
  std::lock_guard<std::mutex> hold(packageLock);
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits.seconds));
  packageError = 0;
  // BuDDy's node: about 20 bytes, and its operation caches a quarter as many entries again.
  const std::uint64_t nodes = std::clamp<std::uint64_t>(limits.maxMemoryBytes / 32, 10'000, 1u << 28);
  // A small table for a small model (the tests search hundreds), a larger one for a large model;
  // it grows by up to four million nodes at a time.
  std::size_t bits = 0;
  for (const ir::Variable& v : model.variables) bits += static_cast<std::size_t>(std::bit_width(static_cast<std::uint64_t>(v.max - v.min)));
  const std::uint64_t first = bits > 32 ? 1u << 20 : 1u << 16;
  bdd_init(static_cast<int>(std::min(nodes, first)), static_cast<int>(first / 4));
  bdd_setmaxincrease(1 << 22);
  bdd_error_hook(recordError);
  bdd_gbc_hook(nullptr);
  bdd_resize_hook(nullptr);
  bdd_setmaxnodenum(static_cast<int>(nodes));
  bdd_setcacheratio(4);
  try {
    SymbolicProduct product(model, ba, fairness, deadline);
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] %zu rules compiled, %.1f s\n", model.rules.size(), std::chrono::duration<double>(Clock::now() - start).count());
    }
    const bdd reach = product.reachable();
    out.reachable = product.count(reach);
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] reachable: %.0f states, %d nodes, %.1f s\n", out.reachable, bdd_nodecount(reach),
                   std::chrono::duration<double>(Clock::now() - start).count());
    }
    if (product.overflowsFrom(reach)) throw GiveUp("an update leaves a variable's declared range");
    SettledSearch search(product, sensing, model.rules.size());
    const bool violated = search.violated(reach, prop.settled);
    out.worlds = search.worlds();
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] fair states searched in %u worlds: %s, %.1f s\n", out.worlds, violated ? "some" : "none",
                   std::chrono::duration<double>(Clock::now() - start).count());
    }
    out.kind = violated ? SymbolicOutcome::Kind::Violation : SymbolicOutcome::Kind::NoViolation;
    if (violated && limits.lasso) {
      out.lasso = SymbolicLasso(product).build(reach, search.fairStates(), search.loopRules());
      out.lasso->property = prop.name;
    }
  } catch (const GiveUp& e) {
    out.kind = SymbolicOutcome::Kind::GaveUp;
    out.why = e.what();
  } catch (const std::logic_error& e) {  // a lasso that could not be built: no verdict
    out = SymbolicOutcome{};
    out.why = std::string("internal error: ") + e.what();
  }
  bdd_done();
  packageError = 0;
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace semo::checker::detail
