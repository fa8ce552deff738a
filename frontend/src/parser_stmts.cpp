// Statements, bodies and `[[ ]]` group blocks.
#include "parser_impl.hpp"

namespace semo::detail {

bool Parser::atStatementStart() const {
  switch (peek().kind) {
    case Tok::KwThrow:
    case Tok::KwLoop:
    case Tok::KwIf:
    case Tok::KwPublish:
    case Tok::KwSubscribe:
    case Tok::KwSend:
    case Tok::KwReceive:
    case Tok::KwWait:
    case Tok::LGroup:
      return true;
    case Tok::Ident:
      return peek(1).kind == Tok::LParen;
    default:
      return false;
  }
}

// Skips the rest of a broken statement: up to a statement start, or a closing `}` / `]]` of the
// enclosing block, counting nested brackets so that an inner `}` does not end the skip early.
void Parser::syncStatement() {
  int depth = 0;
  while (!at(Tok::End)) {
    if (depth == 0) {
      if (atStatementStart() || at(Tok::RBrace) || at(Tok::RGroup) || at(Tok::KwGroup) ||
          at(Tok::KwLeader) || at(Tok::KwOthers) || at(Tok::KwElse)) {
        return;
      }
      if (at(Tok::Semi)) {
        advance();
        return;
      }
      // A top-level definition header means the block's closing brace is missing.
      if (at(Tok::Ident) && peek(1).kind == Tok::Dot && peek(2).kind != Tok::Dot) {
        std::size_t k = 2;
        if (peek(k).kind == Tok::Ident || peek(k).kind == Tok::KwMain) ++k;
        if (peek(k).kind == Tok::Dot || peek(k).kind == Tok::LBrace) return;
      }
    }
    if (at(Tok::LBrace) || at(Tok::LParen) || at(Tok::LGroup)) ++depth;
    if ((at(Tok::RBrace) || at(Tok::RParen) || at(Tok::RGroup)) && depth > 0) --depth;
    advance();
  }
}

std::vector<ast::Stmt> Parser::parseBlock(bool allowGroups, std::string_view context) {
  const Token& open = expect(Tok::LBrace, "to open the block");
  std::vector<ast::Stmt> body;
  while (!at(Tok::RBrace) && !at(Tok::End)) {
    if (diags_.errorCount() - errorsAtStart_ >= kMaxErrors) throw SyntaxError{};
    // `Team.X.Y {` inside a block: the block's `}` is missing. Report it here, at the open brace.
    if (at(Tok::Ident) && peek(1).kind == Tok::Dot && !atStatementStart()) {
      std::size_t k = 2;
      if (peek(k).kind == Tok::Ident || peek(k).kind == Tok::KwMain) ++k;
      if (peek(k).kind == Tok::Dot || peek(k).kind == Tok::LBrace) {
        diags_.error(open.range, "this '{' is never closed");
        return body;
      }
    }
    std::size_t before = pos_;
    try {
      body.push_back(parseStatement(allowGroups));
    } catch (const SyntaxError&) {
      if (pos_ == before) advance();
      syncStatement();
    }
  }
  if (at(Tok::End)) {
    diags_.error(open.range, "this '{' is never closed");
    return body;
  }
  const Token& close = advance();
  if (body.empty()) diags_.error(close.range, "empty block " + std::string(context) + ": expected at least one statement");
  return body;
}

std::vector<ast::Stmt> Parser::parseBody() {
  if (!at(Tok::LBrace)) {
    std::vector<ast::Stmt> one;
    one.push_back(parseStatement(false));
    return one;
  }
  advance();
  std::vector<ast::Stmt> body;
  while (!at(Tok::RBrace)) {
    if (at(Tok::End)) failExpected("'}'", "to close the body");
    body.push_back(parseStatement(false));
  }
  advance();
  return body;
}

void Parser::parseTopic(ast::Stmt& stmt, bool withValue) {
  advance();  // the verb
  expect(Tok::LParen, "after the communication verb");
  stmt.peer = expectName("a team name");
  expect(Tok::Comma, "after the team name");
  stmt.topicOwner = expectName("a topic 'Team.var'");
  expect(Tok::Dot, "in a topic 'Team.var'");
  stmt.topicVar = expectName("a topic variable name after 'Team.'");
  if (withValue) {
    expect(Tok::Assign, "after the topic ('Team.var = value')");
    stmt.value = parseExpr();
  }
  expect(Tok::RParen, "to close the communication statement");
}

ast::Stmt Parser::parseStatement(bool allowGroups) {
  const NestingGuard level = deeper();
  ast::Stmt stmt;
  stmt.range = peek().range;
  switch (peek().kind) {
    case Tok::LGroup:
      if (!allowGroups) {
        diags_.error(peek().range, "group blocks '[[ ]]' cannot be nested inside a group or 'if'");
        stmt = parseGroupBlock();  // kept, so that its own errors are found and the body is not "empty"
        break;
      }
      stmt = parseGroupBlock();
      break;
    case Tok::KwThrow:
      advance();
      stmt.kind = ast::Stmt::Kind::Throw;
      stmt.name = expectName("an event name after 'throw'");
      break;
    case Tok::KwLoop:
    case Tok::KwWait: {
      stmt.kind = at(Tok::KwLoop) ? ast::Stmt::Kind::Loop : ast::Stmt::Kind::Wait;
      const char* word = at(Tok::KwLoop) ? "'loop'" : "'wait'";
      advance();
      expect(Tok::LParen, std::string("after ") + word);
      stmt.duration = parseDuration();
      expect(Tok::RParen, "after the duration");
      break;
    }
    case Tok::KwIf:
      advance();
      stmt.kind = ast::Stmt::Kind::If;
      expect(Tok::LParen, "after 'if'");
      stmt.cond = parseCond();
      expect(Tok::RParen, "to close the condition");
      stmt.thenBody = parseBody();
      if (accept(Tok::KwElse)) {
        stmt.hasElse = true;
        stmt.elseBody = parseBody();
      }
      break;
    case Tok::KwPublish:
      stmt.kind = ast::Stmt::Kind::Publish;
      parseTopic(stmt, true);
      break;
    case Tok::KwSend:
      stmt.kind = ast::Stmt::Kind::Send;
      parseTopic(stmt, true);
      break;
    case Tok::KwSubscribe:
      stmt.kind = ast::Stmt::Kind::Subscribe;
      parseTopic(stmt, false);
      break;
    case Tok::KwReceive:
      stmt.kind = ast::Stmt::Kind::Receive;
      parseTopic(stmt, false);
      break;
    case Tok::Ident: {
      stmt.kind = ast::Stmt::Kind::Call;
      stmt.name = expectName("a service name");
      if (!at(Tok::LParen)) {
        if (at(Tok::Dot)) {
          fail(peek(), "expected a statement; a value such as '" + stmt.name.text +
                           ".x' cannot stand alone (did you mean publish(...) or a call 'name()'?)");
        }
        failExpected("'(' to call service '" + stmt.name.text + "'", "");
      }
      advance();
      if (!at(Tok::RParen)) {
        do {
          stmt.args.push_back(parseExpr());
        } while (accept(Tok::Comma));
      }
      if (!at(Tok::RParen) && !stmt.args.empty()) failExpected("',' or ')'", "in the argument list");
      expect(Tok::RParen, "to close the argument list");
      break;
    }
    case Tok::KwGroup:
    case Tok::KwLeader:
    case Tok::KwOthers:
      fail(peek(), describe(peek().kind) + " may only appear directly inside '[[ ]]'");
    default:
      failExpected("a statement", "");
  }
  accept(Tok::Semi);
  return stmt;
}

ast::GroupCondition Parser::parseGroupCondition() {
  ast::GroupCondition c;
  c.range = peek().range;
  if (atWord("instance")) {
    c.kind = ast::GroupCondition::Kind::InstanceOf;
  } else if (atWord("capable")) {
    c.kind = ast::GroupCondition::Kind::CapableOf;
  } else {
    failExpected("'instance of' or 'capable of'", "in a group condition");
  }
  advance();
  expectWord("of", c.kind == ast::GroupCondition::Kind::InstanceOf ? "after 'instance'" : "after 'capable'");
  const char* what = c.kind == ast::GroupCondition::Kind::InstanceOf ? "a robot type" : "a capability";
  c.names.push_back(expectName(what));
  while (at(Tok::Comma) || at(Tok::Ident)) {
    accept(Tok::Comma);
    c.names.push_back(expectName(what));
  }
  return c;
}

ast::GroupArm Parser::parseGroupArm() {
  ast::GroupArm arm;
  arm.keyword = peek().range;
  if (accept(Tok::KwOthers)) {
    arm.kind = ast::GroupArm::Kind::Others;
  } else {
    arm.kind = at(Tok::KwLeader) ? ast::GroupArm::Kind::Leader : ast::GroupArm::Kind::Group;
    advance();
    expect(Tok::LParen, "after the group keyword");
    arm.condition = parseGroupCondition();
    expect(Tok::RParen, "to close the group condition");
  }
  arm.body = parseBlock(/*allowGroups=*/false, "in a group");
  return arm;
}

// `[[ leader(...) {...} others {...}? ]]` or `[[ group(...) {...}+ others {...}? ]]`.
ast::Stmt Parser::parseGroupBlock() {
  ast::Stmt stmt;
  stmt.kind = ast::Stmt::Kind::GroupBlock;
  const Token& open = advance();
  stmt.range = open.range;
  bool armFailed = false;
  while (at(Tok::KwGroup) || at(Tok::KwLeader) || at(Tok::KwOthers)) {
    std::size_t before = pos_;
    try {
      stmt.arms.push_back(parseGroupArm());
    } catch (const SyntaxError&) {
      armFailed = true;
      if (pos_ == before) advance();
      syncStatement();
      while (!at(Tok::RGroup) && !at(Tok::KwGroup) && !at(Tok::KwLeader) && !at(Tok::KwOthers) && !at(Tok::End) &&
             !at(Tok::RBrace)) {
        advance();
      }
    }
  }
  if (stmt.arms.empty()) {
    if (at(Tok::RGroup)) {
      diags_.error(peek().range, "empty group block: expected 'group (...)', 'leader (...)' or 'others' after '[['");
      advance();
      throw SyntaxError{};
    }
    failExpected("'group (...)', 'leader (...)' or 'others'", "after '[['");
  }
  if (!at(Tok::RGroup)) {
    failExpected("']]' or another group", "to close the group block");
  }
  advance();

  // Shape rules of the grammar: one leader with at most an `others`, or groups then an `others`.
  std::size_t leaders = 0, groups = 0, others = 0;
  for (const ast::GroupArm& arm : stmt.arms) {
    if (arm.kind != ast::GroupArm::Kind::Others && others > 0) {
      diags_.error(arm.keyword, "'others' must be the last arm of a group block");
    }
    if (arm.kind == ast::GroupArm::Kind::Leader) {
      if (++leaders > 1) diags_.error(arm.keyword, "a group block has at most one 'leader'");
    } else if (arm.kind == ast::GroupArm::Kind::Group) {
      ++groups;
    } else if (++others > 1) {
      diags_.error(arm.keyword, "a group block has at most one 'others'");
    }
  }
  if (leaders > 0 && groups > 0) {
    for (const ast::GroupArm& arm : stmt.arms) {
      if (arm.kind == ast::GroupArm::Kind::Group) {
        diags_.error(arm.keyword, "a leader block cannot also hold 'group' arms (use two blocks)");
        break;
      }
    }
  }
  if (leaders == 0 && groups == 0 && others > 0 && !armFailed) {
    diags_.error(stmt.arms.front().keyword, "a group block needs a 'group (...)' or 'leader (...)' before 'others'");
  }
  return stmt;
}

}  // namespace semo::detail
