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
};

std::string toPromela(const ir::Model& model, const PromelaOptions& options = {});

}  // namespace semo::checker
