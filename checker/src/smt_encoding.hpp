#pragma once
// The IR as formulas for Z3: one integer constant per variable per step, the rules as a transition
// relation between consecutive steps (the same IR the explicit engine reads: no second semantics).
// Expressions mean what CompiledModel computes: integers, "true" is non-zero, division and
// remainder truncate toward zero and x / 0 = x % 0 = 0.
#include <cstdint>
#include <string>
#include <vector>

#include <z3++.h>

#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

class SmtEncoding {
 public:
  SmtEncoding(z3::context& ctx, const ir::Model& model);

  // The variables of step k (created on first use).
  const z3::expr_vector& state(std::size_t k);
  // Which rule outcome step k -> k+1 takes (an index into actions()).
  z3::expr action(std::size_t k);

  [[nodiscard]] z3::expr initial(std::size_t k);          // step k is the initial state
  [[nodiscard]] z3::expr inRange(std::size_t k);          // every variable within its declared range
  [[nodiscard]] z3::expr transition(std::size_t k);       // step k -> k+1 by one rule outcome
  // The same relation as one case per rule outcome, without action(k): larger, but the form IC3
  // (Spacer) projects best (several times faster on the examples than transition()).
  [[nodiscard]] z3::expr transitionByCases(std::size_t k);
  // Step k -> k+1 by the rule outcome actions()[action]: its guard, its assignments, the rest kept.
  [[nodiscard]] z3::expr stepBy(std::size_t action, std::size_t k);
  // actions()[action] is enabled at step k and one of its assignments gives a value outside its
  // variable's range (the variables it keeps stay where they are: they need no next step).
  [[nodiscard]] z3::expr stepLeavesRange(std::size_t action, std::size_t k);
  [[nodiscard]] z3::expr holds(const ir::Expr& e, std::size_t k);  // e is true (non-zero) at step k
  [[nodiscard]] z3::expr enabled(std::size_t k);          // some rule is enabled at step k
  [[nodiscard]] z3::expr sameState(std::size_t a, std::size_t b);

  struct Action {
    std::uint32_t rule, branch;
  };
  [[nodiscard]] const std::vector<Action>& actions() const { return actions_; }

 private:
  z3::expr value(const ir::Expr& e, std::size_t k);   // as an integer
  z3::expr truth(const ir::Expr& e, std::size_t k);   // as a Boolean

  z3::context& ctx_;
  const ir::Model& m_;
  std::vector<z3::expr_vector> states_;
  std::vector<Action> actions_;
};

}  // namespace semo::checker::detail
