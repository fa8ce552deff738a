#pragma once
// The IR as Promela, for cross-checking the explicit engine with SPIN: one atomic step per IR rule,
// so that with reductions off (pan -DNOREDUCE -DSAFETY) SPIN stores exactly the states semo finds,
// and checks the same invariants and end states.
#include <string>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

std::string toPromela(const ir::Model& model);

}  // namespace semo::checker
