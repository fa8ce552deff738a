#pragma once
// The IR's expressions for the decision diagrams: value tables, the operators on values, and
// where each variable's bits lie. symbolic_product.hpp compiles guards and assignments with them.
#include <bdd.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <vector>

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

// Where a variable's bits lie: its value less `min`, in `bits` bits, most significant first, each
// bit b of the state at variable 2 * (first + b) and its next copy beside it (symbolic_product.hpp).
struct BitLayout {
  int first = 0, bits = 0;
  std::int64_t min = 0, max = 0;
};

inline int bit(const BitLayout& l, int i, bool next) { return 2 * (l.first + i) + (next ? 1 : 0); }

inline bdd cube(const BitLayout& l, std::int64_t value, bool next) {
  bdd c = bddtrue;
  const std::int64_t offset = value - l.min;
  for (int i = 0; i < l.bits; ++i) {
    const bool one = (offset >> (l.bits - 1 - i) & 1) != 0;
    c &= one ? bdd_ithvar(bit(l, i, next)) : bdd_nithvar(bit(l, i, next));
  }
  return c;
}

inline bdd bitSet(const BitLayout& l, bool next) {
  std::vector<int> v;
  for (int i = 0; i < l.bits; ++i) v.push_back(bit(l, i, next));
  return bdd_makeset(v.data(), static_cast<int>(v.size()));
}

inline void addPairs(bddPair* pair, const BitLayout& l, bool toNext) {
  for (int i = 0; i < l.bits; ++i) bdd_setpair(pair, bit(l, i, !toNext), bit(l, i, toNext));
}

// a and not b in one pass: `a & !b` builds the complement of b first, a whole diagram's worth of
// work for a large b (the reached set, at every image of the forward closure).
inline bdd minus(const bdd& a, const bdd& b) { return bdd_apply(a, b, bddop_diff); }

inline bdd truth(const Values& v) {
  bdd t = bddfalse;
  for (const auto& [value, when] : v) {
    if (value != 0) t |= when;
  }
  return t;
}


// Why the symbolic search stopped before its end: a budget, a full node table, an expression too
// wide to tabulate. The search reports it as undecided.
struct GiveUp : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void addValue(Values& to, std::int64_t value, const bdd& when) {
  if (when == bddfalse) return;
  auto [it, added] = to.try_emplace(value, when);
  if (!added) it->second |= when;
  if (to.size() > kMaxValues) throw GiveUp("an expression takes more than 4,096 values");
}

// The value table of an expression over variables laid out as `layouts` says; `check` runs after
// each binary operator (the product of two tables is where the work lies) and may throw to stop.
template <typename Check>
Values valuesOf(const ir::Expr& e, const std::vector<BitLayout>& layouts, const Check& check) {
  Values out;
  switch (e.op) {
    case ir::Op::Const: addValue(out, e.value, bddtrue); return out;
    case ir::Op::Var: {
      const BitLayout& l = layouts[static_cast<ir::VarId>(e.value)];
      for (std::int64_t k = l.min; k <= l.max; ++k) addValue(out, k, cube(l, k, false));
      return out;
    }
    case ir::Op::Not: {
      const bdd holds = truth(valuesOf(e.args[0], layouts, check));
      addValue(out, 1, !holds);
      addValue(out, 0, holds);
      return out;
    }
    case ir::Op::Neg:
      for (const auto& [value, when] : valuesOf(e.args[0], layouts, check)) addValue(out, -value, when);
      return out;
    case ir::Op::Ite: {
      const bdd c = truth(valuesOf(e.args[0], layouts, check));
      for (const auto& [value, when] : valuesOf(e.args[1], layouts, check)) addValue(out, value, c & when);
      for (const auto& [value, when] : valuesOf(e.args[2], layouts, check)) addValue(out, value, (!c) & when);
      return out;
    }
    default: {
      const Values a = valuesOf(e.args[0], layouts, check);
      const Values b = valuesOf(e.args[1], layouts, check);
      for (const auto& [x, wx] : a) {
        for (const auto& [y, wy] : b) addValue(out, evaluate(e.op, x, y), wx & wy);
      }
      check();
      return out;
    }
  }
}

}  // namespace semo::checker::detail
