#include "semo/checker/prism_export.hpp"

#include <charconv>
#include <set>
#include <unordered_set>

#include <fmt/format.h>

namespace semo::checker {
namespace {

using ir::Expr;
using ir::Op;

// PRISM's keywords (its manual's list), which cannot be identifiers.
const std::unordered_set<std::string> kKeywords{
    "A",       "bool",    "clock",   "const",  "ctmc",      "C",       "double", "dtmc",    "E",     "endinit", "endinvariant",
    "endmodule", "endobservables", "endrewards", "endsystem", "false", "formula", "filter", "func", "F", "global", "G",
    "init",    "invariant", "I",     "int",    "label",     "max",     "mdp",    "min",     "module", "X",     "nondeterministic",
    "observable", "observables", "of", "Pmax", "Pmin",     "P",       "pomdp",  "popta",   "probabilistic", "prob", "pta",
    "rate",    "rewards", "Rmax",    "Rmin",   "R",         "S",       "stochastic", "system", "true", "U",    "W"};

class Writer {
 public:
  explicit Writer(const ir::Model& m) : m_(m) {
    std::set<std::string> taken;
    for (const ir::Variable& v : m.variables) names_.push_back(unique(identifier(v.name), taken));
    for (const ir::Property& p : m.properties) labels_.push_back(unique(identifier(p.name), taken));
    for (const ir::Invariant& i : m.invariants) invariantLabels_.push_back(unique(identifier(i.name), taken));
  }

  std::string variable(ir::VarId v) const { return names_.at(v); }
  const std::vector<std::string>& labels() const { return labels_; }
  const std::vector<std::string>& invariantLabels() const { return invariantLabels_; }

  // PRISM is typed: a bool where a bool is wanted, an int where an int is.
  std::string boolean(const Expr& e) const {
    if (e.op == Op::Const) return e.value != 0 ? "true" : "false";
    return isBool(e) ? text(e) : "(" + text(e) + " != 0)";
  }
  std::string integer(const Expr& e) const { return isBool(e) ? "(" + text(e) + " ? 1 : 0)" : text(e); }
  std::string as(const Expr& e, bool wantBool) const { return wantBool ? boolean(e) : integer(e); }
  bool isVarBool(ir::VarId v) const { return m_.variables.at(v).isBool; }

 private:
  static std::string identifier(const std::string& name) {
    std::string out;
    for (char c : name) {
      const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
      if (ok) out += c;
      else if (c != ']' && (out.empty() || out.back() != '_')) out += '_';
    }
    if (out.empty() || (out[0] >= '0' && out[0] <= '9') || kKeywords.count(out) != 0) out = "v_" + out;
    return out;
  }
  static std::string unique(std::string name, std::set<std::string>& taken) {
    std::string candidate = name;
    for (int n = 2; taken.count(candidate) != 0; ++n) candidate = name + "_" + std::to_string(n);
    taken.insert(candidate);
    return candidate;
  }

  bool isBool(const Expr& e) const {
    switch (e.op) {
      case Op::Var: return m_.variables.at(static_cast<ir::VarId>(e.value)).isBool;
      case Op::Not: case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge:
      case Op::And: case Op::Or: case Op::Implies: return true;
      case Op::Ite: {
        // `c ? p != q : false`: a boolean when one branch is and the other is the constant 0 or 1.
        auto flag = [](const Expr& x) { return x.op == Op::Const && (x.value == 0 || x.value == 1); };
        const Expr &t = e.args[1], &f = e.args[2];
        return (isBool(t) && (isBool(f) || flag(f))) || (flag(t) && isBool(f));
      }
      default: return false;
    }
  }

  std::string text(const Expr& e) const {
    auto a = [&](std::size_t i) { return integer(e.args[i]); };
    auto b = [&](std::size_t i) { return boolean(e.args[i]); };
    switch (e.op) {
      case Op::Const: return std::to_string(e.value);
      case Op::Var: return names_.at(static_cast<ir::VarId>(e.value));
      case Op::Not: return "!" + b(0);
      case Op::Neg: return "(-" + a(0) + ")";
      case Op::Add: return "(" + a(0) + " + " + a(1) + ")";
      case Op::Sub: return "(" + a(0) + " - " + a(1) + ")";
      case Op::Mul: return "(" + a(0) + " * " + a(1) + ")";
      // The IR's integer division truncates toward zero and gives 0 for x / 0; PRISM's `/` is real.
      case Op::Div: {
        const std::string x = a(0), y = a(1);
        return fmt::format("({1} = 0 ? 0 : ({0} / {1} >= 0 ? floor({0} / {1}) : ceil({0} / {1})))", x, y);
      }
      case Op::Mod: {
        const std::string x = a(0), y = a(1);
        return fmt::format("({1} = 0 ? 0 : {0} - {1} * ({0} / {1} >= 0 ? floor({0} / {1}) : ceil({0} / {1})))", x, y);
      }
      case Op::Min: return "min(" + a(0) + ", " + a(1) + ")";
      case Op::Max: return "max(" + a(0) + ", " + a(1) + ")";
      case Op::Eq: case Op::Ne: {
        // Two booleans compare as booleans, anything else as integers.
        const bool bools = isBool(e.args[0]) && isBool(e.args[1]);
        const std::string x = bools ? b(0) : a(0), y = bools ? b(1) : a(1);
        return "(" + x + (e.op == Op::Eq ? " = " : " != ") + y + ")";
      }
      case Op::Lt: return "(" + a(0) + " < " + a(1) + ")";
      case Op::Le: return "(" + a(0) + " <= " + a(1) + ")";
      case Op::Gt: return "(" + a(0) + " > " + a(1) + ")";
      case Op::Ge: return "(" + a(0) + " >= " + a(1) + ")";
      case Op::And: return "(" + b(0) + " & " + b(1) + ")";
      case Op::Or: return "(" + b(0) + " | " + b(1) + ")";
      case Op::Implies: return "(" + b(0) + " => " + b(1) + ")";
      case Op::Ite: {
        const bool bools = isBool(e);
        return "(" + b(0) + " ? " + as(e.args[1], bools) + " : " + as(e.args[2], bools) + ")";
      }
    }
    return "0";
  }

  const ir::Model& m_;
  std::vector<std::string> names_, labels_, invariantLabels_;
};

std::string probability(const ir::Branch& b) {
  if (b.denominator != 0) return fmt::format("{}/{}", b.numerator, b.denominator);
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, b.probability).ptr;  // shortest exact form
  return std::string(buffer, end);
}

// `eventually {p}`: the properties `analyze` measures.
const ir::Expr* eventuallyTarget(const ir::Property& p) {
  if (p.formula.kind == ir::Ltl::Kind::Eventually && p.formula.args.size() == 1 && p.formula.args[0].kind == ir::Ltl::Kind::Atom) {
    return &p.formula.args[0].atom;
  }
  return nullptr;
}

}  // namespace

PrismModel toPrism(const ir::Model& m, bool deterministic) {
  const Writer w(m);
  PrismModel out;
  out.deterministic = deterministic;
  std::string t = "// Written by semo-verify export --prism from the IR (specs/ir.md, specs/quantitative.md): one module holding\n"
                  "// every variable, one command per rule. Names are made valid for PRISM; the IR's are in the comments.\n";
  t += deterministic ? "dtmc\n\n" : "mdp\n\n";
  t += "module semo\n";
  for (ir::VarId v = 0; v < m.variables.size(); ++v) {
    const ir::Variable& var = m.variables[v];
    const std::string comment = w.variable(v) == var.name ? "" : "  // " + var.name;
    if (var.isBool) t += fmt::format("  {} : bool init {};{}\n", w.variable(v), var.init != 0 ? "true" : "false", comment);
    else t += fmt::format("  {} : [{}..{}] init {};{}\n", w.variable(v), var.min, var.max, var.init, comment);
  }
  t += "\n";
  for (const ir::Rule& r : m.rules) {
    t += "  // " + r.name + "\n  [] " + w.boolean(r.guard) + " ->";
    for (std::size_t k = 0; k < r.branches.size(); ++k) {
      const ir::Branch& b = r.branches[k];
      t += k == 0 ? " " : "\n     + ";
      if (r.branches.size() > 1) t += probability(b) + " : ";
      if (b.assignments.empty()) t += "true";
      for (std::size_t i = 0; i < b.assignments.size(); ++i) {
        const ir::Assignment& a = b.assignments[i];
        t += (i == 0 ? "(" : " & (") + w.variable(a.var) + "' = " + w.as(a.value, w.isVarBool(a.var)) + ")";
      }
    }
    t += ";\n";
  }
  t += "endmodule\n\n";
  for (std::size_t p = 0; p < m.properties.size(); ++p) {
    if (const ir::Expr* target = eventuallyTarget(m.properties[p])) t += fmt::format("label \"{}\" = {};\n", w.labels()[p], w.boolean(*target));
  }
  for (std::size_t i = 0; i < m.invariants.size(); ++i) {
    t += fmt::format("label \"{}\" = {};\n", w.invariantLabels()[i], w.boolean(m.invariants[i].holds));
  }
  t += "\n// Every step counts one: expected steps.\nrewards \"steps\"\n  true : 1;\nendrewards\n";
  out.model = std::move(t);

  std::string props = "// The questions semo-verify analyze answers, for PRISM or Storm.\n";
  const std::vector<std::string> optima = deterministic ? std::vector<std::string>{""} : std::vector<std::string>{"min", "max"};
  for (std::size_t p = 0; p < m.properties.size(); ++p) {
    if (eventuallyTarget(m.properties[p]) == nullptr) continue;
    props += "// " + m.properties[p].name + "\n";
    for (const std::string& o : optima) {
      props += fmt::format("P{}=? [ F \"{}\" ];\n", o, w.labels()[p]);
      props += fmt::format("R{{\"steps\"}}{}=? [ F \"{}\" ];\n", o, w.labels()[p]);
    }
  }
  for (std::size_t i = 0; i < m.invariants.size(); ++i) {
    props += "// invariant " + m.invariants[i].name + ": holds where this is 0\n";
    props += fmt::format("P{}=? [ F !\"{}\" ];\n", deterministic ? "" : "max", w.invariantLabels()[i]);
  }
  out.properties = std::move(props);
  return out;
}

}  // namespace semo::checker
