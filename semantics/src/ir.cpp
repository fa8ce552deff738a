#include "semo/semantics/ir.hpp"

#include <array>

namespace semo::ir {

namespace {
constexpr std::array<const char*, 6> kKindNames{"step", "delivery", "loss", "crash", "environment", "timer"};

Expr fold(std::vector<Expr> parts, Op op, std::int32_t empty) {
  if (parts.empty()) return Expr::constant(empty);
  Expr out = std::move(parts.front());
  for (std::size_t i = 1; i < parts.size(); ++i) out = Expr::binary(op, std::move(out), std::move(parts[i]));
  return out;
}
}  // namespace

Expr conjunction(std::vector<Expr> parts) { return fold(std::move(parts), Op::And, 1); }
Expr disjunction(std::vector<Expr> parts) { return fold(std::move(parts), Op::Or, 0); }

const char* opSymbol(Op op) {
  switch (op) {
    case Op::Add: return "+";
    case Op::Sub: return "-";
    case Op::Mul: return "*";
    case Op::Div: return "/";
    case Op::Mod: return "%";
    case Op::Eq: return "==";
    case Op::Ne: return "!=";
    case Op::Lt: return "<";
    case Op::Le: return "<=";
    case Op::Gt: return ">";
    case Op::Ge: return ">=";
    case Op::And: return "&&";
    case Op::Or: return "||";
    case Op::Implies: return "=>";
    default: return "?";
  }
}

const char* ltlKeyword(Ltl::Kind kind) {
  switch (kind) {
    case Ltl::Kind::Atom: return "";
    case Ltl::Kind::Not: return "!";
    case Ltl::Kind::And: return "&&";
    case Ltl::Kind::Or: return "||";
    case Ltl::Kind::Implies: return "=>";
    case Ltl::Kind::Next: return "next";
    case Ltl::Kind::Always: return "always";
    case Ltl::Kind::Eventually: return "eventually";
    case Ltl::Kind::Until: return "until";
    case Ltl::Kind::Release: return "release";
  }
  return "";
}

const char* kindName(RuleKind kind) { return kKindNames[static_cast<std::size_t>(kind)]; }

std::optional<RuleKind> kindFromName(const std::string& name) {
  for (std::size_t i = 0; i < kKindNames.size(); ++i) {
    if (name == kKindNames[i]) return static_cast<RuleKind>(i);
  }
  return std::nullopt;
}

std::optional<VarId> Model::find(const std::string& variableName) const {
  for (VarId i = 0; i < variables.size(); ++i) {
    if (variables[i].name == variableName) return i;
  }
  return std::nullopt;
}

}  // namespace semo::ir
