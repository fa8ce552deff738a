// The `verify` block: assumptions, built-in checks and LTL properties.
#include <array>
#include <charconv>

#include "parser_impl.hpp"

namespace semo::detail {

namespace {

constexpr std::array<std::string_view, 6> kLossKinds{"none", "publish", "events", "knowledge", "heartbeats", "all"};
constexpr std::array<std::string_view, 7> kChecks{"group_formation",  "unique_leader",        "leader_reelection",
                                                  "knowledge_convergence", "mode_agreement", "deadlock_freedom",
                                                  "buffer_bounds"};

template <std::size_t N>
std::vector<std::string> asStrings(const std::array<std::string_view, N>& words) {
  return {words.begin(), words.end()};
}

template <std::size_t N>
bool contains(const std::array<std::string_view, N>& words, std::string_view w) {
  for (std::string_view x : words) {
    if (x == w) return true;
  }
  return false;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

}  // namespace

void Parser::parseVerify(ast::Mission& mission) {
  ast::VerifyBlock block;
  block.range = advance().range;  // 'verify'
  const Token& open = expect(Tok::LBrace, "after 'verify'");
  while (!at(Tok::RBrace) && !at(Tok::End)) {
    std::size_t before = pos_;
    try {
      parseVerifyItem(block);
    } catch (const SyntaxError&) {
      if (pos_ == before) advance();
      // Resynchronise at the next item keyword of the block.
      while (!at(Tok::End) && !at(Tok::RBrace) && !atWord("assume") && !atWord("check") && !atWord("property")) {
        advance();
      }
    }
  }
  if (at(Tok::End)) {
    diags_.error(open.range, "this '{' is never closed");
  } else {
    advance();
  }
  mission.verifies.push_back(std::move(block));
}

void Parser::parseVerifyItem(ast::VerifyBlock& block) {
  if (atWord("assume")) {
    advance();
    if (atWord("crash")) {
      ast::CrashAssumption crash;
      crash.range = advance().range;
      expect(Tok::Le, "after 'assume crash' (write 'assume crash <= N')");
      const Token& n = peek();
      if (!at(Tok::Int)) failExpected("the number of robots that may crash", "");
      advance();
      auto [ptr, ec] = std::from_chars(n.text.data(), n.text.data() + n.text.size(), crash.budget);
      if (ec != std::errc() || crash.budget < 0 || crash.budget > 100000) {
        fail(n, "crash budget must be between 0 and 100000");
      }
      if (atWord("in")) {
        advance();
        crash.team = expectName("a team name after 'in'");
      }
      block.crashes.push_back(std::move(crash));
      return;
    }
    if (atWord("loss")) {
      advance();
      if (atWord("burst")) {
        block.lossBurstAt = advance().range;
        expect(Tok::Le, "after 'assume loss burst' (write 'assume loss burst <= N')");
        const Token& n = peek();
        if (!at(Tok::Int)) failExpected("the longest run of consecutive losses", "");
        advance();
        std::int64_t burst = 0;
        auto [ptr, ec] = std::from_chars(n.text.data(), n.text.data() + n.text.size(), burst);
        if (ec != std::errc() || burst < 1 || burst > 100) fail(n, "a loss burst must be between 1 and 100");
        block.lossBurst = burst;
        return;
      }
      if (atWord("probability")) {
        advance();
        const Token& n = peek();
        if (!at(Tok::Number) && !at(Tok::Int)) failExpected("a probability between 0 and 1 (write 'assume loss probability 0.2')", "");
        advance();
        double p = -1;
        auto [ptr, ec] = std::from_chars(n.text.data(), n.text.data() + n.text.size(), p);
        if (ec != std::errc() || ptr != n.text.data() + n.text.size() || !(p >= 0 && p <= 1)) fail(n, "a loss probability must be between 0 and 1");
        block.lossProbability = p;
        return;
      }
      do {
        // `publish` is a reserved word but also names a loss kind.
        ast::Name kind = at(Tok::KwPublish) ? ast::Name{"publish", advance().range} : expectName("a loss kind");
        if (!contains(kLossKinds, kind.text)) {
          std::string hint = suggestClosest(kind.text, asStrings(kLossKinds));
          diags_.error(kind.range, "unknown loss kind '" + kind.text + "'; expected one of " +
                                       joined(asStrings(kLossKinds)) + (hint.empty() ? "" : " (" + hint + ")"));
        }
        block.losses.push_back(std::move(kind));
      } while (accept(Tok::Comma));
      return;
    }
    if (atWord("fair") || atWord("unfair")) {
      const Token& word = advance();
      block.fairness = ast::Name{std::string(word.text), word.range};
      expectWord("loss", "after '" + std::string(word.text) + "'");
      return;
    }
    failExpected("'crash', 'loss', 'fair loss' or 'unfair loss'", "after 'assume'");
  }
  if (atWord("check")) {
    advance();
    do {
      ast::Name check = expectName("a property to check");
      if (!contains(kChecks, check.text)) {
        std::string hint = suggestClosest(check.text, asStrings(kChecks));
        diags_.error(check.range, "unknown check '" + check.text + "'" + (hint.empty() ? "" : "; " + hint) +
                                      " (built-in checks: " + joined(asStrings(kChecks)) + ")");
      }
      block.checks.push_back(std::move(check));
    } while (accept(Tok::Comma));
    return;
  }
  if (atWord("property")) {
    advance();
    ast::Property property;
    property.name = expectName("a property name");
    expect(Tok::Colon, "after the property name");
    property.formula = parseLtl();
    block.properties.push_back(std::move(property));
    return;
  }
  failExpected("'assume', 'check' or 'property'", "in a verify block");
}

std::unique_ptr<ast::Ltl> Parser::parseLtl() {
  auto left = parseLtlUntil();
  if (!atWord("implies")) return left;
  auto node = std::make_unique<ast::Ltl>();
  node->kind = ast::Ltl::Kind::Implies;
  node->range = advance().range;
  node->left = std::move(left);
  node->right = parseLtl();
  return node;
}

std::unique_ptr<ast::Ltl> Parser::parseLtlUntil() {
  auto left = parseLtlOr();
  if (!atWord("until")) return left;
  auto node = std::make_unique<ast::Ltl>();
  node->kind = ast::Ltl::Kind::Until;
  node->range = advance().range;
  node->left = std::move(left);
  node->right = parseLtlUntil();
  return node;
}

std::unique_ptr<ast::Ltl> Parser::parseLtlOr() {
  return associativeChain<ast::Ltl>(Tok::KwOr, ast::Ltl::Kind::Or, [this] { return parseLtlAnd(); });
}

std::unique_ptr<ast::Ltl> Parser::parseLtlAnd() {
  return associativeChain<ast::Ltl>(Tok::KwAnd, ast::Ltl::Kind::And, [this] { return parseLtlUnary(); });
}

std::unique_ptr<ast::Ltl> Parser::parseLtlUnary() {
  const NestingGuard level = deeper();
  auto node = std::make_unique<ast::Ltl>();
  node->range = peek().range;
  bool temporalWord = at(Tok::Ident) && peek(1).kind != Tok::Dot &&
                      (peek().text == "always" || peek().text == "eventually" || peek().text == "next");
  if (at(Tok::KwNot) || temporalWord) {
    std::string_view word = advance().text;
    node->kind = word == "not"      ? ast::Ltl::Kind::Not
                 : word == "always" ? ast::Ltl::Kind::Always
                 : word == "next"   ? ast::Ltl::Kind::Next
                                    : ast::Ltl::Kind::Eventually;
    node->left = parseLtlUnary();
    return node;
  }
  if (accept(Tok::LParen)) {
    auto inner = parseLtl();
    expect(Tok::RParen, "to close the parenthesised formula");
    return inner;
  }
  node->kind = ast::Ltl::Kind::Atom;
  node->lhs = parseExpr();
  if (auto op = acceptRelOp()) {
    node->op = *op;
    node->rhs = parseExpr();
  }
  return node;
}

}  // namespace semo::detail
