#pragma once
// Tokens of the mission language (specs/language.md, section 1).
#include <string>
#include <string_view>
#include <vector>

#include "semo/frontend/diagnostics.hpp"

namespace semo {

enum class Tok {
  End,
  Ident,
  Int,
  Number,
  String,
  Colon,
  Comma,
  Dot,
  Semi,
  LParen,
  RParen,
  LBrace,
  RBrace,
  LBracket,
  RBracket,
  LGroup,  // [[
  RGroup,  // ]]
  Assign,
  Eq,
  Ne,
  Lt,
  Le,
  Gt,
  Ge,
  // reserved words
  KwLeader,
  KwGroup,
  KwOthers,
  KwThrow,
  KwLoop,
  KwIf,
  KwElse,
  KwPublish,
  KwSubscribe,
  KwSend,
  KwReceive,
  KwWait,
  KwSet,
  KwMain,
  KwCase,
  KwCatch,
  KwDefault,
  KwRepeat,
  KwNot,
  KwAnd,
  KwOr,
  KwTrue,
  KwFalse,
};

struct Token {
  Tok kind = Tok::End;
  std::string_view text;  // for String: the raw text between the quotes
  SourceRange range;
};

// Human-readable spelling for messages: "'{'", "identifier", "end of file".
std::string describe(Tok kind);
bool isReservedWord(std::string_view word);

// Splits a whole file into tokens; the last token is always Tok::End. Lexical errors are reported
// to `diags` and the offending characters skipped, so parsing can go on.
std::vector<Token> tokenize(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo
