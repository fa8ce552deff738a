#pragma once
// The recursive-descent parser shared by parser_*.cpp (one class, split by part of the grammar).
#include <memory>
#include <string>
#include <vector>

#include "semo/frontend/ast.hpp"
#include "semo/frontend/lexer.hpp"
#include "semo/frontend/nesting.hpp"

namespace semo::detail {

// Thrown after a syntax error has been reported; caught where the parser can resynchronise.
struct SyntaxError {};

class Parser {
 public:
  Parser(const SourceManager& sources, FileId file, DiagnosticEngine& diags);
  ast::Mission parseMission();

 private:
  friend class ParserTest;
  static constexpr std::size_t kMaxErrors = 50;
  // One level deeper in statements, conditions and formulas (nesting.hpp): past the limit, a
  // syntax error at the current token.
  [[nodiscard]] NestingGuard deeper() {
    return NestingGuard(depth_, [this] { fail(peek(), "nested too deeply (limit " + std::to_string(kMaxNesting) + ")"); });
  }

  // token access
  [[nodiscard]] const Token& peek(std::size_t ahead = 0) const;
  [[nodiscard]] bool at(Tok kind) const { return peek().kind == kind; }
  [[nodiscard]] bool atWord(std::string_view word) const;  // contextual keyword
  const Token& advance();
  bool accept(Tok kind);
  const Token& expect(Tok kind, std::string_view context);
  void expectWord(std::string_view word, std::string_view context);
  ast::Name expectName(std::string_view what);
  [[noreturn]] void fail(const Token& at, const std::string& message);
  [[noreturn]] void failExpected(std::string_view what, std::string_view context);

  // recovery
  void syncTopLevel();
  void syncStatement();

  // declarations (parser_decls.cpp)
  void parseTopLevel(ast::Mission& mission);
  void parseTeamDecl(ast::Mission& mission);
  void parseService(ast::Mission& mission);
  void parseMode(ast::Mission& mission);
  void parseMain(ast::Mission& mission);
  ast::Transition parseTransition();

  // statements (parser_stmts.cpp)
  std::vector<ast::Stmt> parseBlock(bool allowGroups, std::string_view context);
  std::vector<ast::Stmt> parseBody();
  ast::Stmt parseStatement(bool allowGroups);
  ast::Stmt parseGroupBlock();
  ast::GroupArm parseGroupArm();
  ast::GroupCondition parseGroupCondition();
  void parseTopic(ast::Stmt& stmt, bool withValue);
  [[nodiscard]] bool atStatementStart() const;

  // `next (op next)*`: the shared shape of `and` / `or` in conditions and LTL.
  template <typename Node, typename Next>
  std::unique_ptr<Node> associativeChain(Tok op, typename Node::Kind kind, Next next) {
    // `and` and `or` associate: a chain is read in a loop and held as a balanced tree, log n deep,
    // so that a condition of 100,000 terms is as safe to elaborate (recursively) as one of ten.
    std::vector<std::unique_ptr<Node>> operands;
    std::vector<SourceRange> operators;
    operands.push_back(next());
    while (at(op)) {
      operators.push_back(advance().range);
      operands.push_back(next());
    }
    return balanced<Node>(kind, operands, operators, 0, operands.size());
  }
  // operands[first, last) joined by the operators between them; a node's range is the operator
  // that joins its two halves.
  template <typename Node>
  static std::unique_ptr<Node> balanced(typename Node::Kind kind, std::vector<std::unique_ptr<Node>>& operands,
                                        const std::vector<SourceRange>& operators, std::size_t first, std::size_t last) {
    if (last - first == 1) return std::move(operands[first]);
    const std::size_t middle = first + (last - first) / 2;
    auto node = std::make_unique<Node>();
    node->kind = kind;
    node->range = operators[middle - 1];
    node->left = balanced<Node>(kind, operands, operators, first, middle);
    node->right = balanced<Node>(kind, operands, operators, middle, last);
    return node;
  }

  // expressions (parser_exprs.cpp)
  std::unique_ptr<ast::Cond> parseCond();
  std::unique_ptr<ast::Cond> parseAndCond();
  std::unique_ptr<ast::Cond> parseNotCond();
  ast::Expr parseExpr();
  std::optional<ast::RelOp> acceptRelOp();
  ast::Duration parseDuration();
  [[nodiscard]] bool atDuration() const;

  // verify block (parser_verify.cpp)
  void parseVerify(ast::Mission& mission);
  void parseVerifyItem(ast::VerifyBlock& block);
  std::unique_ptr<ast::Ltl> parseLtl();
  std::unique_ptr<ast::Ltl> parseLtlUntil();
  std::unique_ptr<ast::Ltl> parseLtlOr();
  std::unique_ptr<ast::Ltl> parseLtlAnd();
  std::unique_ptr<ast::Ltl> parseLtlUnary();

  const SourceManager& sources_;
  FileId file_;
  DiagnosticEngine& diags_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::size_t errorsAtStart_ = 0;
  std::size_t depth_ = 0;  // deeper()
};

SourceRange spanOf(const Token& first, const Token& last);

}  // namespace semo::detail
