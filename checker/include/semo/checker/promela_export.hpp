#pragma once
// The IR as Promela, for cross-checking the explicit engine with SPIN: one atomic step per IR rule,
// so that with reductions off (pan -DNOREDUCE -DSAFETY) SPIN stores exactly the states semo finds,
// and checks the same invariants and end states.
#include <string>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct PromelaOptions {
  // For pan's breadth-first search (-DBFS), which rejects `hidden` variables: the property flags
  // and temporaries become ordinary globals that every step leaves 0, so the state count is the
  // same. Breadth-first order makes a depth bound (-m) mean what `check --max-depth` means.
  bool breadthFirst = false;
  // For the LTL properties instead of the invariants: every step records which rule it was in
  // `semo_last`, a time-passing step is allowed where no fair rule is enabled (as semo's runs may
  // stop there), and each property becomes an `ltl` claim `premise -> property`. The premise is
  // semo's fairness (checker/fairness.hpp) and, for a property on a settling world, that every
  // sensed condition is from some point on decided one way; the model keeps the bookkeeping (a
  // phase counter over the fairness conditions, a guess per strongly fair group, the last answer
  // per sensed condition), so that the premise is three conjuncts whatever the number of groups
  // and SPIN's translation of the claim stays small. `pan -a -N claim` then decides each property.
  bool liveness = false;
};

std::string toPromela(const ir::Model& model, const PromelaOptions& options = {});

}  // namespace semo::checker
