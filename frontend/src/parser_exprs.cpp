// Conditions, expressions and durations.
#include <charconv>
#include <cstdlib>

#include "parser_impl.hpp"

namespace semo::detail {

namespace {

std::string unescape(std::string_view raw) {
  std::string out;
  out.reserve(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] == '\\' && i + 1 < raw.size()) ++i;
    out += raw[i];
  }
  return out;
}

}  // namespace

bool Parser::atDuration() const {
  if (!at(Tok::Int) || peek(1).kind != Tok::Ident) return false;
  std::string_view unit = peek(1).text;
  return unit == "MSEC" || unit == "SEC" || unit == "MIN";
}

ast::Duration Parser::parseDuration() {
  ast::Duration d;
  const Token& amount = peek();
  if (!at(Tok::Int)) failExpected("a duration such as '2 SEC'", "");
  advance();
  auto [ptr, ec] = std::from_chars(amount.text.data(), amount.text.data() + amount.text.size(), d.amount);
  if (ec != std::errc() || d.amount < 0 || d.amount > 1000000000) {
    fail(amount, "duration out of range: must be between 0 and 1000000000");
  }
  if (!at(Tok::Ident) || (peek().text != "MSEC" && peek().text != "SEC" && peek().text != "MIN")) {
    failExpected("a time unit (MSEC, SEC or MIN)", "after '" + std::string(amount.text) + "'");
  }
  const Token& unit = advance();
  d.unit = unit.text == "MSEC" ? ast::Duration::Unit::Msec
           : unit.text == "SEC" ? ast::Duration::Unit::Sec
                                : ast::Duration::Unit::Min;
  d.range = spanOf(amount, unit);
  return d;
}

std::optional<ast::RelOp> Parser::acceptRelOp() {
  std::optional<ast::RelOp> op;
  switch (peek().kind) {
    case Tok::Lt: op = ast::RelOp::Lt; break;
    case Tok::Le: op = ast::RelOp::Le; break;
    case Tok::Gt: op = ast::RelOp::Gt; break;
    case Tok::Ge: op = ast::RelOp::Ge; break;
    case Tok::Eq: op = ast::RelOp::Eq; break;
    case Tok::Ne: op = ast::RelOp::Ne; break;
    case Tok::Assign:
      fail(peek(), "'=' assigns; use '==' to compare");
    default: return std::nullopt;
  }
  advance();
  return op;
}

ast::Expr Parser::parseExpr() {
  ast::Expr e;
  const Token& t = peek();
  e.range = t.range;
  switch (t.kind) {
    case Tok::Int: {
      advance();
      auto [ptr, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), e.intValue);
      if (ec != std::errc()) fail(t, "integer out of range");
      e.kind = ast::Expr::Kind::Int;
      return e;
    }
    case Tok::Number:
      advance();
      e.kind = ast::Expr::Kind::Number;
      e.numberValue = std::strtod(std::string(t.text).c_str(), nullptr);
      return e;
    case Tok::String:
      advance();
      e.kind = ast::Expr::Kind::String;
      e.text = unescape(t.text);
      return e;
    case Tok::KwTrue:
    case Tok::KwFalse:
      advance();
      e.kind = ast::Expr::Kind::Bool;
      e.intValue = t.kind == Tok::KwTrue ? 1 : 0;
      return e;
    case Tok::Ident:
      advance();
      if (accept(Tok::Dot)) {
        e.kind = ast::Expr::Kind::Value;
        e.owner = {std::string(t.text), t.range};
        // `r.leader` is a property atom although `leader` is a reserved word.
        e.var = at(Tok::KwLeader) ? ast::Name{"leader", advance().range}
                                  : expectName("a value name after '" + std::string(t.text) + ".'");
        e.range = spanOf(t, tokens_[pos_ - 1]);
      } else {
        e.kind = ast::Expr::Kind::Symbol;
        e.text = std::string(t.text);
      }
      return e;
    default:
      failExpected("a value (number, string, name or 'Team.value')", "");
  }
}

std::unique_ptr<ast::Cond> Parser::parseCond() {
  return associativeChain<ast::Cond>(Tok::KwOr, ast::Cond::Kind::Or, [this] { return parseAndCond(); });
}

std::unique_ptr<ast::Cond> Parser::parseAndCond() {
  return associativeChain<ast::Cond>(Tok::KwAnd, ast::Cond::Kind::And, [this] { return parseNotCond(); });
}

std::unique_ptr<ast::Cond> Parser::parseNotCond() {
  const NestingGuard level = deeper();
  auto node = std::make_unique<ast::Cond>();
  node->range = peek().range;
  if (accept(Tok::KwNot)) {
    node->kind = ast::Cond::Kind::Not;
    node->left = parseNotCond();
    return node;
  }
  if (accept(Tok::LParen)) {
    auto inner = parseCond();
    expect(Tok::RParen, "to close the parenthesised condition");
    return inner;
  }
  node->lhs = parseExpr();
  if (auto op = acceptRelOp()) {
    node->kind = ast::Cond::Kind::Compare;
    node->op = *op;
    node->rhs = parseExpr();
  } else {
    node->kind = ast::Cond::Kind::Test;
  }
  return node;
}

}  // namespace semo::detail
