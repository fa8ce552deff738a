#pragma once
// The abstract syntax tree of a mission (specs/language.md, section 2). Every node keeps the source
// range it came from, so later stages can point diagnostics and counterexample steps at the mission.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "semo/frontend/source.hpp"

namespace semo::ast {

struct Name {
  std::string text;
  SourceRange range;
};

struct Duration {
  enum class Unit { Msec, Sec, Min };
  std::int64_t amount = 0;
  Unit unit = Unit::Sec;
  SourceRange range;
  [[nodiscard]] std::int64_t milliseconds() const {
    return unit == Unit::Msec ? amount : unit == Unit::Sec ? amount * 1000 : amount * 60000;
  }
};

enum class RelOp { Lt, Le, Gt, Ge, Eq, Ne };
const char* spelling(RelOp op);

// A constant, a symbolic constant (`suggestHiding`), or a value `Owner.var`.
struct Expr {
  enum class Kind { Int, Number, String, Bool, Symbol, Value };
  Kind kind = Kind::Int;
  std::int64_t intValue = 0;  // Int; Bool (0 or 1)
  double numberValue = 0;     // Number
  std::string text;           // String (unescaped), Symbol
  Name owner;                 // Value: the team (or robot, in properties)
  Name var;                   // Value: the variable
  SourceRange range;
};

struct Cond {
  enum class Kind { Compare, Test, Not, And, Or };
  Kind kind = Kind::Test;
  RelOp op = RelOp::Eq;             // Compare
  Expr lhs, rhs;                    // Compare: both; Test: lhs
  std::unique_ptr<Cond> left, right;  // Not: left; And/Or: both
  SourceRange range;
};

struct GroupCondition {
  enum class Kind { InstanceOf, CapableOf };
  Kind kind = Kind::InstanceOf;
  std::vector<Name> names;  // robot types (any of) or capabilities (all of)
  SourceRange range;
};

struct Stmt;

// One arm of a `[[ ]]` block: `group (...) {...}`, `leader (...) {...}` or `others {...}`.
struct GroupArm {
  enum class Kind { Group, Leader, Others };
  Kind kind = Kind::Group;
  std::optional<GroupCondition> condition;  // absent for Others
  std::vector<Stmt> body;
  SourceRange keyword;
};

struct Stmt {
  enum class Kind { Call, Throw, Loop, If, Publish, Subscribe, Send, Receive, Wait, GroupBlock };
  Kind kind = Kind::Call;
  SourceRange range;  // the statement's first token

  Name name;               // Call: the service; Throw: the event
  std::vector<Expr> args;  // Call

  Duration duration;  // Loop, Wait

  std::unique_ptr<Cond> cond;  // If
  std::vector<Stmt> thenBody;  // If
  std::vector<Stmt> elseBody;  // If
  bool hasElse = false;        // If

  Name peer;      // Publish/Send: destination team; Subscribe/Receive: source team
  Name topicOwner;  // Publish/Send/Subscribe/Receive: T in T.v
  Name topicVar;    // ... v in T.v
  Expr value;     // Publish/Send

  std::vector<GroupArm> arms;  // GroupBlock
};

struct Repeat {
  bool isPeriod = false;
  Duration period;             // isPeriod
  std::unique_ptr<Cond> cond;  // !isPeriod
  SourceRange range;
};

struct Service {
  Name team, plan, name;
  std::vector<Stmt> body;
  std::optional<Repeat> repeat;
  SourceRange range;
};

struct RobotDecl {
  Name type;
  Name name;
  std::optional<std::int64_t> count;  // `[N]`
  SourceRange countRange;
};

struct TeamDecl {
  Name team;
  std::vector<RobotDecl> robots;
};

struct SetItem {
  Name plan, service;
  SourceRange range;
};

struct ModeDef {
  Name team, mode;
  std::vector<SetItem> sets;
};

struct Transition {
  bool isDefault = false;
  Name event;  // catch
  Name target;
  SourceRange range;
};

struct Case {
  Name mode;
  std::vector<Transition> transitions;
};

struct MainDef {
  Name team;
  std::vector<Case> cases;
  SourceRange range;
};

struct Ltl {
  enum class Kind { Atom, Not, Always, Eventually, Next, And, Or, Until, Implies };
  Kind kind = Kind::Atom;
  Expr lhs;                          // Atom
  std::optional<RelOp> op;           // Atom with comparison
  Expr rhs;                          // Atom with comparison
  std::unique_ptr<Ltl> left, right;  // unary: left; binary: both
  SourceRange range;
};

struct CrashAssumption {
  std::int64_t budget = 0;
  std::optional<Name> team;
  SourceRange range;
};

struct Property {
  Name name;
  std::unique_ptr<Ltl> formula;
};

struct VerifyBlock {
  std::vector<CrashAssumption> crashes;
  std::vector<Name> losses;               // none publish events knowledge heartbeats all
  std::optional<Name> fairness;           // "fair" or "unfair"
  std::optional<std::int64_t> lossBurst;  // assume loss burst <= N
  SourceRange lossBurstAt;
  std::optional<double> lossProbability;  // assume loss probability P (for `analyze` only)
  std::vector<Name> checks;
  std::vector<Property> properties;
  SourceRange range;
};

struct Mission {
  FileId file = kNoFile;
  std::vector<TeamDecl> teams;
  std::vector<Service> services;
  std::vector<ModeDef> modes;
  std::vector<MainDef> mains;
  std::vector<VerifyBlock> verifies;  // more than one is an elaboration error
};

}  // namespace semo::ast
