#pragma once
// From an LTL formula to a generalized Büchi automaton that accepts exactly the runs satisfying it
// (the tableau construction of Gerth, Peled, Vardi and Wolper). The liveness engine builds the
// automaton of the *negated* property and looks for a fair run of the model it accepts.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct BuchiState {
  // The state of the model read on entering this automaton state must satisfy the atoms of
  // `mustHold` and none of `mustFail` (bit k: Buchi::atoms[k]).
  std::uint64_t mustHold = 0, mustFail = 0;
  std::vector<std::uint32_t> successors;
  bool initial = false;
  std::uint64_t acceptance = 0;  // bit k: member of acceptance set k
};

struct Buchi {
  std::vector<ir::Expr> atoms;  // the state formulas the labels speak of (at most 64)
  std::vector<BuchiState> states;
  std::size_t acceptanceSets = 0;  // a run is accepted when it visits every set infinitely often
  [[nodiscard]] std::uint64_t allSets() const {
    return acceptanceSets == 64 ? ~0ull : (1ull << acceptanceSets) - 1;
  }
};

// Throws std::length_error when the formula has more than 64 until/eventually subformulas, more
// than 64 atoms, or an automaton of more than 100000 states.
Buchi buildBuchi(const ir::Ltl& formula);

// Which states may lie on an accepted cycle: those in a strongly connected component that has a
// cycle and a state of every acceptance set. An accepted run ends in such a component, so a search
// for accepted cycles may leave out every other state. An automaton of more than kMaxLoopAnalysis
// states is not analysed (every state is marked).
inline constexpr std::size_t kMaxLoopAnalysis = 1024;
std::vector<char> acceptedLoopStates(const Buchi& ba);

}  // namespace semo::checker
