#include "semo/frontend/lexer.hpp"

#include <array>
#include <optional>
#include <string>
#include <cctype>
#include <utility>

namespace semo {

namespace {

constexpr std::array<std::pair<std::string_view, Tok>, 23> kReserved{{
    {"leader", Tok::KwLeader},   {"group", Tok::KwGroup},     {"others", Tok::KwOthers},
    {"throw", Tok::KwThrow},     {"loop", Tok::KwLoop},       {"if", Tok::KwIf},
    {"else", Tok::KwElse},       {"publish", Tok::KwPublish}, {"subscribe", Tok::KwSubscribe},
    {"send", Tok::KwSend},       {"receive", Tok::KwReceive}, {"wait", Tok::KwWait},
    {"set", Tok::KwSet},         {"main", Tok::KwMain},       {"case", Tok::KwCase},
    {"catch", Tok::KwCatch},     {"default", Tok::KwDefault}, {"repeat", Tok::KwRepeat},
    {"not", Tok::KwNot},         {"and", Tok::KwAnd},         {"or", Tok::KwOr},
    {"true", Tok::KwTrue},       {"false", Tok::KwFalse},
}};

bool isIdentStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isIdentChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

class Lexer {
 public:
  Lexer(const SourceManager& sources, FileId file, DiagnosticEngine& diags)
      : text_(sources.text(file)), file_(file), diags_(diags) {}

  std::vector<Token> run() {
    std::vector<Token> tokens;
    while (true) {
      skipSpaceAndComments();
      if (pos_ >= text_.size()) {
        tokens.push_back({Tok::End, {}, rangeAt(pos_, 1)});
        return tokens;
      }
      if (auto token = next()) tokens.push_back(*token);
    }
  }

 private:
  SourceRange rangeAt(std::size_t offset, std::size_t length) const {
    // Columns are computed from the start of the current line; offset is never before it.
    auto column = static_cast<std::uint32_t>(offset - lineStart_ + 1);
    return {{file_, line_, column}, static_cast<std::uint32_t>(length == 0 ? 1 : length)};
  }

  void skipSpaceAndComments() {
    while (pos_ < text_.size()) {
      char c = text_[pos_];
      if (c == '\n') {
        ++pos_;
        ++line_;
        lineStart_ = pos_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        return;
      }
    }
  }

  std::optional<Token> make(Tok kind, std::size_t begin, std::size_t length) {
    Token t{kind, text_.substr(begin, length), rangeAt(begin, length)};
    pos_ = begin + length;
    return t;
  }

  std::optional<Token> next() {
    std::size_t begin = pos_;
    char c = text_[pos_];
    char d = pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0';
    if (isIdentStart(c)) {
      std::size_t end = pos_;
      while (end < text_.size() && isIdentChar(text_[end])) ++end;
      std::string_view word = text_.substr(begin, end - begin);
      Tok kind = Tok::Ident;
      for (const auto& [spelling, tok] : kReserved) {
        if (spelling == word) kind = tok;
      }
      return make(kind, begin, end - begin);
    }
    if (isDigit(c) || (c == '-' && isDigit(d))) return number(begin);
    if (c == '"') return string(begin);
    switch (c) {
      case ':': return make(Tok::Colon, begin, 1);
      case ',': return make(Tok::Comma, begin, 1);
      case '.': return make(Tok::Dot, begin, 1);
      case ';': return make(Tok::Semi, begin, 1);
      case '(': return make(Tok::LParen, begin, 1);
      case ')': return make(Tok::RParen, begin, 1);
      case '{': return make(Tok::LBrace, begin, 1);
      case '}': return make(Tok::RBrace, begin, 1);
      case '[': return d == '[' ? make(Tok::LGroup, begin, 2) : make(Tok::LBracket, begin, 1);
      case ']': return d == ']' ? make(Tok::RGroup, begin, 2) : make(Tok::RBracket, begin, 1);
      case '=': return d == '=' ? make(Tok::Eq, begin, 2) : make(Tok::Assign, begin, 1);
      case '<': return d == '=' ? make(Tok::Le, begin, 2) : make(Tok::Lt, begin, 1);
      case '>': return d == '=' ? make(Tok::Ge, begin, 2) : make(Tok::Gt, begin, 1);
      case '!':
        if (d == '=') return make(Tok::Ne, begin, 2);
        break;
      default:
        break;
    }
    auto bad = static_cast<unsigned char>(c);
    std::string shown = std::isprint(bad) ? std::string("'") + c + "'" : "byte 0x" + hex(bad);
    diags_.error(rangeAt(begin, 1), "unexpected character " + shown);
    ++pos_;
    return std::nullopt;
  }

  static std::string hex(unsigned char c) {
    const char* digits = "0123456789abcdef";
    return {digits[c >> 4], digits[c & 15]};
  }

  std::optional<Token> number(std::size_t begin) {
    std::size_t end = pos_ + (text_[pos_] == '-' ? 1 : 0);
    while (end < text_.size() && isDigit(text_[end])) ++end;
    Tok kind = Tok::Int;
    if (end + 1 < text_.size() && text_[end] == '.' && isDigit(text_[end + 1])) {
      kind = Tok::Number;
      ++end;
      while (end < text_.size() && isDigit(text_[end])) ++end;
    }
    if (end < text_.size() && isIdentStart(text_[end])) {
      // "2SEC" is almost certainly a duration missing its space; say so rather than mis-lexing.
      std::size_t wordEnd = end;
      while (wordEnd < text_.size() && isIdentChar(text_[wordEnd])) ++wordEnd;
      diags_.error(rangeAt(begin, wordEnd - begin),
                   "a number must be separated from the word after it (write '" +
                       std::string(text_.substr(begin, end - begin)) + " " +
                       std::string(text_.substr(end, wordEnd - end)) + "')");
      pos_ = wordEnd;
      return std::nullopt;
    }
    return make(kind, begin, end - begin);
  }

  std::optional<Token> string(std::size_t begin) {
    std::size_t end = begin + 1;
    while (end < text_.size() && text_[end] != '"' && text_[end] != '\n') {
      if (text_[end] == '\\' && end + 1 < text_.size() && text_[end + 1] != '\n') ++end;
      ++end;
    }
    if (end >= text_.size() || text_[end] != '"') {
      diags_.error(rangeAt(begin, 1), "unterminated string");
      Token t{Tok::String, text_.substr(begin + 1, end - begin - 1), rangeAt(begin, end - begin)};
      pos_ = end;
      return t;
    }
    // A string is written out again (traces, JSON, generated code): it must be text.
    if (const std::size_t bad = firstInvalidUtf8(text_.substr(begin + 1, end - begin - 1)); bad != std::string_view::npos) {
      diags_.error(rangeAt(begin + 1 + bad, 1), "a string must be UTF-8 text: byte 0x" + hex(static_cast<unsigned char>(text_[begin + 1 + bad])) + " is not");
    }
    Token t{Tok::String, text_.substr(begin + 1, end - begin - 1), rangeAt(begin, end - begin + 1)};
    pos_ = end + 1;
    return t;
  }

  std::string_view text_;
  FileId file_;
  DiagnosticEngine& diags_;
  std::size_t pos_ = 0;
  std::size_t lineStart_ = 0;
  std::uint32_t line_ = 1;
};

}  // namespace

bool isReservedWord(std::string_view word) {
  for (const auto& [spelling, tok] : kReserved) {
    if (spelling == word) return true;
  }
  return false;
}

std::string describe(Tok kind) {
  switch (kind) {
    case Tok::End: return "end of file";
    case Tok::Ident: return "a name";
    case Tok::Int: return "an integer";
    case Tok::Number: return "a number";
    case Tok::String: return "a string";
    case Tok::Colon: return "':'";
    case Tok::Comma: return "','";
    case Tok::Dot: return "'.'";
    case Tok::Semi: return "';'";
    case Tok::LParen: return "'('";
    case Tok::RParen: return "')'";
    case Tok::LBrace: return "'{'";
    case Tok::RBrace: return "'}'";
    case Tok::LBracket: return "'['";
    case Tok::RBracket: return "']'";
    case Tok::LGroup: return "'[['";
    case Tok::RGroup: return "']]'";
    case Tok::Assign: return "'='";
    case Tok::Eq: return "'=='";
    case Tok::Ne: return "'!='";
    case Tok::Lt: return "'<'";
    case Tok::Le: return "'<='";
    case Tok::Gt: return "'>'";
    case Tok::Ge: return "'>='";
    default: break;
  }
  for (const auto& [spelling, tok] : kReserved) {
    if (tok == kind) return "'" + std::string(spelling) + "'";
  }
  return "a token";
}

std::vector<Token> tokenize(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  return Lexer(sources, file, diags).run();
}

}  // namespace semo
