#include "semo/semantics/ir.hpp"

#include <array>

namespace semo::ir {

namespace {
constexpr std::array<const char*, 6> kKindNames{"step", "delivery", "loss", "crash", "environment", "timer"};

// parts[first, last) as a balanced tree: recursion as deep as the tree, log n.
Expr balanced(Op op, std::vector<Expr>& parts, std::size_t first, std::size_t last) {
  if (last - first == 1) return std::move(parts[first]);
  const std::size_t middle = first + (last - first) / 2;
  Expr left = balanced(op, parts, first, middle);
  return Expr::binary(op, std::move(left), balanced(op, parts, middle, last));
}

Expr fold(std::vector<Expr> parts, Op op, std::int32_t empty) {
  if (parts.empty()) return Expr::constant(empty);
  return balanced(op, parts, 0, parts.size());
}
}  // namespace

bool isAssociative(Op op) { return op == Op::And || op == Op::Or || op == Op::Add || op == Op::Mul; }

Expr associated(Op op, std::vector<Expr> parts) { return balanced(op, parts, 0, parts.size()); }

std::string Origin::text() const {
  if (line == 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

Origin Origin::parse(const std::string& text, std::string construct) {
  Origin o;
  o.construct = std::move(construct);
  auto number = [](const std::string& s, std::uint32_t& out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = static_cast<std::uint32_t>(std::stoul(s));
    return true;
  };
  std::size_t c2 = text.rfind(':');
  std::size_t c1 = c2 == std::string::npos || c2 == 0 ? std::string::npos : text.rfind(':', c2 - 1);
  if (c1 != std::string::npos && number(text.substr(c1 + 1, c2 - c1 - 1), o.line) && number(text.substr(c2 + 1), o.column) &&
      o.line > 0) {
    o.file = text.substr(0, c1);
    return o;
  }
  o.line = o.column = 0;
  o.file = text;
  return o;
}

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
