#pragma once
// Which robots of a model are interchangeable (Symmetry::find): each class of robots, and for each
// swap of its first robot with another, what the swap does to the variables and to the rules.
// Checked on the IR itself, swap by swap, on what each swap moves (checker/README.md, `symmetry`).
#include <cstdint>
#include <string>
#include <vector>

#include "semo/checker/symmetry.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

using VarMap = std::vector<ir::VarId>;  // a permutation of the variables

struct FoundClass {
  std::vector<std::int32_t> robots;
  std::vector<std::vector<ir::VarId>> blocks;         // blocks[i][j]: the j-th variable of robots[i]
  std::vector<VarMap> variableMaps;                   // [i - 1]: the swap of robots[0] and robots[i]
  std::vector<std::vector<std::uint32_t>> ruleMaps;   // [i - 1]: rule r becomes ruleMaps[i - 1][r]
};

std::vector<FoundClass> findClasses(const ir::Model& model, const SymmetryScope& scope = {});

// Robots that look alike: the same variables by name (the robot's own name left out), range and
// initial value, whether or not the model is the same when they are swapped. A hint of where a
// robot's twin keeps its values, not a symmetry (sliced_liveness.cpp refines slices by it;
// scouting's robots look alike in pairs, but their elections tell them apart). blocks[i][j]: the
// j-th variable of robots[i], the same for every robot of the class but for the robot's name.
// Variables that name two robots belong to no block. Linear in the model's variables.
struct LookalikeClass {
  std::vector<std::int32_t> robots;
  std::vector<std::vector<ir::VarId>> blocks;
};
std::vector<LookalikeClass> lookalikeClasses(const ir::Model& model);

// The variables a rule reads or writes.
std::vector<ir::VarId> variablesOf(const ir::Rule& r);

// A text for an expression, with variables renamed by `map`, that is the same for expressions
// equal up to the order of the operands of commutative operators.
std::string canonicalText(const ir::Expr& e, const VarMap& map);

}  // namespace semo::checker::detail
