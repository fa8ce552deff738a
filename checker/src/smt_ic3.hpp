#pragma once
// Unbounded proofs of one safety property with IC3/PDR (Z3's Spacer engine on constrained Horn
// clauses): Reach(s) for the initial state; Reach(s) and a step s -> s' give Reach(s'); Reach(s)
// and the error condition give Error. Spacer either finds an inductive invariant that excludes the
// error, which semo then checks on its own with a plain solver (it holds initially, every step
// keeps it, and it rules the error out) before calling the property proven, or derives the error,
// and returns that derivation's number of steps so that bounded model checking can rebuild the
// counterexample at exactly that depth.
#include <cstdint>
#include <optional>
#include <string>

#include <z3++.h>

#include "smt_encoding.hpp"

namespace semo::checker::detail {

struct Ic3Outcome {
  enum class Kind { Proven, Violated, Unknown };
  Kind kind = Kind::Unknown;
  std::uint32_t depth = 0;      // Violated: steps from the initial state to the error
  std::uint32_t conjuncts = 0;  // Proven: top-level conjuncts of the checked invariant
  std::string note;             // Unknown: why
  // Proven: the invariant over the state's current copy, checked independently; it holds in every
  // reachable state, so later proofs may take their steps from its states only.
  std::optional<z3::expr> invariant;
};

// A transition system over Boolean and integer constants: `current` and `next` are the state's
// copies (same sorts, same order), `inputs` the other constants a step reads (a rule's choice).
struct TransitionSystem {
  z3::expr_vector current, next, inputs;
  z3::expr initial;   // over current
  z3::expr step;      // over current, inputs and next: the form Spacer is given
  z3::expr checkStep; // the same relation, in the form the independent consecution check is given
  z3::expr error;     // over current, inputs and next (an error may be a step)
};

// timeoutMs = 0: no limit.
Ic3Outcome proveWithIc3(z3::context& ctx, const TransitionSystem& system, unsigned timeoutMs);

// The model of `enc` with `error`, which may mention step 0, action 0 and step 1 of `enc` (a range
// error is a step that leaves a range). `assumed`, over step 0, is known to hold in every reachable
// state (proven lemmas): steps and errors are taken from such states only.
Ic3Outcome proveWithIc3(z3::context& ctx, SmtEncoding& enc, const z3::expr& error, unsigned timeoutMs, const z3::expr& assumed);

}  // namespace semo::checker::detail
