// Writes the IR in its text form (specs/ir.md).
#include <cctype>
#include <charconv>
#include <sstream>

#include "semo/semantics/ir_text.hpp"

namespace semo::ir {

namespace {

int precedence(Op op) {
  switch (op) {
    case Op::Ite: return 1;
    case Op::Implies: return 2;
    case Op::Or: return 3;
    case Op::And: return 4;
    case Op::Eq: case Op::Ne: return 5;
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: return 6;
    case Op::Add: case Op::Sub: return 7;
    case Op::Mul: case Op::Div: case Op::Mod: return 8;
    case Op::Not: case Op::Neg: return 9;
    default: return 10;
  }
}


std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '\n') {  // a string stays on its line
      out += "\\n";
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// Whether the reader takes `name` as one name token: [A-Za-z_][A-Za-z0-9_.]* without "..", and
// with an index suffix [N] if `indexed` (in a variable declaration, a suffix declares an array).
bool isPlainName(const std::string& name, bool indexed) {
  std::size_t end = name.size();
  if (indexed && end > 2 && name.back() == ']') {
    std::size_t open = name.rfind('[');
    if (open != std::string::npos && open + 2 < end &&
        name.find_first_not_of("0123456789", open + 1) == end - 1) {
      end = open;
    }
  }
  if (end == 0 || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  for (std::size_t i = 0; i < end; ++i) {
    char c = name[i];
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.')) return false;
    if (c == '.' && i + 1 < end && name[i + 1] == '.') return false;
  }
  return name != "true" && name != "false" && name != "skip" && name != "bool";
}

// How many variables from `first` on are the elements base[0], base[1], ... of one array as the
// reader declares it (same range, initial value, robot and value names); 0 if `first` is not base[0].
std::size_t arrayRun(const std::vector<Variable>& vars, std::size_t first) {
  const Variable& v = vars[first];
  if (v.name.size() < 4 || v.name.compare(v.name.size() - 3, 3, "[0]") != 0) return 0;
  std::string base = v.name.substr(0, v.name.size() - 3);
  if (!isPlainName(base, false)) return 0;
  std::size_t n = 1;
  while (first + n < vars.size()) {
    const Variable& e = vars[first + n];
    if (e.name != base + "[" + std::to_string(n) + "]" || e.min != v.min || e.max != v.max || e.init != v.init ||
        e.isBool != v.isBool || e.robot != v.robot || e.valueNames != v.valueNames || e.facts != v.facts) {
      break;
    }
    ++n;
  }
  // A lone base[0] followed by a base[1] that differs reads better quoted, like its neighbours.
  if (n == 1 && first + 1 < vars.size() && vars[first + 1].name == base + "[1]") return 0;
  return n;
}

void write(std::ostream& out, const Model& m, const Expr& e, int context) {
  int p = precedence(e.op);
  bool parens = p < context;
  if (parens) out << '(';
  switch (e.op) {
    case Op::Const: out << e.value; break;
    case Op::Var: out << m.variables.at(static_cast<VarId>(e.value)).name; break;
    case Op::Not: out << '!'; write(out, m, e.args[0], 9); break;
    case Op::Neg: out << '-'; write(out, m, e.args[0], 9); break;
    case Op::Min:
    case Op::Max:
      out << (e.op == Op::Min ? "min(" : "max(");
      write(out, m, e.args[0], 0);
      out << ", ";
      write(out, m, e.args[1], 0);
      out << ')';
      break;
    case Op::Ite:
      write(out, m, e.args[0], 2);
      out << " ? ";
      write(out, m, e.args[1], 2);
      out << " : ";
      write(out, m, e.args[2], 1);
      break;
    case Op::Implies:  // right-associative
      write(out, m, e.args[0], p + 1);
      out << " => ";
      write(out, m, e.args[1], p);
      break;
    default:  // left-associative binary operators; an associative one's chain flat, however bracketed
      write(out, m, e.args[0], p);
      out << ' ' << opSymbol(e.op) << ' ';
      write(out, m, e.args[1], isAssociative(e.op) && e.args[1].op == e.op ? p : p + 1);
      break;
  }
  if (parens) out << ')';
}

}  // namespace

std::string toText(const Model& m, const Expr& e) {
  std::ostringstream out;
  write(out, m, e, 0);
  return out.str();
}

namespace {

// Loosest first: until/release, =>, ||, &&, then the prefix operators and atoms.
int ltlPrecedence(Ltl::Kind k) {
  switch (k) {
    case Ltl::Kind::Until: case Ltl::Kind::Release: return 1;
    case Ltl::Kind::Implies: return 2;
    case Ltl::Kind::Or: return 3;
    case Ltl::Kind::And: return 4;
    default: return 5;
  }
}

void writeLtl(std::ostringstream& out, const Model& m, const Ltl& f, int context) {
  int mine = ltlPrecedence(f.kind);
  bool parens = mine < context;
  if (parens) out << '(';
  switch (f.kind) {
    case Ltl::Kind::Atom: out << '{' << toText(m, f.atom) << '}'; break;
    case Ltl::Kind::Not: out << '!'; writeLtl(out, m, f.args[0], 5); break;
    case Ltl::Kind::Next: case Ltl::Kind::Always: case Ltl::Kind::Eventually:
      out << ltlKeyword(f.kind) << ' ';
      writeLtl(out, m, f.args[0], 5);
      break;
    default:
      // Binary: chains of || and && need no parentheses, however bracketed (they associate; the
      // reader holds them balanced); => and until nest to the right.
      bool rightAssoc = f.kind == Ltl::Kind::Implies || f.kind == Ltl::Kind::Until || f.kind == Ltl::Kind::Release;
      bool chain = (f.kind == Ltl::Kind::And || f.kind == Ltl::Kind::Or) && f.args[1].kind == f.kind;
      writeLtl(out, m, f.args[0], rightAssoc ? mine + 1 : mine);
      out << ' ' << ltlKeyword(f.kind) << ' ';
      writeLtl(out, m, f.args[1], rightAssoc || chain ? mine : mine + 1);
  }
  if (parens) out << ')';
}

}  // namespace

std::string toText(const Model& m, const Ltl& f) {
  std::ostringstream out;
  writeLtl(out, m, f, 0);
  return out.str();
}

std::string toText(const Model& m) {
  std::ostringstream out;
  out << "semo-ir 1\n";
  if (!m.robots.empty()) {
    out << "robots";
    for (const std::string& r : m.robots) out << ' ' << r;
    out << ";\n";
  }
  for (const std::string& a : m.assumptions) out << "assume " << quoted(a) << ";\n";
  out << '\n';
  for (std::size_t i = 0; i < m.variables.size();) {
    const Variable& v = m.variables[i];
    std::size_t elements = arrayRun(m.variables, i);
    if (elements > 0) {  // base[0] .. base[n-1], all alike: written back as the array `var base[n]`
      out << "var " << v.name.substr(0, v.name.size() - 3) << '[' << elements << "] : ";
      i += elements;
    } else {
      out << "var " << (isPlainName(v.name, false) ? v.name : quoted(v.name)) << " : ";
      ++i;
    }
    if (v.isBool) {
      out << "bool = " << (v.init != 0 ? "true" : "false");
    } else {
      out << v.min << ".." << v.max << " = " << v.init;
    }
    if (v.robot != kNoRobot) out << " @robot(" << m.robots.at(static_cast<std::size_t>(v.robot)) << ')';
    if (!v.valueNames.empty()) {
      std::string names;
      for (const std::string& n : v.valueNames) names += (names.empty() ? "" : " ") + n;
      out << " @values(" << quoted(names) << ')';
    }
    if (!v.facts.empty()) {
      std::string names;
      for (const std::string& n : v.facts) names += (names.empty() ? "" : " ") + n;
      out << " @facts(" << quoted(names) << ')';
    }
    out << ";\n";
  }
  out << '\n';
  for (const Rule& r : m.rules) {
    out << "rule " << (isPlainName(r.name, true) ? r.name : quoted(r.name));
    if (r.robot != kNoRobot) out << " @robot(" << m.robots.at(static_cast<std::size_t>(r.robot)) << ')';
    if (r.kind != RuleKind::Step) out << " @kind(" << kindName(r.kind) << ')';
    if (!r.origin.empty()) out << " @origin(" << quoted(r.origin.text()) << ')';
    if (!r.origin.construct.empty()) out << " @construct(" << quoted(r.origin.construct) << ')';
    if (!r.label.empty()) out << " @label(" << quoted(r.label) << ')';
    if (r.stronglyFair) out << " @strongly_fair";
    else if (r.weaklyFair && r.fairGroup.empty()) out << " @fair";
    else if (r.weaklyFair) out << " @fair(" << (isPlainName(r.fairGroup, true) ? r.fairGroup : quoted(r.fairGroup)) << ')';
    if (!r.sensed.empty()) {
      std::string senses;
      for (const SensedOutcome& s : r.sensed) senses += (senses.empty() ? "" : " ") + s.point + (s.holds ? "=1" : "=0");
      out << " @senses(" << quoted(senses) << ')';
    }
    out << " :\n  " << toText(m, r.guard) << " ->";
    for (std::size_t b = 0; b < r.branches.size(); ++b) {
      const Branch& branch = r.branches[b];
      if (b > 0) out << "\n  +";
      if (r.branches.size() > 1 && branch.denominator != 0) {
        out << ' ' << branch.numerator << '/' << branch.denominator << " :";
      } else if (r.branches.size() > 1) {
        // The shortest exact form, always with a decimal point ("0.00001", "1.0", never "1e-05"):
        // the reader takes `+ <decimal>` as the start of the next outcome.
        char buffer[512];
        auto end = std::to_chars(buffer, buffer + sizeof buffer, branch.probability, std::chars_format::fixed).ptr;
        std::string_view p(buffer, static_cast<std::size_t>(end - buffer));
        out << ' ' << p << (p.find('.') == std::string_view::npos ? ".0" : "") << " :";
      }
      if (branch.assignments.empty()) out << " skip";
      for (std::size_t i = 0; i < branch.assignments.size(); ++i) {
        const Assignment& a = branch.assignments[i];
        out << (i == 0 ? " " : ", ") << m.variables.at(a.var).name << "' = " << toText(m, a.value);
      }
    }
    out << ";\n";
  }
  if (!m.invariants.empty()) out << '\n';
  // `keyword NAME [@origin(...)] : `, the start of an invariant or a property.
  auto header = [&](const char* keyword, const std::string& name, const std::string& origin, bool settled = false) {
    out << keyword << ' ' << (isPlainName(name, true) ? name : quoted(name));
    if (!origin.empty()) out << " @origin(" << quoted(origin) << ')';
    if (settled) out << " @settled";
    out << " : ";
  };
  for (const Invariant& inv : m.invariants) {
    header("invariant", inv.name, inv.origin);
    out << toText(m, inv.holds) << ";\n";
  }
  if (m.validEnd) out << "valid_end : " << toText(m, *m.validEnd) << ";\n";
  if (!m.properties.empty()) out << '\n';
  for (const Property& p : m.properties) {
    header("property", p.name, p.origin, p.settled);
    out << toText(m, p.formula) << ";\n";
  }
  return out.str();
}

}  // namespace semo::ir
