#pragma once
// Liveness decided symbolically, for models whose product is too large to enumerate: the product
// of the model with the Büchi automaton of the property's negation is held as binary decision
// diagrams (BuDDy), and a fair accepting cycle is looked for as a greatest fixpoint in the manner
// of Emerson and Lei, with weak fairness as justice, strong fairness as compassion (the treatment
// of Kesten, Pnueli and Raviv) and a settling world by splitting on the sensed conditions. It says
// whether a fair violation exists, and builds the lasso of one. See specs/ir.md,
// "Symbolic search".
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "semo/checker/explicit_search.hpp"
#include "semo/checker/trace.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

class LoopNarrowing;

struct SymbolicLimits {
  std::uint64_t maxMemoryBytes = 2ull << 30;  // the decision diagrams' node table may not outgrow it
  double seconds = 120;                       // give up after this long
  bool lasso = true;                          // build the lasso of a violation
  // Look only for loops that take no sensing step (a hunt for violations: a loop that senses
  // nothing is settled on any world; "no violation" then proves nothing).
  bool quietLoop = false;
  // With quietLoop: when no quiet loop is found, search every settling world after all (still a
  // hunt: its "no violation" proves nothing about the rules a hunt leaves out).
  bool thenSettled = false;
  // What the model the searched one was cut from can repeat (recurring_rules.hpp): a loop of
  // each world takes only the rules it allows there. Null: every rule the world allows.
  const LoopNarrowing* narrowing = nullptr;
  // On a settling world: search each world with every sensed condition decided (up to six
  // conditions, 64 worlds) instead of splitting from the world that decides nothing.
  bool everyWorld = false;
  // With everyWorld: a forked helper process searches worlds beside this one (shared_worlds.hpp).
  bool worldsHelper = false;
  // Search the fair states first within a superset of the reachable states (projected_reach.hpp,
  // bounded by the model's invariants, which the caller must have proven), and compute the exact
  // reachable states only when fair states found there may be reachable.
  bool overApproximate = false;
  // Called about once a second: the product states reached (or still candidates for a fair
  // cycle), the round as the depth, the node table's bytes.
  std::function<void(const Progress&)> onProgress;
};

struct SymbolicOutcome {
  enum class Kind { NoViolation, Violation, GaveUp };
  Kind kind = Kind::GaveUp;
  // Product states searched (counted, not enumerated): the model's reachable states, each with
  // the automaton states whose labels it satisfies; the exact reachable product states when a
  // loop found there had to be checked against them (specs/ir.md, "Symbolic search").
  double reachable = 0;
  std::uint32_t worlds = 0;  // settled-world splits searched (1 when none was needed)
  // With everyWorld: the sensed conditions left open, each world searched deciding them either
  // way (SettledSearch::pointsLeftOpen in symbolic_liveness.cpp).
  std::uint32_t openPoints = 0;
  // NoViolation found within the superset of SymbolicLimits::overApproximate (`reachable` counts
  // its product states): the model's invariants were assumed.
  bool overApproximated = false;
  std::string why;       // GaveUp: why
  double seconds = 0;
  std::optional<Trace> lasso;  // Violation: a lasso of the model (kind "lasso", loopStart set)
};

// Whether `model` has a fair run violating its property `property` (on a settling world when the
// property asks for one). Thread-safe: the decision-diagram package is one per process; while
// another call holds it, a large model is searched in a child process of its own (the calls run
// side by side), a small one waits its turn.
SymbolicOutcome decideSymbolically(const ir::Model& model, std::size_t property, const SymbolicLimits& limits);

}  // namespace semo::checker::detail
