#pragma once
// The IR's expressions for the decision diagrams: value tables and the operators on values.
// symbolic_product.hpp compiles guards and assignments with them.
#include <bdd.h>

#include <algorithm>
#include <cstdint>
#include <map>

#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

// The values an expression may take, each with the condition on the current state under which it
// takes it (the conditions are disjoint). Variables have small ranges, so an expression is carried
// as this table rather than as bit vectors: every operator is then evaluated exactly as the
// explicit engine evaluates it, value by value.
using Values = std::map<std::int64_t, bdd>;
inline constexpr std::size_t kMaxValues = 4096;

inline std::int64_t evaluate(ir::Op op, std::int64_t a, std::int64_t b) {
  switch (op) {
    case ir::Op::Add: return a + b;
    case ir::Op::Sub: return a - b;
    case ir::Op::Mul: return a * b;
    case ir::Op::Div: return b == 0 ? 0 : a / b;  // total, as in the explicit and SMT engines
    case ir::Op::Mod: return b == 0 ? 0 : a % b;
    case ir::Op::Min: return std::min(a, b);
    case ir::Op::Max: return std::max(a, b);
    case ir::Op::Eq: return a == b;
    case ir::Op::Ne: return a != b;
    case ir::Op::Lt: return a < b;
    case ir::Op::Le: return a <= b;
    case ir::Op::Gt: return a > b;
    case ir::Op::Ge: return a >= b;
    case ir::Op::And: return a != 0 && b != 0;
    case ir::Op::Or: return a != 0 || b != 0;
    case ir::Op::Implies: return a == 0 || b != 0;
    default: return 0;
  }
}

}  // namespace semo::checker::detail
