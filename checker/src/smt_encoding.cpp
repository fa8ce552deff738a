#include "smt_encoding.hpp"

#include <cstdlib>

namespace semo::checker::detail {

using ir::Op;

SmtEncoding::SmtEncoding(z3::context& ctx, const ir::Model& model) : ctx_(ctx), m_(model) {
  for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
    for (std::uint32_t b = 0; b < model.rules[r].branches.size(); ++b) actions_.push_back({r, b});
  }
}

const z3::expr_vector& SmtEncoding::state(std::size_t k) {
  while (states_.size() <= k) {
    z3::expr_vector vars(ctx_);
    const std::string suffix = "@" + std::to_string(states_.size());
    for (const ir::Variable& v : m_.variables) vars.push_back(ctx_.int_const((v.name + suffix).c_str()));
    states_.push_back(std::move(vars));
  }
  return states_[k];
}

z3::expr SmtEncoding::action(std::size_t k) { return ctx_.int_const(("action@" + std::to_string(k)).c_str()); }

z3::expr SmtEncoding::initial(std::size_t k) {
  const z3::expr_vector& s = state(k);
  z3::expr_vector parts(ctx_);
  for (ir::VarId v = 0; v < m_.variables.size(); ++v) parts.push_back(s[static_cast<int>(v)] == m_.variables[v].init);
  return z3::mk_and(parts);
}

z3::expr SmtEncoding::inRange(std::size_t k) {
  const z3::expr_vector& s = state(k);
  z3::expr_vector parts(ctx_);
  for (ir::VarId v = 0; v < m_.variables.size(); ++v) {
    const ir::Variable& x = m_.variables[v];
    parts.push_back(s[static_cast<int>(v)] >= x.min && s[static_cast<int>(v)] <= x.max);
  }
  return z3::mk_and(parts);
}

z3::expr SmtEncoding::sameState(std::size_t a, std::size_t b) {
  z3::expr_vector parts(ctx_);
  for (ir::VarId v = 0; v < m_.variables.size(); ++v) parts.push_back(state(a)[static_cast<int>(v)] == state(b)[static_cast<int>(v)]);
  return z3::mk_and(parts);
}

z3::expr SmtEncoding::transition(std::size_t k) {
  state(k + 1);
  const z3::expr_vector& now = states_[k];
  const z3::expr_vector& next = states_[k + 1];
  z3::expr act = action(k);
  if (actions_.empty()) return ctx_.bool_val(false);
  // Each variable's next value is one choice over the outcomes that assign it (the others keep it):
  // far smaller than an equation per variable per outcome, which made BMC several times slower.
  z3::expr_vector parts(ctx_);
  parts.push_back(act >= 0 && act < static_cast<int>(actions_.size()));
  std::vector<z3::expr> nextValue;
  nextValue.reserve(m_.variables.size());
  for (ir::VarId v = 0; v < m_.variables.size(); ++v) nextValue.push_back(now[static_cast<int>(v)]);
  for (std::size_t a = actions_.size(); a-- > 0;) {
    const ir::Rule& rule = m_.rules[actions_[a].rule];
    const ir::Branch& branch = rule.branches[actions_[a].branch];
    z3::expr chosen = act == static_cast<int>(a);
    parts.push_back(z3::implies(chosen, truth(rule.guard, k)));
    for (const ir::Assignment& as : branch.assignments) nextValue[as.var] = z3::ite(chosen, value(as.value, k), nextValue[as.var]);
  }
  for (ir::VarId v = 0; v < m_.variables.size(); ++v) parts.push_back(next[static_cast<int>(v)] == nextValue[v]);
  return z3::mk_and(parts);
}

z3::expr SmtEncoding::transitionByCases(std::size_t k) {
  z3::expr_vector cases(ctx_);
  for (std::size_t a = 0; a < actions_.size(); ++a) cases.push_back(stepBy(a, k));
  return z3::mk_or(cases);
}

z3::expr SmtEncoding::stepBy(std::size_t action, std::size_t k) {
  state(k + 1);
  const z3::expr_vector& now = states_[k];
  const z3::expr_vector& next = states_[k + 1];
  const Action& a = actions_[action];
  const ir::Rule& rule = m_.rules[a.rule];
  z3::expr_vector parts(ctx_);
  parts.push_back(truth(rule.guard, k));
  std::vector<char> assigned(m_.variables.size());
  for (const ir::Assignment& as : rule.branches[a.branch].assignments) {
    assigned[as.var] = 1;
    parts.push_back(next[static_cast<int>(as.var)] == value(as.value, k));
  }
  for (ir::VarId v = 0; v < m_.variables.size(); ++v) {
    if (!assigned[v]) parts.push_back(next[static_cast<int>(v)] == now[static_cast<int>(v)]);
  }
  return z3::mk_and(parts);
}

z3::expr SmtEncoding::stepLeavesRange(std::size_t action, std::size_t k) {
  const Action& a = actions_[action];
  const ir::Rule& rule = m_.rules[a.rule];
  z3::expr_vector leaves(ctx_);
  for (const ir::Assignment& as : rule.branches[a.branch].assignments) {
    const ir::Variable& x = m_.variables[as.var];
    const z3::expr v = value(as.value, k);
    leaves.push_back(v < x.min || v > x.max);
  }
  return truth(rule.guard, k) && z3::mk_or(leaves);
}

z3::expr SmtEncoding::enabled(std::size_t k) {
  z3::expr_vector guards(ctx_);
  for (const ir::Rule& r : m_.rules) guards.push_back(truth(r.guard, k));
  return z3::mk_or(guards);
}

z3::expr SmtEncoding::holds(const ir::Expr& e, std::size_t k) { return truth(e, k); }

namespace {
bool isComparisonOrLogic(Op op) {
  switch (op) {
    case Op::Not: case Op::And: case Op::Or: case Op::Implies:
    case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge:
      return true;
    default:
      return false;
  }
}
}  // namespace

z3::expr SmtEncoding::truth(const ir::Expr& e, std::size_t k) {
  switch (e.op) {
    case Op::Const: return ctx_.bool_val(e.value != 0);
    case Op::Not: return !truth(e.args[0], k);
    case Op::And: case Op::Or: {
      // A chain of one connective as one n-ary term, whatever its bracketing (the IR holds chains
      // as balanced trees): the solvers' work depends on the terms' shape.
      std::vector<const ir::Expr*> operands, work{&e};
      while (!work.empty()) {
        const ir::Expr* x = work.back();
        work.pop_back();
        if (x->op != e.op) {
          operands.push_back(x);
          continue;
        }
        for (auto a = x->args.rbegin(); a != x->args.rend(); ++a) work.push_back(&*a);
      }
      z3::expr_vector parts(ctx_);
      for (const ir::Expr* a : operands) parts.push_back(truth(*a, k));
      return e.op == Op::And ? z3::mk_and(parts) : z3::mk_or(parts);
    }
    case Op::Implies: return z3::implies(truth(e.args[0], k), truth(e.args[1], k));
    case Op::Eq: return value(e.args[0], k) == value(e.args[1], k);
    case Op::Ne: return value(e.args[0], k) != value(e.args[1], k);
    case Op::Lt: return value(e.args[0], k) < value(e.args[1], k);
    case Op::Le: return value(e.args[0], k) <= value(e.args[1], k);
    case Op::Gt: return value(e.args[0], k) > value(e.args[1], k);
    case Op::Ge: return value(e.args[0], k) >= value(e.args[1], k);
    case Op::Ite: return z3::ite(truth(e.args[0], k), truth(e.args[1], k), truth(e.args[2], k));
    default: return value(e, k) != 0;
  }
}

z3::expr SmtEncoding::value(const ir::Expr& e, std::size_t k) {
  if (isComparisonOrLogic(e.op)) return z3::ite(truth(e, k), ctx_.int_val(1), ctx_.int_val(0));
  switch (e.op) {
    case Op::Const: return ctx_.int_val(e.value);
    case Op::Var: return state(k)[e.value];
    case Op::Neg: return -value(e.args[0], k);
    case Op::Add: return value(e.args[0], k) + value(e.args[1], k);
    case Op::Sub: return value(e.args[0], k) - value(e.args[1], k);
    case Op::Mul: return value(e.args[0], k) * value(e.args[1], k);
    case Op::Min: {
      z3::expr a = value(e.args[0], k), b = value(e.args[1], k);
      return z3::ite(a <= b, a, b);
    }
    case Op::Max: {
      z3::expr a = value(e.args[0], k), b = value(e.args[1], k);
      return z3::ite(a >= b, a, b);
    }
    case Op::Div: case Op::Mod: {
      z3::expr a = value(e.args[0], k);
      // A divisor variable of a small range: one case per value keeps the arithmetic linear
      // (division by a variable is non-linear, and slow for Z3).
      if (const ir::Expr& d = e.args[1]; d.op == Op::Var || d.op == Op::Const) {
        std::int32_t lo = d.op == Op::Const ? d.value : m_.variables[static_cast<std::size_t>(d.value)].min;
        std::int32_t hi = d.op == Op::Const ? d.value : m_.variables[static_cast<std::size_t>(d.value)].max;
        if (static_cast<std::int64_t>(hi) - lo <= 64) {
          z3::expr b = value(d, k), result = ctx_.int_val(0);  // x / 0 = x % 0 = 0
          z3::expr absA = z3::ite(a >= 0, a, -a);
          for (std::int32_t c = lo; c <= hi; ++c) {
            if (c == 0) continue;
            z3::expr magnitude = absA / std::abs(c);
            z3::expr q = c > 0 ? z3::ite(a >= 0, magnitude, -magnitude) : z3::ite(a >= 0, -magnitude, magnitude);
            result = z3::ite(b == c, e.op == Op::Div ? q : a - q * c, result);
          }
          return result;
        }
      }
      // C's truncating division from Z3's Euclidean one: on magnitudes, then the sign.
      z3::expr b = value(e.args[1], k);
      z3::expr absA = z3::ite(a >= 0, a, -a), absB = z3::ite(b >= 0, b, -b);
      z3::expr q = z3::ite((a >= 0) == (b > 0), absA / absB, -(absA / absB));
      z3::expr result = e.op == Op::Div ? q : a - q * b;
      return z3::ite(b == 0, ctx_.int_val(0), result);
    }
    case Op::Ite: return z3::ite(truth(e.args[0], k), value(e.args[1], k), value(e.args[2], k));
    default: return ctx_.int_val(0);  // unreachable: the comparisons are handled above
  }
}

}  // namespace semo::checker::detail
