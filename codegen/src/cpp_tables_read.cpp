// Reading generated tables back (cpp_tables.hpp): a tokenizer and a parser for the initializer
// syntax `emit` writes, then the parse tree read into the runtime's structs by the same schema the
// writer used, every error with its position.
#include <algorithm>
#include <charconv>
#include <limits>
#include <type_traits>

#include "semo/codegen/cpp_tables.hpp"
#include "table_schema.hpp"

namespace semo::codegen::cpp {

namespace {

using namespace semo::runtime;

using schema::IsPair;
using schema::IsVector;

// ------------------------------------------------------------------ tokens

struct Token {
  enum class Kind : std::uint8_t { LBrace, RBrace, Comma, Dot, Equals, Name, Number, String, Other, End };
  Kind kind = Kind::End;
  std::size_t offset = 0, length = 0;
  std::string text;  // Name, Number: as written; String: resolved
};

class Lexer {
 public:
  Lexer(const SourceManager& sources, FileId file, DiagnosticEngine& diags)
      : file_(file), text_(sources.text(file)), diags_(diags) {
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < text_.size(); ++i) {
      if (text_[i] == '\n') lineStarts_.push_back(i + 1);
    }
  }

  Token next() {
    skipSpaceAndComments();
    Token t;
    t.offset = pos_;
    if (pos_ >= text_.size()) return t;
    const char c = text_[pos_];
    auto single = [&](Token::Kind k) {
      t.kind = k;
      t.length = 1;
      ++pos_;
      return t;
    };
    switch (c) {
      case '{': return single(Token::Kind::LBrace);
      case '}': return single(Token::Kind::RBrace);
      case ',': return single(Token::Kind::Comma);
      case '=': return single(Token::Kind::Equals);
      case '"': return string();
      default: break;
    }
    if (c == '.' && !(pos_ + 1 < text_.size() && isDigit(text_[pos_ + 1]))) return single(Token::Kind::Dot);
    if (isDigit(c) || c == '-' || c == '.') return numberToken();
    if (isNameStart(c)) {
      while (pos_ < text_.size() && (isNameChar(text_[pos_]) || (text_[pos_] == ':' && pos_ + 1 < text_.size() && text_[pos_ + 1] == ':'))) {
        pos_ += text_[pos_] == ':' ? 2 : 1;
      }
      t.kind = Token::Kind::Name;
      t.length = pos_ - t.offset;
      t.text = text_.substr(t.offset, t.length);
      return t;
    }
    return single(Token::Kind::Other);
  }

  [[nodiscard]] SourceRange range(std::size_t offset, std::size_t length) const {
    const auto line = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset) - lineStarts_.begin();  // 1-based
    SourceRange r;
    r.begin = {file_, static_cast<std::uint32_t>(line), static_cast<std::uint32_t>(offset - lineStarts_[static_cast<std::size_t>(line) - 1] + 1)};
    r.length = static_cast<std::uint32_t>(std::clamp<std::size_t>(length, 1, 200));
    return r;
  }
  [[nodiscard]] std::size_t position() const { return pos_; }
  void seek(std::size_t p) { pos_ = p; }
  [[nodiscard]] const std::string& text() const { return text_; }
  DiagnosticEngine& diags() { return diags_; }

 private:
  static bool isDigit(char c) { return c >= '0' && c <= '9'; }
  static bool isNameStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
  static bool isNameChar(char c) { return isNameStart(c) || isDigit(c); }

  void skipSpaceAndComments() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
        const std::size_t end = text_.find("*/", pos_ + 2);
        pos_ = end == std::string::npos ? text_.size() : end + 2;
      } else {
        return;
      }
    }
  }

  Token numberToken() {
    Token t;
    t.kind = Token::Kind::Number;
    t.offset = pos_;
    if (text_[pos_] == '-') ++pos_;
    while (pos_ < text_.size() && (isNameChar(text_[pos_]) || text_[pos_] == '.' ||
                                   ((text_[pos_] == '-' || text_[pos_] == '+') && (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E')))) {
      ++pos_;
    }
    t.length = pos_ - t.offset;
    t.text = text_.substr(t.offset, t.length);
    return t;
  }

  Token string() {
    Token t;
    t.kind = Token::Kind::String;
    t.offset = pos_++;
    while (true) {
      if (pos_ >= text_.size() || text_[pos_] == '\n') {
        diags_.error(range(t.offset, 1), "unterminated string literal");
        t.kind = Token::Kind::Other;
        t.length = pos_ - t.offset;
        return t;
      }
      const char c = text_[pos_++];
      if (c == '"') break;
      if (c != '\\') {
        t.text += c;
        continue;
      }
      if (pos_ >= text_.size()) continue;
      const char e = text_[pos_++];
      switch (e) {
        case 'n': t.text += '\n'; break;
        case 't': t.text += '\t'; break;
        case 'r': t.text += '\r'; break;
        case '"': t.text += '"'; break;
        case '\\': t.text += '\\'; break;
        default:
          if (e >= '0' && e <= '7') {
            int v = e - '0';
            for (int k = 0; k < 2 && pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '7'; ++k) v = v * 8 + (text_[pos_++] - '0');
            t.text += static_cast<char>(v & 0xff);
          } else {
            diags_.error(range(pos_ - 2, 2), std::string("unknown escape sequence '\\") + e + "'");
          }
      }
    }
    t.length = pos_ - t.offset;
    return t;
  }

  FileId file_;
  const std::string& text_;
  DiagnosticEngine& diags_;
  std::size_t pos_ = 0;
  std::vector<std::size_t> lineStarts_;  // offset of each line's first byte
};

// ------------------------------------------------------------------ parse tree

class Parser {
 public:
  explicit Parser(Lexer& lexer) : lex_(lexer) { advance(); }

  std::optional<Node> value(int depth) {
    if (depth > kMaxDepth) return fail("initializer nested deeper than " + std::to_string(kMaxDepth) + " levels");
    Node n;
    n.at = lex_.range(tok_.offset, tok_.length);
    switch (tok_.kind) {
      case Token::Kind::Number: n.kind = Node::Kind::Number; break;
      case Token::Kind::String: n.kind = Node::Kind::String; break;
      case Token::Kind::Name: n.kind = Node::Kind::Name; break;
      case Token::Kind::LBrace: return list(depth);
      default: return fail("expected a value (a number, a string, a name or '{')");
    }
    n.text = tok_.text;
    advance();
    return n;
  }

  std::optional<Node> list(int depth) {
    Node n;
    n.kind = Node::Kind::List;
    n.at = lex_.range(tok_.offset, tok_.length);
    advance();  // {
    while (tok_.kind != Token::Kind::RBrace) {
      if (tok_.kind == Token::Kind::End) return fail("the file ends inside a table: a '}' is missing");
      std::string member;
      SourceRange memberAt;
      if (tok_.kind == Token::Kind::Dot) {
        advance();
        if (tok_.kind != Token::Kind::Name) return fail("expected a member name after '.'");
        member = tok_.text;
        memberAt = lex_.range(tok_.offset, tok_.length);
        advance();
        if (tok_.kind != Token::Kind::Equals) return fail("expected '=' after '." + member + "'");
        advance();
      }
      if (!n.elements.empty() && member.empty() != n.elements.front().member.empty()) {
        return fail("a list mixes designated members (.name = value) and plain values");
      }
      std::optional<Node> element = value(depth + 1);
      if (!element) return std::nullopt;
      element->member = member;
      if (!member.empty()) element->at = memberAt;  // a member's errors point at its name
      n.elements.push_back(std::move(*element));
      if (tok_.kind == Token::Kind::Comma) {
        advance();
        continue;
      }
      if (tok_.kind != Token::Kind::RBrace) return fail("expected ',' or '}'");
    }
    advance();  // }
    return n;
  }

  [[nodiscard]] const Token& token() const { return tok_; }
  void advance() { tok_ = lex_.next(); }

 private:
  std::nullopt_t fail(const std::string& message) {
    lex_.diags().error(lex_.range(tok_.offset, std::max<std::size_t>(tok_.length, 1)), message);
    return std::nullopt;
  }

  Lexer& lex_;
  Token tok_;
};

// ------------------------------------------------------------------ typed reading

class Reader {
 public:
  explicit Reader(DiagnosticEngine& diags) : diags_(diags) {}

  template <class T> bool read(const Node& n, T& out) {
    if constexpr (std::is_same_v<T, bool>) {
      if (n.kind == Node::Kind::Name && (n.text == "true" || n.text == "false")) {
        out = n.text == "true";
        return true;
      }
      return error(n, "expected true or false");
    } else if constexpr (std::is_enum_v<T>) {
      using Info = schema::EnumInfo<T>;
      const std::string prefix = std::string(Info::qualified) + "::";
      if (n.kind == Node::Kind::Name && n.text.starts_with(prefix)) {
        for (std::size_t i = 0; i < Info::names.size(); ++i) {
          if (n.text.substr(prefix.size()) == Info::names[i]) {
            out = static_cast<T>(i);
            return true;
          }
        }
      }
      return error(n, "expected one of " + prefix + "...");
    } else if constexpr (std::is_integral_v<T>) {
      if constexpr (std::is_same_v<T, Id>) {
        if (n.kind == Node::Kind::Name && n.text == "kNone") {
          out = kNone;
          return true;
        }
      }
      if (n.kind != Node::Kind::Number) return error(n, "expected an integer");
      T v{};
      const auto [end, ec] = std::from_chars(n.text.data(), n.text.data() + n.text.size(), v);
      if (ec != std::errc() || end != n.text.data() + n.text.size()) return error(n, "expected an integer in range, not '" + n.text + "'");
      out = v;
      return true;
    } else if constexpr (std::is_floating_point_v<T>) {
      if (n.kind != Node::Kind::Number) return error(n, "expected a number");
      T v{};
      const auto [end, ec] = std::from_chars(n.text.data(), n.text.data() + n.text.size(), v);
      if (ec != std::errc() || end != n.text.data() + n.text.size()) return error(n, "expected a number, not '" + n.text + "'");
      out = v;
      return true;
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (n.kind != Node::Kind::String) return error(n, "expected a string literal");
      out = n.text;
      return true;
    } else if constexpr (IsPair<T>::value) {
      if (n.kind != Node::Kind::List || n.elements.size() != 2 || !n.elements[0].member.empty()) return error(n, "expected {first, second}");
      return read(n.elements[0], out.first) && read(n.elements[1], out.second);
    } else if constexpr (IsVector<T>::value) {
      if (n.kind != Node::Kind::List) return error(n, "expected a list in braces");
      if (!n.elements.empty() && !n.elements.front().member.empty()) return error(n.elements.front(), "expected a list of values, not members");
      out.assign(n.elements.size(), typename T::value_type{});
      for (std::size_t i = 0; i < n.elements.size(); ++i) {
        if (!read(n.elements[i], out[i])) return false;
      }
      return true;
    } else {
      if (n.kind != Node::Kind::List) return error(n, "expected a table in braces");
      if (!n.elements.empty() && n.elements.front().member.empty()) return error(n.elements.front(), "expected members (.name = value)");
      Members v{*this, n};
      schema::describe(v, out);
      if (!v.ok) return false;
      if (v.next < n.elements.size()) {
        const Node& extra = n.elements[v.next];
        return error(extra, "'." + extra.member + "' is not a member here, or comes out of order (members go in declaration order)");
      }
      return true;
    }
  }

 private:
  // Walks the schema's members in order, taking each from the list when it is the next one there.
  struct Members {
    Reader& r;
    const Node& list;
    std::size_t next = 0;
    bool ok = true;
    template <class F> void field(const char* name, F& value) {
      if (!ok || next >= list.elements.size() || list.elements[next].member != name) return;
      ok = r.read(list.elements[next++], value);
    }
  };

  bool error(const Node& n, const std::string& message) {
    diags_.error(n.at, message);
    return false;
  }

  DiagnosticEngine& diags_;
};

// ------------------------------------------------------------------ comparing

class Comparer {
 public:
  template <class T> bool same(const T& e, const T& a, const Node* n, const std::string& path) {
    if (diff_) return false;
    if constexpr (IsVector<T>::value) {
      using E = typename T::value_type;
      if constexpr (std::is_same_v<E, Row>) {
        if (!sameRows(e, a, n, path)) return false;
      }
      if (e.size() != a.size()) {
        return differ(n, path, std::to_string(e.size()) + " elements", std::to_string(a.size()) + " elements",
                      "has " + std::to_string(a.size()) + " elements where the projection has " + std::to_string(e.size()));
      }
      for (std::size_t i = 0; i < e.size(); ++i) {
        const Node* c = n != nullptr && n->kind == Node::Kind::List && i < n->elements.size() ? &n->elements[i] : n;
        if (!same(e[i], a[i], c, path + "[" + std::to_string(i) + "]")) {
          if constexpr (std::is_same_v<E, Row>) {
            if (diff_->irRule == kNone) diff_->irRule = e[i].irRule;  // a difference inside a row is about its rule
          }
          return false;
        }
      }
      return true;
    } else if constexpr (std::is_class_v<T> && !std::is_same_v<T, std::string> && !IsPair<T>::value) {
      Pointers p;
      schema::describe(p, const_cast<T&>(e));  // describe only reads through the references here
      Members v{*this, std::move(p.out), n, path};
      schema::describe(v, const_cast<T&>(a));
      return !diff_;
    } else {
      if (e == a) return true;
      return differ(n, path, schema::scalarText(e), schema::scalarText(a), {});
    }
  }

  std::optional<Difference> difference() { return diff_; }

 private:
  // Rows: every IR rule of the robot's program has exactly one row (a bijection), then the rows
  // compare member by member in order.
  bool sameRows(const std::vector<Row>& e, const std::vector<Row>& a, const Node* n, const std::string& path) {
    auto count = [](const std::vector<Row>& rows, Id rule) {
      return std::count_if(rows.begin(), rows.end(), [rule](const Row& r) { return r.irRule == rule; });
    };
    for (const Row& r : e) {
      if (r.irRule == kNone || count(a, r.irRule) == 1) continue;
      differ(n, path, rowText(r), count(a, r.irRule) == 0 ? "none" : std::to_string(count(a, r.irRule)) + " rows",
             count(a, r.irRule) == 0 ? "has no row for this IR rule" : "has several rows for this IR rule");
      diff_->irRule = r.irRule;
      return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].irRule == kNone || count(e, a[i].irRule) != 0) continue;
      const Node* c = n != nullptr && i < n->elements.size() ? &n->elements[i] : n;
      differ(c, path + "[" + std::to_string(i) + "]", "none", rowText(a[i]), "is a row for this IR rule, which is no step of this robot's program");
      diff_->irRule = a[i].irRule;
      return false;
    }
    return true;
  }

  // The members of a struct in order, as pointers: the expected object's, to pair with the actual's.
  struct Pointers {
    std::vector<const void*> out;
    template <class F> void field(const char*, F& value) { out.push_back(&value); }
  };

  struct Members {
    Comparer& c;
    std::vector<const void*> expected;
    const Node* node;
    std::string path;
    std::size_t index = 0;
    template <class F> void field(const char* name, F& actual) {
      const F& e = *static_cast<const F*>(expected[index++]);  // same struct, same member order
      c.same(e, actual, child(name), path.empty() ? name : path + "." + name);
    }
    [[nodiscard]] const Node* child(const char* name) const {
      if (node == nullptr || node->kind != Node::Kind::List) return node;
      for (const Node& m : node->elements) {
        if (m.member == name) return &m;
      }
      return node;  // at its default: the table that leaves it out
    }
  };

  bool differ(const Node* n, const std::string& path, std::string expected, std::string actual, std::string what) {
    Difference d;
    if (n != nullptr) d.at = n->at;
    d.path = path;
    d.expected = std::move(expected);
    d.actual = std::move(actual);
    d.what = std::move(what);
    diff_ = std::move(d);
    return false;
  }

  std::optional<Difference> diff_;
};

}  // namespace

std::optional<Node> parseInitializer(const SourceManager& sources, FileId file, std::string_view declaration, DiagnosticEngine& diags) {
  const std::string& text = sources.text(file);
  Lexer lexer(sources, file, diags);
  const std::size_t at = text.find(declaration);
  if (at == std::string::npos) {
    diags.error({{file, 0, 0}, 1}, "no '" + std::string(declaration) + "' in this file: it is not a table emit wrote");
    return std::nullopt;
  }
  lexer.seek(at + declaration.size());
  Parser parser(lexer);
  if (parser.token().kind != Token::Kind::LBrace) {
    diags.error(lexer.range(parser.token().offset, 1), "expected '{' after '" + std::string(declaration) + "'");
    return std::nullopt;
  }
  std::optional<Node> node = parser.list(0);
  if (node && (parser.token().kind != Token::Kind::Other || text[parser.token().offset] != ';')) {
    diags.error(lexer.range(parser.token().offset, 1), "expected ';' after the table");
    return std::nullopt;
  }
  return diags.hasErrors() ? std::nullopt : node;
}

bool readMission(const Node& node, MissionTables& out, DiagnosticEngine& diags) { return Reader(diags).read(node, out); }
bool readRobot(const Node& node, RobotTable& out, DiagnosticEngine& diags) { return Reader(diags).read(node, out); }

std::optional<Difference> compareMission(const MissionTables& expected, const MissionTables& actual, const Node& node) {
  Comparer c;
  c.same(expected, actual, &node, "");
  return c.difference();
}

std::optional<Difference> compareRobot(const RobotTable& expected, const RobotTable& actual, const Node& node) {
  Comparer c;
  c.same(expected, actual, &node, "");
  return c.difference();
}

}  // namespace semo::codegen::cpp
