// Token access, error recovery, and the top-level definitions of a mission.
#include <charconv>

#include "parser_impl.hpp"
#include "semo/frontend/parser.hpp"

namespace semo::detail {

SourceRange spanOf(const Token& first, const Token& last) {
  SourceRange r = first.range;
  if (last.range.begin.line == first.range.begin.line && last.range.begin.column >= first.range.begin.column) {
    r.length = last.range.begin.column + last.range.length - first.range.begin.column;
  }
  return r;
}

Parser::Parser(const SourceManager& sources, FileId file, DiagnosticEngine& diags)
    : sources_(sources), file_(file), diags_(diags) {
  errorsAtStart_ = diags.errorCount();
  tokens_ = tokenize(sources, file, diags);
}

const Token& Parser::peek(std::size_t ahead) const {
  std::size_t i = pos_ + ahead;
  return i < tokens_.size() ? tokens_[i] : tokens_.back();
}

bool Parser::atWord(std::string_view word) const { return at(Tok::Ident) && peek().text == word; }

const Token& Parser::advance() {
  const Token& t = peek();
  if (pos_ + 1 < tokens_.size()) ++pos_;
  return t;
}

bool Parser::accept(Tok kind) {
  if (!at(kind)) return false;
  advance();
  return true;
}

void Parser::fail(const Token& at, const std::string& message) {
  diags_.error(at.range, message);
  throw SyntaxError{};
}

void Parser::failExpected(std::string_view what, std::string_view context) {
  const Token& t = peek();
  std::string found = t.kind == Tok::Ident ? "'" + std::string(t.text) + "'" : describe(t.kind);
  if (isReservedWord(t.text) && t.kind != Tok::Ident) found = "reserved word " + found;
  std::string message = "expected " + std::string(what);
  if (!context.empty()) message += " " + std::string(context);
  fail(t, message + ", found " + found);
}

const Token& Parser::expect(Tok kind, std::string_view context) {
  if (!at(kind)) failExpected(describe(kind), context);
  return advance();
}

void Parser::expectWord(std::string_view word, std::string_view context) {
  if (!atWord(word)) failExpected("'" + std::string(word) + "'", context);
  advance();
}

ast::Name Parser::expectName(std::string_view what) {
  if (!at(Tok::Ident)) {
    if (peek().kind >= Tok::KwLeader) {
      fail(peek(), "'" + std::string(peek().text) + "' is a reserved word and cannot be used as " + std::string(what));
    }
    failExpected(what, "");
  }
  const Token& t = advance();
  return {std::string(t.text), t.range};
}

// Skips to the next token that can begin a top-level definition: `Name :`, `Name .` or `verify {`
// at brace depth zero.
void Parser::syncTopLevel() {
  int depth = 0;
  while (!at(Tok::End)) {
    if (depth == 0 && at(Tok::Ident) &&
        (peek(1).kind == Tok::Colon || peek(1).kind == Tok::Dot ||
         (peek().text == "verify" && peek(1).kind == Tok::LBrace))) {
      return;
    }
    if (at(Tok::LBrace)) ++depth;
    if (at(Tok::RBrace) && depth > 0) --depth;
    advance();
  }
}

ast::Mission Parser::parseMission() {
  ast::Mission mission;
  mission.file = file_;
  if (at(Tok::End)) {
    diags_.error(peek().range, "the mission is empty: expected a team declaration such as 'Team: RobotType robot'");
    return mission;
  }
  while (!at(Tok::End)) {
    std::size_t before = pos_;
    try {
      parseTopLevel(mission);
    } catch (const SyntaxError&) {
      if (diags_.errorCount() - errorsAtStart_ >= kMaxErrors) {
        diags_.error(peek().range, "too many errors; stopping");
        break;
      }
      if (pos_ == before) advance();  // always make progress
      syncTopLevel();
    }
  }
  return mission;
}

void Parser::parseTopLevel(ast::Mission& mission) {
  if (atWord("verify") && peek(1).kind == Tok::LBrace) return parseVerify(mission);
  if (!at(Tok::Ident)) {
    if (at(Tok::RBrace)) fail(peek(), "unmatched '}'");
    failExpected("a team declaration, service, mode, main or verify block", "");
  }
  if (peek(1).kind == Tok::Colon) return parseTeamDecl(mission);
  if (peek(1).kind == Tok::Dot) {
    if (peek(2).kind == Tok::KwMain) return parseMain(mission);
    if (peek(2).kind == Tok::Ident && peek(3).kind == Tok::Dot) return parseService(mission);
    if (peek(2).kind == Tok::Ident && peek(3).kind == Tok::LBrace) return parseMode(mission);
    advance();
    advance();
    if (peek().kind >= Tok::KwLeader) {
      fail(peek(), "'" + std::string(peek().text) + "' is a reserved word and cannot name a plan or mode");
    }
    expectName("a plan, mode or 'main' after 'Team.'");
    failExpected("'{' (mode definition) or '.' (service definition)", "");
  }
  advance();
  failExpected("':' (team declaration) or '.' (service, mode or main)", "after a name at top level");
}

void Parser::parseTeamDecl(ast::Mission& mission) {
  ast::TeamDecl team;
  team.team = expectName("a team name");
  expect(Tok::Colon, "after the team name");
  do {
    ast::RobotDecl robot;
    robot.type = expectName("a robot type");
    robot.name = expectName("a robot name after the robot type");
    if (at(Tok::LBracket)) {
      advance();
      const Token& count = peek();
      if (!at(Tok::Int)) failExpected("the number of robots", "inside '[ ]'");
      advance();
      std::int64_t n = 0;
      auto [ptr, ec] = std::from_chars(count.text.data(), count.text.data() + count.text.size(), n);
      if (ec != std::errc() || n < 1 || n > 100000) {
        fail(count, "the number of robots must be between 1 and 100000");
      }
      robot.count = n;
      robot.countRange = count.range;
      expect(Tok::RBracket, "after the number of robots");
    }
    team.robots.push_back(std::move(robot));
    if (at(Tok::Ident) && peek(1).kind == Tok::Ident) {
      fail(peek(), "expected ',' before another robot declaration");
    }
  } while (accept(Tok::Comma));
  mission.teams.push_back(std::move(team));
}

void Parser::parseService(ast::Mission& mission) {
  ast::Service service;
  service.range = peek().range;
  service.team = expectName("a team name");
  expect(Tok::Dot, "");
  service.plan = expectName("a plan name");
  expect(Tok::Dot, "");
  service.name = expectName("a service name");
  // The body's own errors are recovered inside parseBlock; a broken service header is not.
  service.body = parseBlock(/*allowGroups=*/true, "in a service body");
  if (at(Tok::KwRepeat)) {
    ast::Repeat repeat;
    repeat.range = advance().range;
    expect(Tok::LParen, "after 'repeat'");
    if (atDuration()) {
      repeat.isPeriod = true;
      repeat.period = parseDuration();
    } else {
      repeat.cond = parseCond();
    }
    expect(Tok::RParen, "to close 'repeat ('");
    service.repeat = std::move(repeat);
  }
  mission.services.push_back(std::move(service));
}

void Parser::parseMode(ast::Mission& mission) {
  ast::ModeDef mode;
  mode.team = expectName("a team name");
  expect(Tok::Dot, "");
  mode.mode = expectName("a mode name");
  expect(Tok::LBrace, "to open the mode definition");
  while (!at(Tok::RBrace) && !at(Tok::End)) {
    if (!at(Tok::KwSet)) failExpected("'set(Plan, Service)'", "in a mode definition");
    ast::SetItem item;
    item.range = advance().range;
    expect(Tok::LParen, "after 'set'");
    item.plan = expectName("a plan name");
    expect(Tok::Comma, "between plan and service in 'set'");
    item.service = expectName("a service name");
    expect(Tok::RParen, "to close 'set ('");
    accept(Tok::Semi);
    mode.sets.push_back(std::move(item));
  }
  const Token& close = expect(Tok::RBrace, "to close the mode definition");
  if (mode.sets.empty()) {
    diags_.error(close.range, "mode '" + mode.mode.text + "' sets no service: expected 'set(Plan, Service)'");
  }
  mission.modes.push_back(std::move(mode));
}

void Parser::parseMain(ast::Mission& mission) {
  ast::MainDef main;
  main.range = peek().range;
  main.team = expectName("a team name");
  expect(Tok::Dot, "");
  expect(Tok::KwMain, "");
  expect(Tok::LBrace, "to open the main block");
  while (!at(Tok::RBrace) && !at(Tok::End)) {
    if (!at(Tok::KwCase)) failExpected("'case (MODE):'", "in a main block");
    advance();
    ast::Case c;
    expect(Tok::LParen, "after 'case'");
    c.mode = expectName("a mode name");
    expect(Tok::RParen, "after the mode name");
    expect(Tok::Colon, "after 'case (MODE)'");
    while (at(Tok::KwCatch) || at(Tok::KwDefault)) c.transitions.push_back(parseTransition());
    if (c.transitions.empty()) failExpected("'catch(Event): mode = M' or 'default: mode = M'", "after 'case (MODE):'");
    main.cases.push_back(std::move(c));
  }
  const Token& close = expect(Tok::RBrace, "to close the main block");
  if (main.cases.empty()) diags_.error(close.range, "main block has no case: expected 'case (MODE):'");
  mission.mains.push_back(std::move(main));
}

ast::Transition Parser::parseTransition() {
  ast::Transition t;
  t.range = peek().range;
  if (accept(Tok::KwDefault)) {
    t.isDefault = true;
  } else {
    expect(Tok::KwCatch, "");
    expect(Tok::LParen, "after 'catch'");
    t.event = expectName("an event name");
    expect(Tok::RParen, "after the event name");
  }
  expect(Tok::Colon, t.isDefault ? "after 'default'" : "after 'catch(Event)'");
  expectWord("mode", "in a transition ('mode = M')");
  expect(Tok::Assign, "after 'mode'");
  t.target = expectName("the target mode");
  accept(Tok::Semi);
  return t;
}

}  // namespace semo::detail

namespace semo {

ast::Mission parseMission(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  return detail::Parser(sources, file, diags).parseMission();
}

}  // namespace semo
