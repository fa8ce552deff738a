// Reads the text form of the IR (specs/ir.md).
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <unordered_map>
#include <unordered_set>

#include "semo/frontend/nesting.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo::ir {

namespace {

enum class T { End, Name, Int, Number, String, Punct };

struct Token {
  T kind = T::End;
  std::string_view text;
  SourceRange range;
};

struct Failure {};

class Reader {
 public:
  Reader(const SourceManager& sources, FileId file, DiagnosticEngine& diags)
      : text_(sources.text(file)), file_(file), diags_(diags) {
    tokenize();
  }

  std::optional<Model> run() {
    try {
      expectWord("semo-ir", "at the start of an IR file");
      const Token& version = expectKind(T::Int, "the IR version");
      if (version.text != "1") fail(version, "unsupported IR version " + std::string(version.text) + " (this semo reads version 1)");
      accept(";");
      while (peek().kind != T::End) item();
    } catch (const Failure&) {
      return std::nullopt;
    }
    if (diags_.hasErrors()) return std::nullopt;
    return std::move(model_);
  }

 private:
  // ---- tokens
  void tokenize() {
    std::size_t pos = 0, lineStart = 0;
    std::uint32_t line = 1;
    auto range = [&](std::size_t b, std::size_t e) {
      return SourceRange{{file_, line, static_cast<std::uint32_t>(b - lineStart + 1)}, static_cast<std::uint32_t>(e - b)};
    };
    while (pos < text_.size()) {
      char c = text_[pos];
      if (c == '\n') {
        ++line;
        lineStart = ++pos;
        continue;
      }
      if (c == ' ' || c == '\t' || c == '\r') {
        ++pos;
        continue;
      }
      if (c == '#') {
        while (pos < text_.size() && text_[pos] != '\n') ++pos;
        continue;
      }
      std::size_t b = pos;
      if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
        while (pos < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos])) || text_[pos] == '_' ||
                                      text_[pos] == '.' || text_[pos] == '-')) {
          // '-' belongs to a name only inside "semo-ir"; elsewhere it is an operator.
          if (text_[pos] == '-' && text_.substr(b, pos - b) != "semo") break;
          if (text_[pos] == '.' && pos + 1 < text_.size() && text_[pos + 1] == '.') break;  // `0..3`
          ++pos;
        }
        // An index suffix `[N]` is part of the name: arrays are flattened.
        if (pos < text_.size() && text_[pos] == '[') {
          std::size_t e = pos + 1;
          while (e < text_.size() && std::isdigit(static_cast<unsigned char>(text_[e]))) ++e;
          if (e > pos + 1 && e < text_.size() && text_[e] == ']') pos = e + 1;
        }
        tokens_.push_back({T::Name, text_.substr(b, pos - b), range(b, pos)});
      } else if (std::isdigit(static_cast<unsigned char>(c))) {
        while (pos < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos]))) ++pos;
        T kind = T::Int;
        if (pos + 1 < text_.size() && text_[pos] == '.' && std::isdigit(static_cast<unsigned char>(text_[pos + 1]))) {
          kind = T::Number;
          ++pos;
          while (pos < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos])) || text_[pos] == 'e' ||
                                        text_[pos] == '-' || text_[pos] == '+')) {
            ++pos;
          }
        }
        tokens_.push_back({kind, text_.substr(b, pos - b), range(b, pos)});
      } else if (c == '"') {
        ++pos;
        while (pos < text_.size() && text_[pos] != '"' && text_[pos] != '\n') pos += text_[pos] == '\\' ? 2 : 1;
        if (pos >= text_.size() || text_[pos] != '"') {
          diags_.error(range(b, b + 1), "unterminated string");
          pos = std::min(pos, text_.size());
          continue;
        }
        ++pos;
        // A string is written out again (traces, JSON): it must be text.
        if (const std::size_t bad = firstInvalidUtf8(text_.substr(b + 1, pos - b - 2)); bad != std::string_view::npos) {
          static const char* digits = "0123456789abcdef";
          const auto byte = static_cast<unsigned char>(text_[b + 1 + bad]);
          diags_.error(range(b + 1 + bad, b + 2 + bad), std::string("a string must be UTF-8 text: byte 0x") + digits[byte >> 4] + digits[byte & 15] +
                                                            " is not");
        }
        tokens_.push_back({T::String, text_.substr(b + 1, pos - b - 2), range(b, pos)});
      } else {
        static const char* twoChar[] = {"->", "==", "!=", "<=", ">=", "&&", "||", "=>", ".."};
        std::size_t length = 1;
        for (const char* t : twoChar) {
          if (text_.compare(pos, 2, t) == 0) length = 2;
        }
        if (length == 1 && std::string_view(":;,()'=<>+-*/%!?@[]{}").find(c) == std::string_view::npos) {
          diags_.error(range(b, b + 1), std::string("unexpected character '") + c + "'");
          ++pos;
          continue;
        }
        pos += length;
        tokens_.push_back({T::Punct, text_.substr(b, length), range(b, pos)});
      }
    }
    tokens_.push_back({T::End, {}, range(pos, pos + 1)});
  }

  const Token& peek(std::size_t ahead = 0) const { return tokens_[std::min(pos_ + ahead, tokens_.size() - 1)]; }
  const Token& advance() {
    const Token& t = peek();
    if (pos_ + 1 < tokens_.size()) ++pos_;
    return t;
  }
  bool isPunct(std::string_view p) const { return peek().kind == T::Punct && peek().text == p; }
  // `INT / INT :` from `ahead` on: a probability written as a fraction (an expression never has
  // `:` after a division).
  bool startsFraction(std::size_t ahead) const {
    auto punct = [this](std::size_t k, std::string_view p) { return peek(k).kind == T::Punct && peek(k).text == p; };
    return peek(ahead).kind == T::Int && punct(ahead + 1, "/") && peek(ahead + 2).kind == T::Int && punct(ahead + 3, ":");
  }
  bool isWord(std::string_view w) const { return peek().kind == T::Name && peek().text == w; }
  bool accept(std::string_view p) {
    if (!isPunct(p)) return false;
    advance();
    return true;
  }
  [[noreturn]] void fail(const Token& at, const std::string& message) {
    diags_.error(at.range, message);
    throw Failure{};
  }
  std::string found() const {
    return peek().kind == T::End ? "end of file" : "'" + std::string(peek().text) + "'";
  }
  void expect(std::string_view p, const std::string& context) {
    if (!accept(p)) fail(peek(), "expected '" + std::string(p) + "' " + context + ", found " + found());
  }
  void expectWord(std::string_view w, const std::string& context) {
    if (!isWord(w)) fail(peek(), "expected '" + std::string(w) + "' " + context + ", found " + found());
    advance();
  }
  const Token& expectKind(T kind, const std::string& what) {
    if (peek().kind != kind) fail(peek(), "expected " + what + ", found " + found());
    return advance();
  }
  // `negative`: the literal follows a '-', so that -2147483648 can be written.
  std::int32_t integer(const Token& t, bool negative = false) {
    std::int64_t v = 0;
    auto [ptr, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (negative) v = -v;
    if (ec != std::errc() || v < INT32_MIN || v > INT32_MAX) fail(t, "integer out of range");
    return static_cast<std::int32_t>(v);
  }
  std::int32_t signedInteger() {
    bool negative = accept("-");
    return integer(expectKind(T::Int, "an integer"), negative);
  }

  // ---- items
  void item() {
    if (isWord("robots")) {
      advance();
      while (peek().kind == T::Name) {
        const Token& at = advance();
        std::string name(at.text);
        if (robotIndex_.count(name) != 0) fail(at, "robot '" + name + "' is declared twice");
        robotIndex_[name] = static_cast<std::int32_t>(model_.robots.size());
        model_.robots.push_back(name);
      }
      expect(";", "after the robot names");
    } else if (isWord("assume")) {
      advance();
      model_.assumptions.push_back(unescape(expectKind(T::String, "a quoted assumption").text));
      expect(";", "after the assumption");
    } else if (isWord("var")) {
      variable();
    } else if (isWord("rule")) {
      rule();
    } else if (isWord("invariant")) {
      advance();
      Invariant inv;
      verdictHeader("invariant", inv.name, inv.origin);
      inv.holds = wholeExpr();
      expect(";", "after the invariant");
      model_.invariants.push_back(std::move(inv));
    } else if (isWord("property")) {
      advance();
      Property prop;
      verdictHeader("property", prop.name, prop.origin, &prop.settled);
      prop.formula = ltl();
      expect(";", "after the property");
      model_.properties.push_back(std::move(prop));
    } else if (isWord("valid_end")) {
      const Token& at = advance();
      if (model_.validEnd) fail(at, "valid_end is given twice");
      expect(":", "after 'valid_end'");
      model_.validEnd = wholeExpr();
      expect(";", "after valid_end");
    } else {
      fail(peek(), "expected 'var', 'rule', 'invariant', 'property', 'valid_end', 'robots' or 'assume', found " + found());
    }
  }

  // `NAME [@origin("...")] :` of an invariant or a property. Verdicts and JSON output are keyed by
  // name: two of one name (invariants and properties together) would be ambiguous.
  void verdictHeader(const std::string& what, std::string& name, std::string& origin, bool* settled = nullptr) {
    const Token& nameToken = peek();
    name = declaredName(std::string(what == "invariant" ? "an " : "a ") + what + " name").first;
    if (!invariantNames_.insert(name).second) fail(nameToken, what + " '" + name + "' is declared twice");
    attributes([&](const Token& key, const std::string& value) {
      if (key.text == "origin") return origin = value, true;
      if (key.text == "settled" && settled != nullptr) return *settled = true, true;
      return false;
    });
    expect(":", "after the " + what + " name");
  }

  static std::string unescape(std::string_view raw) {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '\\' && i + 1 < raw.size()) {
        ++i;
        out += raw[i] == 'n' ? '\n' : raw[i];  // \n is a line break; \" \\ and any other \c are c
        continue;
      }
      out += raw[i];
    }
    return out;
  }

  // `@key`, `@key(value)`; `handle` returns false for an unknown key.
  template <typename Handle>
  void attributes(Handle handle) {
    while (accept("@")) {
      const Token& key = expectKind(T::Name, "an attribute name after '@'");
      std::string value;
      if (accept("(")) {
        const Token& v = peek();
        if (v.kind != T::Name && v.kind != T::String) fail(v, "expected a name or a string in the attribute, found " + found());
        value = v.kind == T::String ? unescape(advance().text) : std::string(advance().text);
        expect(")", "to close the attribute");
      }
      if (!handle(key, value)) fail(key, "unknown attribute '@" + std::string(key.text) + "' here");
    }
  }

  std::int32_t robot(const Token& key, const std::string& name) {
    auto it = robotIndex_.find(name);
    if (it == robotIndex_.end()) fail(key, "unknown robot '" + name + "' (declare it with 'robots ...;')");
    return it->second;
  }

  void declare(Variable v, const Token& at) {
    if (varIndex_.count(v.name) != 0) fail(at, "variable '" + v.name + "' is declared twice");
    varIndex_[v.name] = static_cast<VarId>(model_.variables.size());
    model_.variables.push_back(std::move(v));
  }

  // The name in a declaration: a name, or a quoted string taken literally (for names that are not
  // names of the text form, such as "group_formation[Search group]" or one element "a[2]").
  std::pair<std::string, bool> declaredName(const std::string& what) {
    if (peek().kind == T::String) return {unescape(advance().text), true};
    return {std::string(expectKind(T::Name, what).text), false};
  }

  void variable() {
    advance();
    const Token& nameToken = peek();
    auto [name, quoted] = declaredName("a variable name");
    std::int32_t arraySize = 0;
    if (auto open = name.find('['); open != std::string::npos && !quoted) {
      std::string_view digits = std::string_view(name).substr(open + 1, name.size() - open - 2);
      auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), arraySize);
      name.resize(open);
      if (ec != std::errc() || arraySize > 1'000'000) fail(nameToken, "an array has at most 1000000 elements");
      if (arraySize < 1) fail(nameToken, "an array needs at least one element");
    }
    expect(":", "after the variable name");
    Variable v;
    v.name = name;
    if (isWord("bool")) {
      advance();
      v.isBool = true;
    } else {
      v.min = signedInteger();
      expect("..", "in the range 'min..max'");
      v.max = signedInteger();
      if (v.max < v.min) fail(nameToken, "empty range: max is below min");
    }
    v.init = v.min;
    if (accept("=")) {
      if (isWord("true") || isWord("false")) {
        v.init = advance().text == "true" ? 1 : 0;
      } else {
        v.init = signedInteger();
      }
    }
    if (v.init < v.min || v.init > v.max) fail(nameToken, "initial value " + std::to_string(v.init) + " is outside the range");
    attributes([&](const Token& key, const std::string& value) {
      if (key.text == "robot") return v.robot = robot(key, value), true;
      if (key.text == "values" || key.text == "facts") {
        std::vector<std::string>& names = key.text == "values" ? v.valueNames : v.facts;
        std::string word;
        for (char c : value + " ") {
          if (c != ' ') {
            word += c;
          } else if (!word.empty()) {
            names.push_back(std::move(word));
            word.clear();
          }
        }
        return true;
      }
      return false;
    });
    expect(";", "after the variable declaration");
    if (arraySize == 0) return declare(std::move(v), nameToken);
    for (std::int32_t i = 0; i < arraySize; ++i) {
      Variable element = v;
      element.name = name + "[" + std::to_string(i) + "]";
      declare(std::move(element), nameToken);
    }
  }

  void rule() {
    advance();
    Rule r;
    const Token& nameToken = peek();
    r.name = declaredName("a rule name").first;
    if (!ruleNames_.insert(r.name).second) fail(nameToken, "rule '" + r.name + "' is declared twice");
    attributes([&](const Token& key, const std::string& value) {
      if (key.text == "robot") return r.robot = robot(key, value), true;
      if (key.text == "origin") return r.origin = Origin::parse(value, r.origin.construct), true;
      if (key.text == "construct") return r.origin.construct = value, true;
      if (key.text == "label") return r.label = value, true;
      if (key.text == "fair") return r.weaklyFair = true, r.fairGroup = value, true;
      if (key.text == "senses") {
        // "POINT=1 POINT=0 ...": the sensed conditions the step decides, and how.
        std::string word;
        for (char c : value + " ") {
          if (c != ' ') {
            word += c;
            continue;
          }
          if (word.empty()) continue;
          const std::size_t eq = word.rfind('=');
          if (eq == std::string::npos || eq == 0 || eq + 2 != word.size() || (word[eq + 1] != '0' && word[eq + 1] != '1')) {
            fail(key, "'" + word + "' in @senses is not POINT=0 or POINT=1");
          }
          r.sensed.push_back({word.substr(0, eq), word[eq + 1] == '1'});
          word.clear();
        }
        return true;
      }
      if (key.text == "strongly_fair") return r.weaklyFair = r.stronglyFair = true, true;
      if (key.text == "kind") {
        auto kind = kindFromName(value);
        if (!kind) fail(key, "unknown rule kind '" + value + "' (step, delivery, loss, crash, environment, timer)");
        r.kind = *kind;
        return true;
      }
      return false;
    });
    expect(":", "after the rule name");
    r.guard = wholeExpr();
    expect("->", "after the guard");
    double total = 0;
    do {
      Branch b;
      if (startsFraction(0)) {
        const Token& n = advance();
        advance();  // '/'
        const Token& d = advance();
        const std::int64_t num = integer(n, false), den = integer(d, false);
        if (den == 0) fail(d, "a probability's denominator must not be 0");
        if (num <= 0 || num > den) fail(n, "a probability must be in (0, 1]");
        b.numerator = static_cast<std::uint32_t>(num);
        b.denominator = static_cast<std::uint32_t>(den);
        b.probability = static_cast<double>(num) / static_cast<double>(den);
        expect(":", "after the probability");
      } else if (peek().kind == T::Number || (peek().kind == T::Int && peek(1).kind == T::Punct && peek(1).text == ":")) {
        const Token& p = advance();
        b.probability = std::strtod(std::string(p.text).c_str(), nullptr);
        if (!(b.probability > 0 && b.probability <= 1)) fail(p, "a probability must be in (0, 1]");
        expect(":", "after the probability");
      }
      total += b.probability;
      if (isWord("skip")) {
        advance();
      } else {
        do {
          const Token& target = expectKind(T::Name, "an assignment 'x' = ...'");
          auto it = varIndex_.find(std::string(target.text));
          if (it == varIndex_.end()) fail(target, "undeclared variable '" + std::string(target.text) + "'");
          for (const Assignment& a : b.assignments) {
            if (a.var == it->second) fail(target, "variable '" + std::string(target.text) + "' is assigned twice in one branch");
          }
          expect("'", "after the assigned variable (write x' = ...)");
          expect("=", "in the assignment");
          b.assignments.push_back({it->second, wholeExpr()});
        } while (accept(","));
      }
      r.branches.push_back(std::move(b));
      // The qualitative engines keep an outcome in 8 bits; a rule with more (a synchronous round of
      // many random choices) is for the quantitative engine, which says so to the others.
      if (r.branches.size() > kMaxOutcomes) fail(peek(), "a rule has at most " + std::to_string(kMaxOutcomes) + " outcomes");
    } while (accept("+"));
    if (std::fabs(total - 1.0) > 1e-9) {  // a single outcome too: `-> 0.5 : x' = 1;` is an error
      fail(peek(), "the probabilities of rule '" + r.name + "' add up to " + std::to_string(total) + ", not 1");
    }
    expect(";", "after the rule");
    model_.rules.push_back(std::move(r));
  }

  // ---- temporal formulas: atoms in braces; loosest first: until/release (right), =>, ||, &&, prefix
  Ltl ltl(int depth = 0) {
    if (depth > 200) fail(peek(), "formula nested too deeply");
    Ltl left = ltlImplies(depth);
    for (auto kind : {Ltl::Kind::Until, Ltl::Kind::Release}) {
      if (isWord(ltlKeyword(kind))) {
        advance();
        return Ltl::binary(kind, std::move(left), ltl(depth + 1));
      }
    }
    return left;
  }
  Ltl ltlImplies(int depth) {
    Ltl left = ltlChain(depth, 0);
    if (!accept("=>")) return left;
    return Ltl::binary(Ltl::Kind::Implies, std::move(left), ltlImplies(depth + 1));
  }
  Ltl ltlChain(int depth, int level) {  // level 0: ||, level 1: &&
    if (level == 2) return ltlPrefix(depth);
    // A chain as a balanced tree (log n deep), as for expressions.
    std::vector<Ltl> parts;
    parts.push_back(ltlChain(depth, level + 1));
    const char* op = level == 0 ? "||" : "&&";
    while (accept(op)) parts.push_back(ltlChain(depth, level + 1));
    return ltlBalanced(level == 0 ? Ltl::Kind::Or : Ltl::Kind::And, parts, 0, parts.size());
  }
  static Ltl ltlBalanced(Ltl::Kind kind, std::vector<Ltl>& parts, std::size_t first, std::size_t last) {
    if (last - first == 1) return std::move(parts[first]);
    const std::size_t middle = first + (last - first) / 2;
    Ltl left = ltlBalanced(kind, parts, first, middle);
    return Ltl::binary(kind, std::move(left), ltlBalanced(kind, parts, middle, last));
  }
  Ltl ltlPrefix(int depth) {
    if (depth > 200) fail(peek(), "formula nested too deeply");
    if (accept("!")) return Ltl::unary(Ltl::Kind::Not, ltlPrefix(depth + 1));
    for (auto kind : {Ltl::Kind::Next, Ltl::Kind::Always, Ltl::Kind::Eventually}) {
      if (isWord(ltlKeyword(kind))) {
        advance();
        return Ltl::unary(kind, ltlPrefix(depth + 1));
      }
    }
    if (accept("(")) {
      Ltl f = ltl(depth + 1);
      expect(")", "to close the parenthesis");
      return f;
    }
    if (!accept("{")) fail(peek(), "expected a state formula in braces '{...}', a temporal operator or '(', found " + found());
    Expr e = wholeExpr();
    expect("}", "to close the state formula");
    return Ltl::of(std::move(e));
  }

  // ---- expressions, loosest first: ?:  =>  ||  &&  == !=  < <= > >=  + -  * / %  unary
  // Nesting (parentheses, prefix operators, right-nested ?: and =>) is limited (nesting.hpp): past
  // it an error, never a stack overflow. Long flat chains (a && b && ...) are read in a loop, into
  // balanced trees where the operator associates; wholeExpr() limits the depth of the whole tree.
  [[nodiscard]] NestingGuard deeper() {
    return NestingGuard(exprDepth_, [this] { fail(peek(), "expression nested too deeply (limit " + std::to_string(kMaxNesting) + ")"); });
  }

  // An expression as a guard, update, invariant or atom holds it. Its tree is no deeper than
  // kMaxTreeDepth: long chains of &&, ||, + and * are read into balanced trees (depth log n), but a
  // chain of an operator that does not associate (-, /, %, comparisons) nests one level per
  // operator, and every engine walks trees recursively. Measured in one pass over the tree.
  Expr wholeExpr() {
    const Token start = peek();
    Expr e = expr();
    std::size_t deepest = 0;
    std::vector<std::pair<const Expr*, std::size_t>> todo{{&e, 1}};
    while (!todo.empty()) {
      const auto [node, depth] = todo.back();
      todo.pop_back();
      deepest = std::max(deepest, depth);
      for (const Expr& a : node->args) todo.emplace_back(&a, depth + 1);
    }
    if (deepest > kMaxTreeDepth) treeTooDeep(start, std::to_string(deepest));
    return e;
  }
  [[noreturn]] void treeTooDeep(const Token& start, const std::string& levels) {
    fail(start, "expression nested too deeply (" + levels + " levels, limit " + std::to_string(kMaxTreeDepth) +
                    "): a chain of '-', '/', '%' or comparisons nests one level per operator");
  }

  Expr expr() {
    Expr c = implication();
    if (!accept("?")) return c;
    const NestingGuard level = deeper();
    Expr t = expr();
    expect(":", "in 'c ? a : b'");
    Expr e = expr();
    return Expr::ite(std::move(c), std::move(t), std::move(e));
  }
  Expr implication() {
    Expr l = binary(0);
    if (!accept("=>")) return l;
    const NestingGuard level = deeper();
    return Expr::binary(Op::Implies, std::move(l), implication());
  }
  Expr binary(int level) {
    static const std::vector<std::vector<std::pair<const char*, Op>>> levels{
        {{"||", Op::Or}},
        {{"&&", Op::And}},
        {{"==", Op::Eq}, {"!=", Op::Ne}},
        {{"<=", Op::Le}, {">=", Op::Ge}, {"<", Op::Lt}, {">", Op::Gt}},
        {{"+", Op::Add}, {"-", Op::Sub}},
        {{"*", Op::Mul}, {"/", Op::Div}, {"%", Op::Mod}}};
    if (level == static_cast<int>(levels.size())) return unary();
    // The operands and operators of the chain at this level, then the tree: left to right, a run
    // of one associative operator (a && b && c, a + b + c) as a balanced tree, so that a chain of
    // n terms costs n to read and is log n deep (ir::associated).
    const Token start = peek();
    std::vector<Expr> operands;
    std::vector<Op> ops;
    operands.push_back(binary(level + 1));
    while (true) {
      bool matched = false;
      for (const auto& [spelling, op] : levels[static_cast<std::size_t>(level)]) {
        if (!isPunct(spelling)) continue;
        // `+ 0.25 :` starts the next outcome of a probabilistic rule: no expression has a decimal.
        if (op == Op::Add && (peek(1).kind == T::Number || startsFraction(1))) break;
        advance();
        ops.push_back(op);
        operands.push_back(binary(level + 1));
        matched = true;
        break;
      }
      if (!matched) break;
    }
    // Each run nests the tree one level deeper. Refused before the tree is built: a tree of a
    // million levels (a 4 MB chain of '- 1') could not even be destroyed, its destructor being
    // recursive (a stack overflow, found under the sanitizers).
    std::size_t runs = 0;
    for (std::size_t i = 0; i < ops.size(); ++i) runs += i == 0 || !isAssociative(ops[i]) || ops[i] != ops[i - 1] ? 1 : 0;
    if (runs > kMaxTreeDepth) treeTooDeep(start, "at least " + std::to_string(runs + 1));
    Expr left = std::move(operands[0]);
    for (std::size_t i = 0; i < ops.size();) {
      std::size_t end = i + 1;
      while (isAssociative(ops[i]) && end < ops.size() && ops[end] == ops[i]) ++end;
      std::vector<Expr> run;
      run.reserve(end - i + 1);
      run.push_back(std::move(left));
      for (std::size_t k = i; k < end; ++k) run.push_back(std::move(operands[k + 1]));
      left = run.size() == 2 ? Expr::binary(ops[i], std::move(run[0]), std::move(run[1])) : associated(ops[i], std::move(run));
      i = end;
    }
    return left;
  }
  Expr unary() {
    const NestingGuard level = deeper();  // one level per prefix operator or parenthesis
    if (accept("!")) return Expr::unary(Op::Not, unary());
    if (accept("-")) {
      // The writer writes the constant INT32_MIN as -2147483648, which Neg(2147483648) cannot be.
      if (peek().kind == T::Int && peek().text == "2147483648") return Expr::constant(integer(advance(), true));
      return Expr::unary(Op::Neg, unary());
    }
    if (accept("(")) {
      Expr e = expr();
      expect(")", "to close the parenthesis");
      return e;
    }
    const Token& t = peek();
    if (t.kind == T::Int) return Expr::constant(integer(advance()));
    if (t.kind != T::Name) fail(t, "expected an expression, found " + found());
    advance();
    if (t.text == "true" || t.text == "false") return Expr::constant(t.text == "true" ? 1 : 0);
    if ((t.text == "min" || t.text == "max") && accept("(")) {
      Expr a = expr();
      expect(",", "between the arguments");
      Expr b = expr();
      expect(")", "to close the call");
      return Expr::binary(t.text == "min" ? Op::Min : Op::Max, std::move(a), std::move(b));
    }
    auto it = varIndex_.find(std::string(t.text));
    if (it == varIndex_.end()) fail(t, "undeclared variable '" + std::string(t.text) + "'");
    return Expr::var(it->second);
  }

  std::string_view text_;
  FileId file_;
  DiagnosticEngine& diags_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::size_t exprDepth_ = 0;  // deeper()
  static constexpr std::size_t kMaxTreeDepth = 1024;  // wholeExpr()
  Model model_;
  std::unordered_map<std::string, VarId> varIndex_;
  std::unordered_map<std::string, std::int32_t> robotIndex_;
  std::unordered_set<std::string> ruleNames_, invariantNames_;
};

}  // namespace

std::optional<Model> parseText(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  return Reader(sources, file, diags).run();
}

bool looksLikeIr(const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    at = text.find_first_not_of(" \t\r\n", at);
    if (at == std::string::npos) return false;
    if (text[at] != '#') return text.compare(at, 7, "semo-ir") == 0;
    at = text.find('\n', at);  // a comment line
  }
  return false;
}

}  // namespace semo::ir
