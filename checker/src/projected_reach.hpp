#pragma once
// A cheap superset of a model's reachable states, for the fair-state search of a property's exact
// cone (symbolic_liveness.cpp): the states whose projection on each part of the variables is one
// the part can reach, within the invariants the check has proven.
#include <bdd.h>

#include "semo/semantics/ir.hpp"
#include "symbolic_product.hpp"

namespace semo::checker::detail {

// The parts: each robot's variables, and each family of variables (the same name after every
// robot's, `burger_0.alive` and `ev3_1.alive`), each with the team's own variables. Each part's set
// starts as the initial state's projection and grows by the projections of each rule's image of
// the conjunction of all parts (and of the model's invariants) until nothing grows: every
// reachable state is in the result, as the initial one is and each step from a state in it lands
// in every part's set. The invariants are those of `model` (ir::Model::invariants), which the
// caller must have proven: a reachable state satisfies them, so leaving out the states that do not
// keeps every reachable one.
//
// Why these parts: a robot's own variables hold its program counters against its flags (a leader
// flag and the arm it stands in); a family holds what the team's rules keep across robots (at most
// one crash among the `alive` flags, with the team's crash count). What no part sees, two leaders
// at once, the proven invariant `unique_leader` rules out. Measured in checker/README.md ("The
// exact cone").
bdd projectedReachable(SymbolicProduct& product, const ir::Model& model);

}  // namespace semo::checker::detail
