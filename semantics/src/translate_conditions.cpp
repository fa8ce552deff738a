// What a robot's conditions test: the model's variables where the condition reads them (a
// topic's symbols, a knowledge item, modes), and otherwise what the robot senses, named as one
// sensed condition per robot, or per team for values of one source (specs/semantics.md).
#include <algorithm>

#include "translator.hpp"

namespace semo::detail {

std::int32_t Translator::symbolValue(Index topic, const model::Expr& e) const {
  const std::vector<std::string>& symbols = m_.topics[topic].symbols;
  std::string text = e.kind == model::Expr::Kind::Bool ? (e.intValue != 0 ? "true" : "false") : e.text;
  if (e.kind == model::Expr::Kind::Symbol || e.kind == model::Expr::Kind::String || e.kind == model::Expr::Kind::Bool) {
    auto it = std::find(symbols.begin(), symbols.end(), text);
    if (it != symbols.end()) return static_cast<std::int32_t>(it - symbols.begin()) + 1;
  }
  return symbols.empty() ? 1 : -1;  // -1: a value the topic never carries
}

// The condition as an IR expression over the robot's own state, or nullopt when it reads the
// environment (sensed values, knowledge): then both outcomes are possible.
std::optional<Expr> Translator::condition(Index robot, const model::Cond& c) const {
  using K = model::Cond::Kind;
  switch (c.kind) {
    case K::Not: {
      auto a = condition(robot, *c.left);
      return a ? std::optional<Expr>(lnot(std::move(*a))) : std::nullopt;
    }
    case K::And:
    case K::Or: {
      auto a = condition(robot, *c.left), b = condition(robot, *c.right);
      if (!a || !b) return std::nullopt;
      return Expr::binary(c.kind == K::And ? Op::And : Op::Or, std::move(*a), std::move(*b));
    }
    case K::Test:
      if (c.lhs.kind == model::Expr::Kind::Bool) return Expr::constant(static_cast<std::int32_t>(c.lhs.intValue));
      return std::nullopt;
    case K::Compare: break;
  }
  const model::Expr* value = c.lhs.kind == model::Expr::Kind::Value ? &c.lhs : c.rhs.kind == model::Expr::Kind::Value ? &c.rhs : nullptr;
  const model::Expr* constant = value == &c.lhs ? &c.rhs : &c.lhs;
  if (value == nullptr || value->valueKind != model::ValueKind::Topic || constant->kind == model::Expr::Kind::Value) {
    return std::nullopt;
  }
  auto view = vars_[robot].view.find(value->topic);
  if (view == vars_[robot].view.end()) return std::nullopt;
  std::int32_t symbol = symbolValue(value->topic, *constant);
  if (symbol < 0 || m_.topics[value->topic].symbols.empty()) return std::nullopt;
  Expr test = eq(Expr::var(view->second), symbol);
  if (c.op == model::RelOp::Eq) return test;
  if (c.op == model::RelOp::Ne) return lnot(std::move(test));
  return std::nullopt;  // ordering symbols means nothing
}

bool Translator::readsTeamSourcesOnly(const model::Cond& c) const {
  using K = model::Cond::Kind;
  if (c.kind == K::Not) return readsTeamSourcesOnly(*c.left);
  if (c.kind == K::And || c.kind == K::Or) return readsTeamSourcesOnly(*c.left) && readsTeamSourcesOnly(*c.right);
  bool anyValue = false;
  for (const model::Expr* e : {&c.lhs, &c.rhs}) {
    if (c.kind == K::Test && e == &c.rhs) break;
    if (e->kind != model::Expr::Kind::Value) continue;
    anyValue = true;
    if (e->owner >= m_.teams.size()) return false;
    const std::string& team = m_.teams[e->owner].name;
    const auto v = std::find_if(m_.strategy.values.begin(), m_.strategy.values.end(),
                                [&](const strategy::Value& x) { return x.team == team && x.var == e->var; });
    if (v == m_.strategy.values.end() || !v->teamSource) return false;
  }
  return anyValue;
}

std::string Translator::sensedText(const model::Cond& c, bool& negated) const {
  using K = model::Cond::Kind;
  auto exprText = [&](const model::Expr& e) -> std::string {
    switch (e.kind) {
      case model::Expr::Kind::Int: return std::to_string(e.intValue);
      case model::Expr::Kind::Number: return std::to_string(e.numberValue);
      case model::Expr::Kind::Bool: return e.intValue != 0 ? "true" : "false";
      case model::Expr::Kind::Value: return (e.owner < m_.teams.size() ? m_.teams[e.owner].name + "." : std::string()) + e.var;
      default: return e.text;
    }
  };
  switch (c.kind) {
    case K::Not: {
      std::string inner = sensedText(*c.left, negated);
      negated = !negated;
      return inner;
    }
    case K::And:
    case K::Or: {
      bool l = false, r = false;
      std::string a = sensedText(*c.left, l), b = sensedText(*c.right, r);
      return "(" + std::string(l ? "!" : "") + a + (c.kind == K::And ? "&&" : "||") + (r ? "!" : "") + b + ")";
    }
    case K::Test: return exprText(c.lhs);
    case K::Compare: break;
  }
  // The value on the left; then <, <= and == are the positive forms.
  const bool swapped = c.lhs.kind != model::Expr::Kind::Value && c.rhs.kind == model::Expr::Kind::Value;
  const model::Expr& left = swapped ? c.rhs : c.lhs;
  const model::Expr& right = swapped ? c.lhs : c.rhs;
  model::RelOp op = c.op;
  if (swapped) {
    op = op == model::RelOp::Lt ? model::RelOp::Gt : op == model::RelOp::Gt ? model::RelOp::Lt
       : op == model::RelOp::Le ? model::RelOp::Ge : op == model::RelOp::Ge ? model::RelOp::Le : op;
  }
  const char* spelling = "==";
  switch (op) {
    case model::RelOp::Lt: spelling = "<"; break;
    case model::RelOp::Le: spelling = "<="; break;
    case model::RelOp::Eq: spelling = "=="; break;
    case model::RelOp::Ge: spelling = "<", negated = !negated; break;
    case model::RelOp::Gt: spelling = "<=", negated = !negated; break;
    case model::RelOp::Ne: spelling = "==", negated = !negated; break;
  }
  return exprText(left) + spelling + exprText(right);
}

}  // namespace semo::detail
