#include "semo/checker/compiled_model.hpp"

#include <algorithm>
#include <bit>
#include <optional>

namespace semo::checker {

Program::Program(const ir::Expr& e) {
  compile(e);
}

void Program::compile(const ir::Expr& e) {
  using ir::Op;
  if (e.op == Op::And || e.op == Op::Or || e.op == Op::Implies) {
    compile(e.args[0]);
    std::size_t jump = code_.size();
    code_.push_back({static_cast<std::uint8_t>(e.op == Op::And ? kJumpIfFalse : e.op == Op::Or ? kJumpIfTrue : kJumpIfFalseTrue), 0});
    --depth_;  // popped when not taken
    compile(e.args[1]);
    code_.push_back({kTruth, 0});
    code_[jump].operand = static_cast<std::int32_t>(code_.size());
    return;
  }
  // The other operators evaluate every operand; `?:` too, which is exact without side effects.
  for (const ir::Expr& a : e.args) compile(a);
  code_.push_back({static_cast<std::uint8_t>(e.op), e.value});
  if (e.op == Op::Const || e.op == Op::Var) {
    maxStack_ = std::max(maxStack_, ++depth_);
  } else {
    depth_ -= e.args.size() - 1;
  }
}

Value Program::eval(const Value* vars) const {
  // Most updates are a constant (a program counter) or a copy of a variable.
  if (code_.size() == 1) return code_[0].op == static_cast<std::uint8_t>(ir::Op::Const) ? code_[0].operand : vars[code_[0].operand];
  constexpr std::size_t kInline = 64;
  Value inlineStack[kInline];
  std::vector<Value> heap;
  Value* stack = inlineStack;
  if (maxStack_ > kInline) {
    heap.resize(maxStack_);
    stack = heap.data();
  }
  std::size_t sp = 0;
  const std::size_t n = code_.size();
  for (std::size_t pc = 0; pc < n; ++pc) {
    const Instr& in = code_[pc];
    switch (in.op) {
      case kJumpIfFalse:
        if (stack[sp - 1] == 0) pc = static_cast<std::size_t>(in.operand) - 1;
        else --sp;
        continue;
      case kJumpIfTrue:
        if (stack[sp - 1] != 0) stack[sp - 1] = 1, pc = static_cast<std::size_t>(in.operand) - 1;
        else --sp;
        continue;
      case kJumpIfFalseTrue:
        if (stack[sp - 1] == 0) stack[sp - 1] = 1, pc = static_cast<std::size_t>(in.operand) - 1;
        else --sp;
        continue;
      case kTruth: stack[sp - 1] = stack[sp - 1] != 0; continue;
      default: break;
    }
    switch (static_cast<ir::Op>(in.op)) {
      case ir::Op::Const: stack[sp++] = in.operand; break;
      case ir::Op::Var: stack[sp++] = vars[in.operand]; break;
      case ir::Op::Not: stack[sp - 1] = stack[sp - 1] == 0; break;
      case ir::Op::Neg: stack[sp - 1] = -stack[sp - 1]; break;
      case ir::Op::Ite: {
        Value e = stack[--sp], t = stack[--sp];
        stack[sp - 1] = stack[sp - 1] != 0 ? t : e;
        break;
      }
      default: {
        Value b = stack[--sp];
        Value& a = stack[sp - 1];
        switch (static_cast<ir::Op>(in.op)) {
          case ir::Op::Add: a = a + b; break;
          case ir::Op::Sub: a = a - b; break;
          case ir::Op::Mul: a = a * b; break;
          case ir::Op::Div: a = b == 0 ? 0 : a / b; break;  // total: x/0 = 0, as in the SMT encoding
          case ir::Op::Mod: a = b == 0 ? 0 : a % b; break;
          case ir::Op::Min: a = std::min(a, b); break;
          case ir::Op::Max: a = std::max(a, b); break;
          case ir::Op::Eq: a = a == b; break;
          case ir::Op::Ne: a = a != b; break;
          case ir::Op::Lt: a = a < b; break;
          case ir::Op::Le: a = a <= b; break;
          case ir::Op::Gt: a = a > b; break;
          case ir::Op::Ge: a = a >= b; break;
          default: break;
        }
      }
    }
  }
  return stack[0];
}

Condition::Condition(const ir::Expr& e) { add(e); }

void Condition::add(const ir::Expr& e) {
  using ir::Op;
  if (e.op == Op::And) {
    add(e.args[0]);
    add(e.args[1]);
    return;
  }
  if (e.op == Op::Const) {
    if (e.value == 0) rest_.emplace_back(e);  // never holds
    return;
  }
  if (e.op == Op::Var) return tests_.push_back({static_cast<ir::VarId>(e.value), Op::Ne, 0});
  if (e.op == Op::Not && e.args[0].op == Op::Var) return tests_.push_back({static_cast<ir::VarId>(e.args[0].value), Op::Eq, 0});
  bool comparison = e.op == Op::Eq || e.op == Op::Ne || e.op == Op::Lt || e.op == Op::Le || e.op == Op::Gt || e.op == Op::Ge;
  if (comparison && e.args[0].op == Op::Var && e.args[1].op == Op::Const) {
    return tests_.push_back({static_cast<ir::VarId>(e.args[0].value), e.op, e.args[1].value});
  }
  if (comparison && e.args[1].op == Op::Var && e.args[0].op == Op::Const) {
    // c < v  is  v > c, and so on.
    Op mirrored = e.op == Op::Lt ? Op::Gt : e.op == Op::Le ? Op::Ge : e.op == Op::Gt ? Op::Lt : e.op == Op::Ge ? Op::Le : e.op;
    return tests_.push_back({static_cast<ir::VarId>(e.args[1].value), mirrored, e.args[0].value});
  }
  // A disjunction of such comparisons (the barriers: `!alive || !(pc > a && pc < b)` for each other
  // robot) is a clause of tests.
  std::vector<Test> clause;
  if ((e.op == Op::Or || e.op == Op::Not || e.op == Op::Implies) && disjunction(e, false, clause) && !clause.empty()) {
    clauses_.push_back({static_cast<std::uint32_t>(clauseTests_.size()), static_cast<std::uint32_t>(clauseTests_.size() + clause.size())});
    clauseTests_.insert(clauseTests_.end(), clause.begin(), clause.end());
    return;
  }
  rest_.emplace_back(e);
}

bool Condition::disjunction(const ir::Expr& e, bool negated, std::vector<Test>& out) {
  using ir::Op;
  auto flip = [](Op op) {
    switch (op) {
      case Op::Eq: return Op::Ne;
      case Op::Ne: return Op::Eq;
      case Op::Lt: return Op::Ge;
      case Op::Le: return Op::Gt;
      case Op::Gt: return Op::Le;
      default: return Op::Lt;  // Ge
    }
  };
  switch (e.op) {
    case Op::Not: return disjunction(e.args[0], !negated, out);
    case Op::Or:   // a || b, or under negation !a && !b (not a disjunction)
      return !negated && disjunction(e.args[0], false, out) && disjunction(e.args[1], false, out);
    case Op::And:  // !(a && b) is !a || !b
      return negated && disjunction(e.args[0], true, out) && disjunction(e.args[1], true, out);
    case Op::Implies:  // a => b is !a || b
      return !negated && disjunction(e.args[0], true, out) && disjunction(e.args[1], false, out);
    case Op::Var:
      out.push_back({static_cast<ir::VarId>(e.value), negated ? Op::Eq : Op::Ne, 0});
      return true;
    case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: {
      Op op = e.op;
      const ir::Expr *var = &e.args[0], *constant = &e.args[1];
      if (var->op == Op::Const && constant->op == Op::Var) {
        std::swap(var, constant);
        op = op == Op::Lt ? Op::Gt : op == Op::Le ? Op::Ge : op == Op::Gt ? Op::Lt : op == Op::Ge ? Op::Le : op;
      }
      if (var->op != Op::Var || constant->op != Op::Const) return false;
      out.push_back({static_cast<ir::VarId>(var->value), negated ? flip(op) : op, constant->value});
      return true;
    }
    default: return false;
  }
}

StateLayout::StateLayout(const ir::Model& model) {
  std::uint32_t word = 0, shift = 0;
  for (const ir::Variable& v : model.variables) {
    auto span = static_cast<std::uint64_t>(static_cast<std::int64_t>(v.max) - v.min);
    auto width = static_cast<std::uint32_t>(span == 0 ? 0 : std::bit_width(span));
    if (shift + width > 64) {
      ++word;
      shift = 0;
    }
    fields_.push_back({word, shift, width, v.min});
    shift += width;
    bits_ += width;
  }
  words_ = word + 1;
}

void StateLayout::pack(const Value* values, std::uint64_t* out) const {
  std::fill(out, out + words_, 0);
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    const Field& f = fields_[i];
    out[f.word] |= static_cast<std::uint64_t>(static_cast<std::int64_t>(values[i]) - f.min) << f.shift;
  }
}

void StateLayout::unpack(const std::uint64_t* in, Value* values) const {
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    const Field& f = fields_[i];
    std::uint64_t mask = f.width == 64 ? ~0ull : ((1ull << f.width) - 1);
    values[i] = static_cast<Value>(static_cast<std::int64_t>((in[f.word] >> f.shift) & mask) + f.min);
  }
}

namespace {

// A conjunct `var == constant` (either way round) that the guard requires, if there is one.
std::optional<std::pair<ir::VarId, Value>> requiredEquality(const ir::Expr& e) {
  if (e.op == ir::Op::And) {
    if (auto left = requiredEquality(e.args[0])) return left;
    return requiredEquality(e.args[1]);
  }
  if (e.op != ir::Op::Eq) return std::nullopt;
  const ir::Expr& a = e.args[0];
  const ir::Expr& b = e.args[1];
  if (a.op == ir::Op::Var && b.op == ir::Op::Const) return std::pair{static_cast<ir::VarId>(a.value), b.value};
  if (b.op == ir::Op::Var && a.op == ir::Op::Const) return std::pair{static_cast<ir::VarId>(b.value), a.value};
  return std::nullopt;
}

}  // namespace

CompiledModel::CompiledModel(const ir::Model& model) : model_(&model), layout_(model) {
  std::vector<std::int32_t> triggerOf(model.variables.size(), -1);
  for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
    auto eq = requiredEquality(model.rules[r].guard);
    const ir::Variable* v = eq ? &model.variables[eq->first] : nullptr;
    if (v == nullptr || eq->second < v->min || eq->second > v->max) {
      untriggered_.push_back(r);  // (an equality outside the range: the rule can never fire, but keep it simple)
      continue;
    }
    if (triggerOf[eq->first] < 0) {
      triggerOf[eq->first] = static_cast<std::int32_t>(triggers_.size());
      triggers_.push_back({eq->first, std::vector<std::vector<std::uint32_t>>(static_cast<std::size_t>(v->max - v->min) + 1)});
    }
    triggers_[static_cast<std::size_t>(triggerOf[eq->first])].rulesByValue[static_cast<std::size_t>(eq->second - v->min)].push_back(r);
  }
  for (const ir::Rule& r : model.rules) {
    CompiledRule c{Condition(r.guard), {}};
    for (const ir::Branch& b : r.branches) {
      CompiledBranch cb;
      for (const ir::Assignment& a : b.assignments) {
        const ir::Variable& target = model.variables[a.var];
        bool safe = (a.value.op == ir::Op::Const && a.value.value >= target.min && a.value.value <= target.max) ||
                    (a.value.op == ir::Op::Var && model.variables[static_cast<std::size_t>(a.value.value)].min >= target.min &&
                     model.variables[static_cast<std::size_t>(a.value.value)].max <= target.max);
        cb.assignments.push_back({a.var, Program(a.value), !safe});
      }
      c.branches.push_back(std::move(cb));
    }
    rules_.push_back(std::move(c));
  }
  for (const ir::Invariant& inv : model.invariants) invariants_.emplace_back(inv.holds);
  if (model.validEnd) {
    validEnd_ = Program(*model.validEnd);
    hasValidEnd_ = true;
  }
}

void CompiledModel::candidateRules(const Value* values, std::vector<std::uint32_t>& out) const {
  out.assign(untriggered_.begin(), untriggered_.end());
  for (const Trigger& t : triggers_) {
    const std::vector<std::uint32_t>& bucket =
        t.rulesByValue[static_cast<std::size_t>(values[t.var] - model_->variables[t.var].min)];
    out.insert(out.end(), bucket.begin(), bucket.end());
  }
  // Rule order decides which of several shortest counterexamples is reported: keep it stable.
  // Each rule is in one bucket at most, so ordering them is all there is to do. A few are sorted;
  // many (a large team: thousands per state of the 10,600 rules of 100 robots, where the sort took
  // 15 % of the safety search) are marked in a bitmap read back in order.
  if (out.size() < 256) {
    std::sort(out.begin(), out.end());
    return;
  }
  thread_local std::vector<std::uint64_t> marks;
  marks.assign((rules_.size() + 63) / 64, 0);
  for (std::uint32_t r : out) marks[r >> 6] |= std::uint64_t{1} << (r & 63);
  out.clear();
  for (std::size_t w = 0; w < marks.size(); ++w) {
    for (std::uint64_t bits = marks[w]; bits != 0; bits &= bits - 1) {
      out.push_back(static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(bits))));
    }
  }
}

std::vector<Value> CompiledModel::initialValues() const {
  std::vector<Value> values;
  for (const ir::Variable& v : model_->variables) values.push_back(v.init);
  return values;
}

bool CompiledModel::step(const CompiledBranch& branch, const Value* in, Value* out) const {
  std::copy_n(in, layout_.variables(), out);
  bool ok = true;
  for (const CompiledAssignment& a : branch.assignments) {
    Value v = a.value.eval(in);  // every right-hand side reads the old state
    ok = ok && inRange(a.var, v);
    out[a.var] = v;
  }
  return ok;
}

bool CompiledModel::inRange(ir::VarId var, Value value) const {
  const ir::Variable& v = model_->variables[var];
  return value >= v.min && value <= v.max;
}

}  // namespace semo::checker
