#pragma once
// The IR prepared for fast evaluation: expressions as postfix programs over an array of variable
// values, and the bit layout that packs a state into 64-bit words.
#include <cstdint>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

using Value = std::int32_t;

// A postfix program; evaluating it never allocates. `&&`, `||` and `=>` skip their right operand
// when the left one decides (expressions have no side effects, so this changes no value).
class Program {
 public:
  Program() = default;
  explicit Program(const ir::Expr& e);
  [[nodiscard]] Value eval(const Value* vars) const;

 private:
  // An IR operator, or one of these control instructions (operand: the index to jump to).
  enum Control : std::uint8_t {
    kJumpIfFalse = 100,  // top == 0: leave 0 and jump; else pop
    kJumpIfTrue,         // top != 0: leave 1 and jump; else pop
    kJumpIfFalseTrue,    // top == 0: leave 1 and jump (=>); else pop
    kTruth,              // top = (top != 0)
  };
  struct Instr {
    std::uint8_t op;  // an ir::Op or a Control
    std::int32_t operand;
  };
  void compile(const ir::Expr& e);
  std::vector<Instr> code_;
  std::size_t maxStack_ = 0;
  std::size_t depth_ = 0;
};

// A guard: the conjuncts of a conjunction tested in turn, stopping at the first that fails; the
// comparisons of a variable with a constant (most conjuncts: program counters, `alive`) first,
// without the stack machine.
class Condition {
 public:
  Condition() = default;
  explicit Condition(const ir::Expr& e);
  [[nodiscard]] bool holds(const Value* vars) const {
    for (const Test& t : tests_) {
      if (!t.holds(vars[t.var])) return false;
    }
    for (const Clause& c : clauses_) {
      bool any = false;
      for (std::uint32_t k = c.first; k < c.end && !any; ++k) any = clauseTests_[k].holds(vars[clauseTests_[k].var]);
      if (!any) return false;
    }
    for (const Program& p : rest_) {
      if (p.eval(vars) == 0) return false;
    }
    return true;
  }
  [[nodiscard]] Value eval(const Value* vars) const { return holds(vars) ? 1 : 0; }

 private:
  struct Test {
    ir::VarId var;
    ir::Op op;  // Eq, Ne, Lt, Le, Gt, Ge against `constant`
    Value constant;
    [[nodiscard]] bool holds(Value v) const {
      switch (op) {
        case ir::Op::Eq: return v == constant;
        case ir::Op::Ne: return v != constant;
        case ir::Op::Lt: return v < constant;
        case ir::Op::Le: return v <= constant;
        case ir::Op::Gt: return v > constant;
        default: return v >= constant;
      }
    }
  };
  struct Clause {
    std::uint32_t first, end;  // a disjunction of clauseTests_[first, end)
  };
  void add(const ir::Expr& conjunct);
  // Appends e (negated when `negated`) as a disjunction of tests, if it is one.
  static bool disjunction(const ir::Expr& e, bool negated, std::vector<Test>& out);
  std::vector<Test> tests_;
  std::vector<Clause> clauses_;
  std::vector<Test> clauseTests_;
  std::vector<Program> rest_;
};

class StateLayout {
 public:
  explicit StateLayout(const ir::Model& model);
  [[nodiscard]] std::size_t words() const { return words_; }
  [[nodiscard]] std::size_t variables() const { return fields_.size(); }
  [[nodiscard]] std::size_t bits() const { return bits_; }
  void pack(const Value* values, std::uint64_t* out) const;
  // Overwrites one variable's field in a packed state (the value must be in the range).
  void set(std::uint64_t* packed, ir::VarId var, Value value) const {
    const Field& f = fields_[var];
    std::uint64_t mask = (f.width == 64 ? ~0ull : ((1ull << f.width) - 1)) << f.shift;
    packed[f.word] = (packed[f.word] & ~mask) | ((static_cast<std::uint64_t>(static_cast<std::int64_t>(value) - f.min) << f.shift) & mask);
  }
  void unpack(const std::uint64_t* in, Value* values) const;

 private:
  struct Field {
    std::uint32_t word, shift, width;
    Value min;
  };
  std::vector<Field> fields_;
  std::size_t words_ = 1;
  std::size_t bits_ = 0;
};

struct CompiledAssignment {
  ir::VarId var;
  Program value;
  bool mayLeaveRange = true;  // false for a constant in range, or a copy of a variable of the same range
};

struct CompiledBranch {
  std::vector<CompiledAssignment> assignments;
};

struct CompiledRule {
  Condition guard;
  std::vector<CompiledBranch> branches;
};

class CompiledModel {
 public:
  explicit CompiledModel(const ir::Model& model);
  [[nodiscard]] const ir::Model& model() const { return *model_; }
  [[nodiscard]] const StateLayout& layout() const { return layout_; }
  [[nodiscard]] const std::vector<CompiledRule>& rules() const { return rules_; }
  [[nodiscard]] const std::vector<Program>& invariants() const { return invariants_; }
  [[nodiscard]] const Program* validEnd() const { return hasValidEnd_ ? &validEnd_ : nullptr; }
  [[nodiscard]] std::vector<Value> initialValues() const;
  // The rules whose guard may hold in a state, in rule order: rules whose guard requires
  // `var == constant` (a robot's program counter, mostly) are only offered when it holds.
  void candidateRules(const Value* values, std::vector<std::uint32_t>& out) const;
  // Whether `value` fits the declared range of `var` (an update out of range is a model error).
  [[nodiscard]] bool inRange(ir::VarId var, Value value) const;
  // The state after `branch`: `out` (distinct from `in`) becomes `in` with the branch's
  // simultaneous assignments. False when a new value leaves its variable's range.
  bool step(const CompiledBranch& branch, const Value* in, Value* out) const;

 private:
  const ir::Model* model_;
  StateLayout layout_;
  std::vector<CompiledRule> rules_;
  std::vector<Program> invariants_;
  Program validEnd_;
  bool hasValidEnd_ = false;
  struct Trigger {
    ir::VarId var;
    std::vector<std::vector<std::uint32_t>> rulesByValue;  // indexed by value - min
  };
  std::vector<Trigger> triggers_;
  std::vector<std::uint32_t> untriggered_;
};

}  // namespace semo::checker
