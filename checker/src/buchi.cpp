#include "semo/checker/buchi.hpp"

#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

namespace semo::checker {

namespace {

// Formulas in negation normal form, interned: equal subformulas share one id, so that the tableau
// can compare sets of ids.
struct Formula {
  enum class Kind : std::uint8_t { True, False, Literal, And, Or, Next, Until, Release };
  Kind kind = Kind::True;
  int a = -1, b = -1;
  int atom = -1;         // Literal: index into Tableau::atoms_
  bool positive = true;  // Literal: the atom, or its negation
};

using Set = std::set<int>;
constexpr int kInit = -1;  // the "incoming" mark of an initial node
constexpr std::size_t kMaxNodes = 100000;  // the tableau is exponential in the formula

struct Node {
  Set incoming, fresh, old, next;  // fresh: still to be processed ("New" in the original paper)
};

class Tableau {
 public:
  Buchi run(const ir::Ltl& f) {
    int root = nnf(f, false);
    expand(root);
    return automaton();
  }

 private:
  int intern(Formula f) {
    auto key = std::make_tuple(f.kind, f.a, f.b, f.atom, f.positive);
    auto [it, added] = ids_.emplace(key, static_cast<int>(formulas_.size()));
    if (added) formulas_.push_back(f);
    return it->second;
  }
  int make(Formula::Kind k, int a = -1, int b = -1) { return intern({k, a, b, -1, true}); }

  // The negation normal form of f (of !f when `negated`).
  int nnf(const ir::Ltl& f, bool negated) {
    using K = ir::Ltl::Kind;
    using F = Formula::Kind;
    switch (f.kind) {
      case K::Atom: {
        if (f.atom.op == ir::Op::Const) return make((f.atom.value != 0) != negated ? F::True : F::False);
        atoms_.push_back(&f.atom);
        return intern({F::Literal, -1, -1, static_cast<int>(atoms_.size() - 1), !negated});
      }
      case K::Not: return nnf(f.args[0], !negated);
      case K::And: return make(negated ? F::Or : F::And, nnf(f.args[0], negated), nnf(f.args[1], negated));
      case K::Or: return make(negated ? F::And : F::Or, nnf(f.args[0], negated), nnf(f.args[1], negated));
      case K::Implies:  // a => b  is  !a || b
        return make(negated ? F::And : F::Or, nnf(f.args[0], !negated), nnf(f.args[1], negated));
      case K::Next: return make(F::Next, nnf(f.args[0], negated));
      case K::Always:  // always a  is  false release a
        return negated ? make(F::Until, make(F::True), nnf(f.args[0], true)) : make(F::Release, make(F::False), nnf(f.args[0], false));
      case K::Eventually:  // eventually a  is  true until a
        return negated ? make(F::Release, make(F::False), nnf(f.args[0], true)) : make(F::Until, make(F::True), nnf(f.args[0], false));
      case K::Until: return make(negated ? F::Release : F::Until, nnf(f.args[0], negated), nnf(f.args[1], negated));
      case K::Release: return make(negated ? F::Until : F::Release, nnf(f.args[0], negated), nnf(f.args[1], negated));
    }
    return make(F::True);
  }

  void expand(int root) {
    std::vector<Node> work{Node{{kInit}, {root}, {}, {}}};
    while (!work.empty()) {
      Node q = std::move(work.back());
      work.pop_back();
      if (q.fresh.empty()) {
        auto same = nodeIndex_.find({q.old, q.next});
        if (same != nodeIndex_.end()) {
          nodes_[same->second].incoming.insert(q.incoming.begin(), q.incoming.end());
          continue;
        }
        if (nodes_.size() >= kMaxNodes) throw std::length_error("a property's automaton has more than 100000 states");
        int id = static_cast<int>(nodes_.size());
        nodeIndex_[{q.old, q.next}] = static_cast<std::size_t>(id);
        work.push_back(Node{{id}, q.next, {}, {}});
        nodes_.push_back(std::move(q));
        continue;
      }
      int eta = *q.fresh.begin();
      q.fresh.erase(q.fresh.begin());
      if (q.old.count(eta) != 0) {
        work.push_back(std::move(q));
        continue;
      }
      const Formula f = formulas_[static_cast<std::size_t>(eta)];
      auto add = [&](Node& n, int g) {
        if (n.old.count(g) == 0) n.fresh.insert(g);
      };
      switch (f.kind) {
        case Formula::Kind::False: break;  // contradiction: the node is dropped
        case Formula::Kind::True:
          q.old.insert(eta);
          work.push_back(std::move(q));
          break;
        case Formula::Kind::Literal: {
          int opposite = intern({Formula::Kind::Literal, -1, -1, f.atom, !f.positive});
          if (q.old.count(opposite) != 0) break;
          q.old.insert(eta);
          work.push_back(std::move(q));
          break;
        }
        case Formula::Kind::And:
          add(q, f.a);
          add(q, f.b);
          q.old.insert(eta);
          work.push_back(std::move(q));
          break;
        case Formula::Kind::Next:
          q.next.insert(f.a);
          q.old.insert(eta);
          work.push_back(std::move(q));
          break;
        case Formula::Kind::Or: case Formula::Kind::Until: case Formula::Kind::Release: {
          Node second = q;
          q.old.insert(eta);
          second.old.insert(eta);
          if (f.kind == Formula::Kind::Or) {
            add(q, f.a);
            add(second, f.b);
          } else if (f.kind == Formula::Kind::Until) {  // a U b: b now, or a now and a U b next
            add(q, f.a);
            q.next.insert(eta);
            add(second, f.b);
          } else {  // a R b: b now and a R b next, or a and b now
            add(q, f.b);
            q.next.insert(eta);
            add(second, f.a);
            add(second, f.b);
          }
          work.push_back(std::move(q));
          work.push_back(std::move(second));
          break;
        }
      }
    }
  }

  Buchi automaton() const {
    Buchi out;
    std::vector<int> untils;
    for (std::size_t i = 0; i < formulas_.size(); ++i) {
      if (formulas_[i].kind == Formula::Kind::Until) untils.push_back(static_cast<int>(i));
    }
    if (untils.size() > 64) throw std::length_error("a property has more than 64 'until'/'eventually' subformulas");
    out.acceptanceSets = untils.empty() ? 1 : untils.size();
    if (atoms_.size() > 64) throw std::length_error("a property has more than 64 state formulas");
    for (const ir::Expr* atom : atoms_) out.atoms.push_back(*atom);
    out.states.resize(nodes_.size());
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const Node& node = nodes_[n];
      BuchiState& s = out.states[n];
      for (int g : node.old) {
        const Formula& f = formulas_[static_cast<std::size_t>(g)];
        if (f.kind != Formula::Kind::Literal) continue;
        (f.positive ? s.mustHold : s.mustFail) |= 1ull << f.atom;
      }
      for (int from : node.incoming) {
        if (from == kInit) s.initial = true;
        else out.states[static_cast<std::size_t>(from)].successors.push_back(static_cast<std::uint32_t>(n));
      }
      if (untils.empty()) s.acceptance = 1;
      for (std::size_t k = 0; k < untils.size(); ++k) {
        // Set k: the until is not pending, or it is fulfilled here.
        const Formula& u = formulas_[static_cast<std::size_t>(untils[k])];
        if (node.old.count(untils[k]) == 0 || node.old.count(u.b) != 0) s.acceptance |= 1ull << k;
      }
    }
    return out;
  }

  std::vector<Formula> formulas_;
  std::map<std::tuple<Formula::Kind, int, int, int, bool>, int> ids_;
  std::vector<const ir::Expr*> atoms_;
  std::vector<Node> nodes_;
  std::map<std::pair<Set, Set>, std::size_t> nodeIndex_;
};

}  // namespace

Buchi buildBuchi(const ir::Ltl& formula) { return Tableau().run(formula); }

std::vector<char> acceptedLoopStates(const Buchi& ba) {
  const std::size_t n = ba.states.size();
  if (n > kMaxLoopAnalysis) return std::vector<char>(n, 1);
  // reaches[q][p]: p is reached from q in one step or more (the automata are small: a search per
  // state is enough).
  std::vector<std::vector<char>> reaches(n, std::vector<char>(n, 0));
  for (std::size_t q = 0; q < n; ++q) {
    std::vector<std::uint32_t> toVisit(ba.states[q].successors);
    while (!toVisit.empty()) {
      const std::uint32_t p = toVisit.back();
      toVisit.pop_back();
      if (reaches[q][p] != 0) continue;
      reaches[q][p] = 1;
      for (std::uint32_t next : ba.states[p].successors) {
        if (reaches[q][next] == 0) toVisit.push_back(next);
      }
    }
  }
  std::vector<char> out(n, 0);
  for (std::size_t q = 0; q < n; ++q) {
    if (reaches[q][q] == 0) continue;  // on no cycle
    std::uint64_t sets = 0;
    for (std::size_t p = 0; p < n; ++p) {
      if (reaches[q][p] != 0 && reaches[p][q] != 0) sets |= ba.states[p].acceptance;
    }
    out[q] = (sets & ba.allSets()) == ba.allSets() ? 1 : 0;
  }
  return out;
}

}  // namespace semo::checker
