#pragma once
// The IR: one finite transition system in guarded-command form that every engine reads (explicit
// search, SMT, the Promela and PRISM exports). Bounded integer variables (booleans are 0..1), and
// rules `guard -> simultaneous assignments`, each tagged with the robot that fires it, what kind
// of step it is, and the mission location it comes from. See specs/ir.md.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace semo::ir {

using VarId = std::uint32_t;
inline constexpr std::int32_t kNoRobot = -1;
// The most outcomes a rule may have (a synchronous round of ten coin flips has 1,024). The
// qualitative engines number a rule's outcomes in 8 bits and take at most kMaxSearchedOutcomes.
inline constexpr std::size_t kMaxOutcomes = 65536;
inline constexpr std::size_t kMaxSearchedOutcomes = 256;

struct Variable {
  std::string name;
  std::int32_t min = 0, max = 1;
  std::int32_t init = 0;
  bool isBool = false;
  std::int32_t robot = kNoRobot;  // the robot it belongs to, if any (for traces and symmetry)
  std::vector<std::string> valueNames;  // optional names of min, min+1, ... (modes, phases) for traces
  // A knowledge count (how many facts of a knowledge item a robot holds): the names of the facts,
  // which traces use to show one assignment of facts that fits the counts (checker/trace.hpp).
  std::vector<std::string> facts;
};

enum class Op : std::uint8_t {
  Const, Var,
  Not, Neg,
  Add, Sub, Mul, Div, Mod, Min, Max,
  Eq, Ne, Lt, Le, Gt, Ge,
  And, Or, Implies,
  Ite,  // args: condition, then, else
};

// The operands of a new node, moved in. A braced list ({std::move(a), std::move(b)}) would not do:
// a vector built from an initializer list copies its elements, so every node built on an operand
// copied the operand's whole tree, and a chain of n terms read left to right cost n^2 (a guard of
// 20,000 conjuncts took two minutes to read; bench/expression_bench.sh).
template <typename T, typename... Parts>
std::vector<T> movedOperands(Parts&&... parts) {
  std::vector<T> out;
  out.reserve(sizeof...(parts));
  (out.push_back(std::forward<Parts>(parts)), ...);
  return out;
}

struct Expr {
  Op op = Op::Const;
  std::int32_t value = 0;  // Const: the constant; Var: the VarId
  std::vector<Expr> args;

  static Expr constant(std::int32_t v) { return {Op::Const, v, {}}; }
  static Expr var(VarId id) { return {Op::Var, static_cast<std::int32_t>(id), {}}; }
  static Expr unary(Op op, Expr a) { return {op, 0, movedOperands<Expr>(std::move(a))}; }
  static Expr binary(Op op, Expr a, Expr b) { return {op, 0, movedOperands<Expr>(std::move(a), std::move(b))}; }
  static Expr ite(Expr c, Expr t, Expr e) { return {Op::Ite, 0, movedOperands<Expr>(std::move(c), std::move(t), std::move(e))}; }
  [[nodiscard]] bool isTrue() const { return op == Op::Const && value != 0; }
};

// Folds a list with And / Or; the empty conjunction is true, the empty disjunction false. The
// tree is balanced (log n deep): a guard over every robot of a large team stays shallow.
Expr conjunction(std::vector<Expr> parts);
Expr disjunction(std::vector<Expr> parts);

// And, Or, Add and Mul: a chain of one of them means the same however it is bracketed (integers
// wrap the same way), so chains are held as balanced trees and written without brackets.
bool isAssociative(Op op);
// parts[0] op parts[1] op ... as a balanced tree; parts must not be empty.
Expr associated(Op op, std::vector<Expr> parts);

// The infix spelling of a binary operator (C's, and `=>` for Implies); "?" for the others.
const char* opSymbol(Op op);

enum class RuleKind : std::uint8_t { Step, Delivery, Loss, Crash, Environment, Timer };
const char* kindName(RuleKind kind);
std::optional<RuleKind> kindFromName(const std::string& name);

struct Assignment {
  VarId var = 0;
  Expr value;
};

// One outcome of a rule. A rule with several branches is a probabilistic choice among them (their
// probabilities add up to 1); explicit search takes every branch as a successor.
struct Branch {
  double probability = 1.0;
  std::vector<Assignment> assignments;  // simultaneous: every right-hand side reads the old state
  // When the text form wrote the probability as a fraction (`1/27`): its exact value, kept so that
  // it is written back the same way; 0/0 otherwise.
  std::uint32_t numerator = 0, denominator = 0;
};

// Where a rule comes from in the mission: the construct and its position (empty for a model
// written by hand without @origin). The text form is "file:line:col".
struct Origin {
  std::string file;
  std::uint32_t line = 0, column = 0;
  std::string construct;  // "publish", "loop", "leader block", "event", ... (empty when not known)
  [[nodiscard]] bool empty() const { return file.empty() && line == 0; }
  [[nodiscard]] std::string text() const;
  // "file:line:col" (the file may itself hold ':'); any other text is kept whole as the file.
  static Origin parse(const std::string& text, std::string construct = {});
  bool operator==(const Origin&) const = default;
};

// One sensed condition decided by a step: where it is sensed (a robot, and the place in its
// program), and whether it held.
struct SensedOutcome {
  std::string point;
  bool holds = true;
  bool operator==(const SensedOutcome&) const = default;
};

struct Rule {
  std::string name;
  std::int32_t robot = kNoRobot;
  RuleKind kind = RuleKind::Step;
  Origin origin;
  std::string label;   // what the step means for a person ("throws find_color_paper")
  Expr guard;
  std::vector<Branch> branches;
  bool weaklyFair = false;    // for liveness: a rule enabled for ever is taken eventually
  bool stronglyFair = false;  // a rule enabled again and again is taken again and again (fair loss)
  // Weakly fair rules of one non-empty group share their fairness: while some rule of the group is
  // enabled for ever, some rule of it is taken again and again. The steps a robot may take from one
  // control point form a group, so that a robot does not stop, while which way a sensed condition
  // goes stays the environment's choice (specs/ir.md, "Fairness groups").
  std::string fairGroup;
  // The sensed conditions this step decided, and how (a sensed condition is the environment's:
  // either outcome is possible). A property checked on a settling world (Property::settled) looks
  // only at runs on which, from some point on, each of them is always decided the same way.
  std::vector<SensedOutcome> sensed;
};

struct Invariant {
  std::string name;
  std::string origin;
  Expr holds;  // must hold in every reachable state
};

// A linear temporal logic formula over state predicates (Atom: an expression on the state).
struct Ltl {
  enum class Kind : std::uint8_t { Atom, Not, And, Or, Implies, Next, Always, Eventually, Until, Release };
  Kind kind = Kind::Atom;
  Expr atom;
  std::vector<Ltl> args;  // one for the unary kinds, two for the binary ones

  static Ltl of(Expr e) { return {Kind::Atom, std::move(e), {}}; }
  static Ltl unary(Kind k, Ltl a) { return {k, {}, movedOperands<Ltl>(std::move(a))}; }
  static Ltl binary(Kind k, Ltl a, Ltl b) { return {k, {}, movedOperands<Ltl>(std::move(a), std::move(b))}; }
};
const char* ltlKeyword(Ltl::Kind kind);  // "always", "until", ... ; "" for Atom

// A property every infinite run must satisfy (liveness, or any LTL). Runs that end are extended by
// repeating their last state.
struct Property {
  std::string name;
  std::string origin;
  Ltl formula;
  // Checked on the runs on which every sensed condition (Rule::sensed), at each place a robot
  // senses it, is from some point on always decided the same way: once the world settles.
  bool settled = false;
};

struct Model {
  std::vector<std::string> robots;  // robot names, indexed by Rule::robot / Variable::robot
  std::vector<Variable> variables;
  std::vector<Rule> rules;
  std::vector<Invariant> invariants;
  std::vector<Property> properties;
  // A state where no rule is enabled is a deadlock unless this holds (e.g. every robot has
  // finished or crashed). Absent: deadlock_freedom is not checked.
  std::optional<Expr> validEnd;
  std::vector<std::string> assumptions;  // what the model assumes, in words, for every verdict

  [[nodiscard]] std::optional<VarId> find(const std::string& variableName) const;
};

}  // namespace semo::ir
