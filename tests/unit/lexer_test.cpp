#include <gtest/gtest.h>

#include "semo/frontend/lexer.hpp"

namespace semo {
namespace {

struct Lexed {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::vector<Token> tokens;
};

std::unique_ptr<Lexed> lex(const std::string& text) {
  auto l = std::make_unique<Lexed>();
  FileId f = l->sources.add("t.semo", text);
  l->tokens = tokenize(l->sources, f, l->diags);
  return l;
}

std::vector<Tok> kinds(const Lexed& l) {
  std::vector<Tok> out;
  for (const Token& t : l.tokens) out.push_back(t.kind);
  return out;
}

TEST(Lexer, PunctuationAndGroupBrackets) {
  auto l = lex("[[ ]] [ ] { } ( ) : , . ; = == != < <= > >=");
  EXPECT_EQ(kinds(*l), (std::vector<Tok>{Tok::LGroup, Tok::RGroup, Tok::LBracket, Tok::RBracket, Tok::LBrace, Tok::RBrace,
                                         Tok::LParen, Tok::RParen, Tok::Colon, Tok::Comma, Tok::Dot, Tok::Semi, Tok::Assign,
                                         Tok::Eq, Tok::Ne, Tok::Lt, Tok::Le, Tok::Gt, Tok::Ge, Tok::End}));
  EXPECT_FALSE(l->diags.hasErrors());
}

TEST(Lexer, ArrayIndexIsNotAGroupBracket) {
  auto l = lex("burger[2]");
  EXPECT_EQ(kinds(*l), (std::vector<Tok>{Tok::Ident, Tok::LBracket, Tok::Int, Tok::RBracket, Tok::End}));
}

TEST(Lexer, ReservedAndContextualWords) {
  auto l = lex("leader group others throw loop if else publish subscribe send receive wait set main case catch default "
               "repeat not and or true false verify instance capable of mode");
  std::vector<Tok> k = kinds(*l);
  EXPECT_EQ(k[0], Tok::KwLeader);
  EXPECT_EQ(k[22], Tok::KwFalse);
  for (std::size_t i = 23; i < 28; ++i) EXPECT_EQ(k[i], Tok::Ident) << i;  // contextual words are names
  EXPECT_TRUE(isReservedWord("publish"));
  EXPECT_FALSE(isReservedWord("verify"));
}

TEST(Lexer, NumbersStringsAndPositions) {
  auto l = lex("x = -12 3.25 \"a \\\"b\\\"\"\n  # comment\n  y");
  ASSERT_EQ(l->tokens.size(), 7u);
  EXPECT_EQ(l->tokens[2].kind, Tok::Int);
  EXPECT_EQ(l->tokens[2].text, "-12");
  EXPECT_EQ(l->tokens[3].kind, Tok::Number);
  EXPECT_EQ(l->tokens[4].kind, Tok::String);
  EXPECT_EQ(l->tokens[4].text, "a \\\"b\\\"");
  EXPECT_EQ(l->tokens[5].range.begin.line, 3u);
  EXPECT_EQ(l->tokens[5].range.begin.column, 3u);
  EXPECT_FALSE(l->diags.hasErrors());
}

TEST(Lexer, UnterminatedStringIsReportedAtItsQuote) {
  auto l = lex("move(\"Paris\n)");
  ASSERT_EQ(l->diags.errorCount(), 1u);
  const Diagnostic& d = l->diags.diagnostics().front();
  EXPECT_EQ(d.message, "unterminated string");
  EXPECT_EQ(d.range.begin.line, 1u);
  EXPECT_EQ(d.range.begin.column, 6u);
}

TEST(Lexer, UnexpectedCharacterIsSkipped) {
  auto l = lex("a @ b");
  ASSERT_EQ(l->diags.errorCount(), 1u);
  EXPECT_EQ(l->diags.diagnostics().front().message, "unexpected character '@'");
  EXPECT_EQ(l->diags.diagnostics().front().range.begin.column, 3u);
  EXPECT_EQ(kinds(*l), (std::vector<Tok>{Tok::Ident, Tok::Ident, Tok::End}));
}

TEST(Lexer, NumberGluedToUnit) {
  auto l = lex("loop(2SEC)");
  ASSERT_EQ(l->diags.errorCount(), 1u);
  EXPECT_NE(l->diags.diagnostics().front().message.find("write '2 SEC'"), std::string::npos);
}

}  // namespace
}  // namespace semo
