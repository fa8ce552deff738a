#pragma once
// An independent check of a lasso counterexample on a model, sharing nothing with the engines that
// find lassos but the compiled guards and updates: from the initial state every step's rule must be
// enabled and lead to the state the trace says; the loop must come back to the state it started
// in; every fairness group (fairness.hpp) must be treated fairly on the loop (a weakly fair one
// taken there or disabled somewhere on it, a strongly fair one taken there or disabled everywhere
// on it; a run that stays for ever in its last state may do so only where no fair rule is enabled);
// on a settling world (ir::Property::settled) the loop decides every sensed condition one way
// only; and the property
// must be false on the run the lasso stands for (the LTL formula on the ultimately periodic word).
// The sliced liveness search reports a lasso only when this check passes; the tests run it on the
// lassos of every engine.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/checker/trace.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct LassoCheck {
  bool valid = false;       // a path of the model from its initial state, and a loop that closes
  std::string why;          // when not valid
  std::vector<std::uint32_t> unfairGroups;  // fairness groups the loop does not treat fairly
  std::vector<std::uint32_t> unsettled;     // settling world: loop steps deciding a sensed condition the other way
  bool violates = false;    // the property is false on the run
  [[nodiscard]] bool counterexample() const { return valid && unfairGroups.empty() && unsettled.empty() && violates; }
};

LassoCheck checkLasso(const ir::Model& model, const Trace& lasso, const ir::Property& property);

// The truth of `f` at the first position of the ultimately periodic run states[0..n-1] whose last
// position is followed by states[loopStart] (loopStart < n). `atom` evaluates a state formula.
template <typename AtomEval>
bool ltlOnLasso(const ir::Ltl& f, std::size_t n, std::size_t loopStart, AtomEval atom);

// Implementation detail of ltlOnLasso: the truth of f at every position.
namespace detail {
template <typename AtomEval>
std::vector<char> ltlPositions(const ir::Ltl& f, std::size_t n, std::size_t loopStart, AtomEval& atom) {
  using K = ir::Ltl::Kind;
  auto next = [&](std::size_t i) { return i + 1 < n ? i + 1 : loopStart; };
  std::vector<char> out(n, 0);
  if (f.kind == K::Atom) {
    for (std::size_t i = 0; i < n; ++i) out[i] = atom(f.atom, i) ? 1 : 0;
    return out;
  }
  std::vector<char> a = ltlPositions(f.args[0], n, loopStart, atom);
  std::vector<char> b = f.args.size() > 1 ? ltlPositions(f.args[1], n, loopStart, atom) : std::vector<char>();
  switch (f.kind) {
    case K::Not: for (std::size_t i = 0; i < n; ++i) out[i] = !a[i]; break;
    case K::And: for (std::size_t i = 0; i < n; ++i) out[i] = a[i] && b[i]; break;
    case K::Or: for (std::size_t i = 0; i < n; ++i) out[i] = a[i] || b[i]; break;
    case K::Implies: for (std::size_t i = 0; i < n; ++i) out[i] = !a[i] || b[i]; break;
    case K::Next: for (std::size_t i = 0; i < n; ++i) out[i] = a[next(i)]; break;
    case K::Eventually:  // least fixed point of x = a || X x
    case K::Until: {     // least fixed point of x = b || (a && X x)
      const std::vector<char>& goal = f.kind == K::Until ? b : a;
      for (bool changed = true; changed;) {  // backward sweeps until stable (two, but for the loop's back edge)
        changed = false;
        for (std::size_t i = n; i-- > 0;) {
          char x = goal[i] || ((f.kind == K::Eventually || a[i]) && out[next(i)]);
          changed = changed || x != out[i];
          out[i] = x;
        }
      }
      break;
    }
    case K::Always:     // greatest fixed point of x = a && X x
    case K::Release: {  // greatest fixed point of x = b && (a || X x)
      const std::vector<char>& hold = f.kind == K::Release ? b : a;
      out.assign(n, 1);
      for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t i = n; i-- > 0;) {
          char x = hold[i] && ((f.kind == K::Release && a[i]) || out[next(i)]);
          changed = changed || x != out[i];
          out[i] = x;
        }
      }
      break;
    }
    case K::Atom: break;
  }
  return out;
}
}  // namespace detail

template <typename AtomEval>
bool ltlOnLasso(const ir::Ltl& f, std::size_t n, std::size_t loopStart, AtomEval atom) {
  return detail::ltlPositions(f, n, loopStart, atom)[0] != 0;
}

}  // namespace semo::checker
