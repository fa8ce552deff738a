// Writes the IR in its text form (specs/ir.md).
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

const char* symbol(Op op) {
  switch (op) {
    case Op::Add: return "+";
    case Op::Sub: return "-";
    case Op::Mul: return "*";
    case Op::Div: return "/";
    case Op::Mod: return "%";
    case Op::Eq: return "==";
    case Op::Ne: return "!=";
    case Op::Lt: return "<";
    case Op::Le: return "<=";
    case Op::Gt: return ">";
    case Op::Ge: return ">=";
    case Op::And: return "&&";
    case Op::Or: return "||";
    case Op::Implies: return "=>";
    default: return "?";
  }
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
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
    default:  // left-associative binary operators
      write(out, m, e.args[0], p);
      out << ' ' << symbol(e.op) << ' ';
      write(out, m, e.args[1], p + 1);
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
  for (const Variable& v : m.variables) {
    out << "var " << v.name << " : ";
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
    out << ";\n";
  }
  out << '\n';
  for (const Rule& r : m.rules) {
    out << "rule " << r.name;
    if (r.robot != kNoRobot) out << " @robot(" << m.robots.at(static_cast<std::size_t>(r.robot)) << ')';
    if (r.kind != RuleKind::Step) out << " @kind(" << kindName(r.kind) << ')';
    if (!r.origin.empty()) out << " @origin(" << quoted(r.origin) << ')';
    if (!r.label.empty()) out << " @label(" << quoted(r.label) << ')';
    if (r.weaklyFair) out << " @fair";
    out << " :\n  " << toText(m, r.guard) << " ->";
    for (std::size_t b = 0; b < r.branches.size(); ++b) {
      const Branch& branch = r.branches[b];
      if (b > 0) out << "\n  +";
      if (r.branches.size() > 1) {
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
  for (const Invariant& inv : m.invariants) {
    out << "invariant " << inv.name;
    if (!inv.origin.empty()) out << " @origin(" << quoted(inv.origin) << ')';
    out << " : " << toText(m, inv.holds) << ";\n";
  }
  if (m.validEnd) out << "valid_end : " << toText(m, *m.validEnd) << ";\n";
  return out.str();
}

}  // namespace semo::ir
