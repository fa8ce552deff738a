#pragma once
// LTL model checking of the IR's properties under fairness: for each property, the product of the
// model with a Büchi automaton of the property's negation is explored, its strongly connected
// components are searched for a fair accepting cycle, and one found is printed as a lasso (a path,
// then a loop that repeats for ever). Fairness: a weakly fair rule enabled for ever is taken
// eventually; a strongly fair rule enabled again and again is taken again and again (specs/ir.md).
// "Proven" needs the whole product explored; a limit leaves the property "unknown".
#include <cstdint>
#include <string>
#include <vector>

#include "semo/checker/explicit_search.hpp"

namespace semo::checker {

struct LivenessResult {
  std::vector<PropertyResult> properties;  // Model::properties in order
  std::uint64_t states = 0;       // product states, summed over the properties
  std::uint64_t transitions = 0;  // product transitions, summed
  bool complete = true;           // every product explored whole
  std::string limitReached;
  double seconds = 0;
};

// Each property has its own product; up to limits.threads of them are searched at once, each
// within limits.maxStates and an equal share of limits.maxMemoryBytes (one that outgrows its share
// is searched again afterwards, alone, with the whole budget).
LivenessResult checkLiveness(const ir::Model& model, const SearchLimits& limits);

}  // namespace semo::checker
