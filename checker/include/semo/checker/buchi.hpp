#pragma once
// From an LTL formula to a generalized Büchi automaton that accepts exactly the runs satisfying it
// (the tableau construction of Gerth, Peled, Vardi and Wolper). The liveness engine builds the
// automaton of the *negated* property and looks for a fair run of the model it accepts.
#include <cstdint>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct BuchiState {
  // The state of the model read on entering this automaton state must satisfy every literal.
  std::vector<ir::Expr> label;
  std::vector<std::uint32_t> successors;
  bool initial = false;
  std::uint64_t acceptance = 0;  // bit k: member of acceptance set k
};

struct Buchi {
  std::vector<BuchiState> states;
  std::size_t acceptanceSets = 0;  // a run is accepted when it visits every set infinitely often
  [[nodiscard]] std::uint64_t allSets() const {
    return acceptanceSets == 64 ? ~0ull : (1ull << acceptanceSets) - 1;
  }
};

// Throws std::length_error when the formula has more than 64 until/eventually subformulas.
Buchi buildBuchi(const ir::Ltl& formula);

}  // namespace semo::checker
