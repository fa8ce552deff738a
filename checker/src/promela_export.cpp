// The IR as Promela (SPIN 6), for cross-checking the explicit engine.
//
// The shape of the output, and why it gives SPIN exactly semo's state space:
//
//   * every IR variable is a global of the smallest Promela type that holds its range (bool, bit,
//     byte, short, int); nothing else is in the state vector: the temporaries and the property
//     flags are `hidden`, and the one process never leaves its loop head between steps;
//   * one `active proctype` whose body is one `do` loop, and the loop head is its first location,
//     so the initial state is (initial values, loop head), like semo's;
//   * one loop option per rule and per outcome of a probabilistic rule, `d_step { guard -> ... }`:
//     a d_step is a single transition, so no intermediate state is stored (SPIN ignores the
//     probabilities: every outcome is a nondeterministic choice, which is also how semo's explicit
//     search takes them);
//   * the invariants are checked by a loop option `d_step { !(all invariants) -> assert ... }`: it
//     is enabled exactly in the states that violate one, the initial state included, and its step
//     leads back to the same state. Asserting before the loop instead would add a stored state (the
//     process at its first location), and asserting after each update would miss the initial state;
//   * SPIN leaves a variable that is only ever assigned, never read, out of the state vector (its
//     dead-variable elimination, off only with `spin -o2`); a never-enabled option reads every such
//     variable, so that the plain `spin -a` keeps them, as semo does;
//   * deadlock: when the model has valid_end, an option `atomic { timeout -> assert valid_end }`
//     (timeout holds exactly when no rule's guard does). The loop is labelled `end` in every case, so
//     a state without successors is never an "invalid end state" of its own: without valid_end a
//     deadlock is not an error, as in semo. The invariant option is enabled in a violating state and
//     so hides `timeout` there; it checks valid_end itself in such a state, so that `pan -c0` (go on
//     after errors) reports the same set of violated properties as semo.
//
// Every assert names a hidden flag `prop_...` so that pan's "assertion violated prop_x" says which
// property failed; the declaration of each flag carries the property's IR name in a comment
// (tests/e2e/spin_crosscheck.cmake reads it).
//
// One difference is deliberate: an update that leaves a variable's declared range is a modelling
// error for semo (the search stops and says where), while pan stores the value the C way (a byte
// wraps modulo 256, a bit keeps the lowest bit, with at most a warning). Such models are not
// cross-checked.
#include "semo/checker/promela_export.hpp"

#include "promela_liveness.hpp"
#include "promela_text.hpp"

#include <algorithm>
#include <optional>
#include <charconv>
#include <cctype>
#include <climits>
#include <set>
#include <sstream>

namespace semo::checker {

namespace {

using detail::cat;
using detail::commentText;

using ir::Expr;
using ir::Op;

// Words a Promela identifier must not be: Promela keywords and predefined names, C keywords (pan.c
// refers to each global as `now.name`, and to hidden ones by their bare name), and the object-like
// macros of pan.c and pan.h.
const std::set<std::string>& reservedWords() {
  static const std::set<std::string> words{
      // Promela
      "active", "assert", "atomic", "bit", "bool", "break", "byte", "c_code", "c_decl", "c_expr", "c_state",
      "c_track", "chan", "d_proctype", "d_step", "do", "else", "empty", "enabled", "eval", "false", "fi", "for",
      "full", "get_priority", "goto", "hidden", "if", "in", "init", "inline", "int", "len", "local", "ltl", "mtype",
      "nempty", "never", "nfull", "notrace", "np_", "od", "of", "pc_value", "pid", "print", "printf", "printm",
      "priority", "proctype", "provided", "run", "select", "set_priority", "short", "show", "skip", "timeout",
      "trace", "true", "typedef", "unless", "unsigned", "xr", "xs", "STDIN", "always", "eventually", "until",
      "weak", "stronguntil", "weakuntil", "release", "implies", "equivalent", "next", "accept", "progress", "end",
      // C
      "auto", "case", "char", "const", "continue", "default", "double", "enum", "extern", "float", "long",
      "register", "restrict", "return", "signed", "sizeof", "static", "struct", "switch", "union", "void",
      "volatile", "while", "main", "now",
      // pan.c / pan.h macros and globals that a hidden variable could meet
      "uchar", "uint", "ulong", "ushort", "final", "max", "min", "mix", "rand", "rot", "cas", "depth", "errors",
      "trail", "trpt", "tau", "boq", "nstates", "nstored", "nlinks", "truncs", "Mask", "Maxbody", "vsize"};
  return words;
}

// Deterministic, injective naming: the first owner of a spelling keeps it, later ones get _2, _3...
class Names {
 public:
  std::string fresh(const std::string& wanted) {
    // "robot.mode" -> robot_mode, "fork[2]" -> fork_2, "formation[Search (Burger)]" -> formation_Search_Burger
    std::string base;
    bool replaced = false;  // the last character of `base` stands for a run of other characters
    for (char c : wanted) {
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
        base += c;
        replaced = false;
      } else if (!replaced) {
        base += '_';
        replaced = true;
      }
    }
    if (replaced && base.size() > 1) base.pop_back();
    if (base.empty() || std::isdigit(static_cast<unsigned char>(base.front()))) base = "v" + base;
    std::string name = base;
    for (int k = 2; used_.count(name) != 0 || reservedWords().count(name) != 0; ++k) name = base + "_" + std::to_string(k);
    used_.insert(name);
    return name;
  }

 private:
  std::set<std::string> used_;
};

const char* promelaType(const ir::Variable& v) {
  if (v.isBool) return "bool";
  if (v.min >= 0 && v.max <= 1) return "bit";
  if (v.min >= 0 && v.max <= 255) return "byte";
  if (v.min >= -32768 && v.max <= 32767) return "short";
  return "int";
}

std::string constant(std::int32_t v) {
  if (v == INT32_MIN) return "(-2147483647 - 1)";
  return std::to_string(v);
}

bool reads(const Expr& e, ir::VarId var) {
  if (e.op == Op::Var) return static_cast<ir::VarId>(e.value) == var;
  return std::any_of(e.args.begin(), e.args.end(), [&](const Expr& a) { return reads(a, var); });
}

class Writer {
 public:
  Writer(const ir::Model& m, const PromelaOptions& options) : m_(m), options_(options) {
    for (const ir::Variable& v : m.variables) varNames_.push_back(names_.fresh(v.name));
  }

  std::string run() {
    header();
    variables();
    scratch();
    process();
    if (liveness_) liveness_->claims(out_);
    return out_.str();
  }

 private:
  // ---- expressions (Promela's precedences are C's; `?:` is written `(c -> a : b)`)
  static int precedence(const Expr& e) {
    switch (e.op) {
      case Op::Const: return e.value < 0 ? 9 : 10;
      case Op::Not: case Op::Neg: return 9;
      case Op::Mul: return 8;
      case Op::Div: case Op::Mod: return divisorIsNonzeroConstant(e) ? 8 : 10;
      case Op::Add: case Op::Sub: return 7;
      case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: return 6;
      case Op::Eq: case Op::Ne: return 5;
      case Op::And: return 4;
      case Op::Or: return 3;
      default: return 10;  // variables, and what is written in its own parentheses
    }
  }
  static bool divisorIsNonzeroConstant(const Expr& e) {
    const Expr* d = &e.args[1];
    while (d->op == Op::Neg) d = &d->args[0];  // -2 is Neg(2) in the IR
    return d->op == Op::Const && d->value != 0;
  }

  std::string expr(const Expr& e, int context = 0) const {
    std::string s = bare(e);
    return precedence(e) < context ? cat("(", s, ")") : s;
  }

  std::string bare(const Expr& e) const {
    switch (e.op) {
      case Op::Const: return constant(e.value);
      case Op::Var: return varNames_.at(static_cast<std::size_t>(e.value));
      case Op::Not: return negation(e.args[0]);
      case Op::Neg: {
        std::string a = expr(e.args[0], 9);
        return a.front() == '-' ? cat("-(", a, ")") : cat("-", a);  // never "--": that is decrement
      }
      case Op::Implies: return cat("(", negation(e.args[0]), " || ", expr(e.args[1], 3), ")");
      case Op::Ite: return cat("(", expr(e.args[0]), " -> ", expr(e.args[1]), " : ", expr(e.args[2]), ")");
      case Op::Min:
      case Op::Max: {
        std::string a = expr(e.args[0], 7), b = expr(e.args[1], 7);
        return cat("(", a, e.op == Op::Min ? " <= " : " >= ", b, " -> ", expr(e.args[0]), " : ", expr(e.args[1]), ")");
      }
      case Op::Div:
      case Op::Mod:
        if (!divisorIsNonzeroConstant(e)) {  // x / 0 = x % 0 = 0 in the IR
          return cat("(", expr(e.args[1], 6), " == 0 -> 0 : ", expr(e.args[0], 8), " ", ir::opSymbol(e.op), " ",
                     expr(e.args[1], 9), ")");
        }
        [[fallthrough]];
      default: {  // left-associative binary operators
        int p = precedence(e);
        return cat(expr(e.args[0], p), " ", ir::opSymbol(e.op), " ", expr(e.args[1], p + 1));
      }
    }
  }

  // !e, never written "!!": that is a Promela send operator.
  std::string negation(const Expr& e) const {
    std::string a = expr(e, 9);
    return a.front() == '!' ? cat("!(", a, ")") : cat("!", a);
  }

  std::string guard(const Expr& e) const { return e.isTrue() ? "true" : expr(e); }

  // ---- sections
  void header() {
    out_ << "/* Promela model generated by semo (semo-verify export --promela) from the IR.\n"
         << " * " << m_.variables.size() << " variables, " << m_.rules.size() << " rules, " << m_.invariants.size()
         << " invariants, deadlock " << (m_.validEnd ? "checked against valid_end" : "not checked (no valid_end)")
         << ".\n *\n"
         << " * Cross-check with SPIN (partial-order reduction off, safety only):\n";
    if (options_.breadthFirst) {
      out_ << " *   spin -a model.pml && gcc -O2 -DNOREDUCE -DSAFETY -DBFS -o pan pan.c && ./pan -mK\n"
           << " * pan's \"states, stored\" is then exactly the number of states `semo-verify check --max-depth K`\n"
           << " * explores (pan judges the states at depth K only with -m(K+1)).\n";
    } else {
      out_ << " *   spin -a model.pml && gcc -O2 -DNOREDUCE -DSAFETY -o pan pan.c && ./pan -m1000000\n"
           << " * pan's \"states, stored\" is then exactly the number of states `semo-verify check` explores\n"
           << " * (-m must exceed the depth of pan's depth-first search, at most that number of states).\n";
    }
    out_ << " * Each rule, and each outcome of a probabilistic rule, is one d_step option of the loop below;\n"
         << " * probabilities are ignored (an outcome is a nondeterministic choice). An update out of a\n"
         << " * variable's declared range is a modelling error for semo; here it would wrap or truncate.\n";
    if (!m_.robots.empty()) {
      out_ << " *\n * robots:";
      for (const std::string& r : m_.robots) out_ << ' ' << commentText(r);
      out_ << "\n";
    }
    if (!m_.assumptions.empty()) {
      out_ << " *\n * assumptions:\n";
      for (const std::string& a : m_.assumptions) out_ << " *   - " << commentText(a) << "\n";
    }
    out_ << " */\n\n";
  }

  void variables() {
    if (m_.variables.empty()) return;
    out_ << "/* ---- state: IR variable, range, owner */\n";
    for (std::size_t i = 0; i < m_.variables.size(); ++i) {
      const ir::Variable& v = m_.variables[i];
      std::string init = v.isBool ? (v.init != 0 ? "true" : "false") : constant(v.init);
      std::string decl = std::string(promelaType(v)) + " " + varNames_[i] + " = " + init + ";";
      out_ << decl << std::string(decl.size() < 32 ? 32 - decl.size() : 1, ' ') << "/* " << commentText(v.name)
           << " : ";
      if (v.isBool) {
        out_ << "bool";
      } else {
        out_ << v.min << ".." << v.max;
      }
      if (v.robot != ir::kNoRobot) out_ << " @robot(" << commentText(m_.robots.at(static_cast<std::size_t>(v.robot))) << ")";
      if (!v.valueNames.empty()) {
        out_ << " values";
        for (std::size_t k = 0; k < v.valueNames.size(); ++k) out_ << ' ' << (v.min + static_cast<std::int64_t>(k)) << '=' << commentText(v.valueNames[k]);
      }
      out_ << " */\n";
    }
    out_ << "\n";
  }

  void scratch() {
    // Temporaries for simultaneous assignments: as many as the largest branch needs.
    std::size_t temporaries = 0;
    for (const ir::Rule& r : m_.rules) {
      for (const ir::Branch& b : r.branches) temporaries = std::max(temporaries, needsTemporary(b).size());
    }
    if (!options_.liveness) {
      for (const ir::Invariant& inv : m_.invariants) invariantFlags_.push_back(names_.fresh("prop_" + inv.name));
      if (m_.validEnd) validEndFlag_ = names_.fresh("prop_deadlock_freedom");
    } else {
      detail::PromelaText text{[this](const Expr& e) { return expr(e); }, [this](const Expr& e) { return negation(e); },
                               [this](const std::string& wanted) { return names_.fresh(wanted); }};
      liveness_.emplace(m_, std::move(text));
      liveness_->declare(out_);
    }
    for (std::size_t t = 0; t < temporaries; ++t) temporaries_.push_back(names_.fresh("semo_old" + std::to_string(t)));
    // Variables that no guard, update, invariant or valid_end reads: SPIN would leave them out of
    // the state vector as write-only (unless `spin -o2`), and then store fewer states than semo.
    std::vector<bool> read(m_.variables.size(), false);
    auto mark = [&](const Expr& e, auto& self) -> void {
      if (e.op == Op::Var) read.at(static_cast<std::size_t>(e.value)) = true;
      for (const Expr& a : e.args) self(a, self);
    };
    for (const ir::Rule& r : m_.rules) {
      mark(r.guard, mark);
      for (const ir::Branch& b : r.branches) {
        for (const ir::Assignment& a : b.assignments) mark(a.value, mark);
      }
    }
    for (const ir::Invariant& inv : m_.invariants) mark(inv.holds, mark);
    if (m_.validEnd) mark(*m_.validEnd, mark);
    for (std::size_t v = 0; v < read.size(); ++v) {
      if (!read[v]) unread_.push_back(v);
    }
    if (!unread_.empty()) readSink_ = names_.fresh("semo_read");
    processName_ = names_.fresh("semo_model");
    if (temporaries == 0 && invariantFlags_.empty() && validEndFlag_.empty() && unread_.empty()) return;
    // Breadth-first pan rejects `hidden`; there these are globals every step leaves 0.
    const char* hidden = options_.breadthFirst ? "" : "hidden ";
    out_ << (options_.breadthFirst ? "/* ---- scratch: 0 between steps (pan -DBFS allows no hidden variables) */\n"
                                   : "/* ---- hidden: not part of the state vector */\n");
    for (std::size_t i = 0; i < invariantFlags_.size(); ++i) {
      out_ << hidden << "byte " << invariantFlags_[i] << ";\t/* property '" << commentText(m_.invariants[i].name) << "'";
      if (!m_.invariants[i].origin.empty()) out_ << " at " << commentText(m_.invariants[i].origin);
      out_ << " */\n";
    }
    if (!validEndFlag_.empty()) {
      out_ << hidden << "byte " << validEndFlag_ << ";\t/* property 'deadlock_freedom': valid_end where no rule is enabled */\n";
    }
    for (const std::string& t : temporaries_) out_ << hidden << "int " << t << ";\t/* an old value, for a simultaneous assignment */\n";
    if (!readSink_.empty()) out_ << hidden << "int " << readSink_ << ";\t/* see the last option of the loop */\n";
    out_ << "\n";
  }

  // The assignments of a branch whose variable another right-hand side reads: their new values are
  // computed into temporaries first, and stored last.
  static std::vector<std::size_t> needsTemporary(const ir::Branch& b) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < b.assignments.size(); ++i) {
      for (std::size_t j = 0; j < b.assignments.size(); ++j) {
        if (j != i && reads(b.assignments[j].value, b.assignments[i].var)) {
          out.push_back(i);
          break;
        }
      }
    }
    return out;
  }

  std::vector<std::string> assignments(const ir::Branch& b) const {
    std::vector<std::size_t> late = needsTemporary(b);
    std::vector<std::string> out;
    for (std::size_t k = 0; k < late.size(); ++k) out.push_back(temporaries_[k] + " = " + expr(b.assignments[late[k]].value));
    for (std::size_t i = 0; i < b.assignments.size(); ++i) {
      if (std::find(late.begin(), late.end(), i) != late.end()) continue;
      const ir::Assignment& a = b.assignments[i];
      bool boolConstant = m_.variables[a.var].isBool && a.value.op == Op::Const && (a.value.value == 0 || a.value.value == 1);
      out.push_back(cat(varNames_[a.var], " = ", boolConstant ? (a.value.value != 0 ? "true" : "false") : expr(a.value)));
    }
    for (std::size_t k = 0; k < late.size(); ++k) out.push_back(varNames_[b.assignments[late[k]].var] + " = " + temporaries_[k]);
    if (options_.breadthFirst) {
      for (std::size_t k = 0; k < late.size(); ++k) out.push_back(temporaries_[k] + " = 0");
    }
    if (out.empty()) out.emplace_back("skip");
    return out;
  }

  // Whether `e` is always 0 or 1.
  bool isBoolean(const Expr& e) const {
    switch (e.op) {
      case Op::Const: return e.value == 0 || e.value == 1;
      case Op::Var: {
        const ir::Variable& v = m_.variables.at(static_cast<std::size_t>(e.value));
        return v.min >= 0 && v.max <= 1;
      }
      case Op::Not: case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge:
      case Op::And: case Op::Or: case Op::Implies:
        return true;
      case Op::Ite: return isBoolean(e.args[1]) && isBoolean(e.args[2]);
      default: return false;
    }
  }

  // `flag = e; assert(flag)`: the flags are bytes, so a condition that may be another non-zero
  // value (256 would be stored as 0) is written `e != 0`.
  std::string assertion(const std::string& flag, const Expr& e) const {
    std::string value = isBoolean(e) ? expr(e, 3) : expr(Expr::binary(Op::Ne, e, Expr::constant(0)));
    return cat(flag, " = ", value, "; assert(", flag, ")", options_.breadthFirst ? cat("; ", flag, " = 0") : "");
  }

  std::string assertValidEnd() const { return assertion(validEndFlag_, *m_.validEnd); }

  void option(const std::string& step, const std::string& guardText, const std::vector<std::string>& body) {
    std::string oneLine = "  :: " + step + " { " + guardText + " -> ";
    for (std::size_t i = 0; i < body.size(); ++i) oneLine += (i == 0 ? "" : "; ") + body[i];
    oneLine += " }";
    if (oneLine.size() <= 110 && oneLine.find('\n') == std::string::npos) {
      out_ << oneLine << "\n";
      return;
    }
    out_ << "  :: " << step << " { " << guardText << " ->\n";
    for (std::size_t i = 0; i < body.size(); ++i) out_ << "       " << body[i] << (i + 1 < body.size() ? ";\n" : "\n");
    out_ << "     }\n";
  }

  void process() {
    out_ << "active proctype " << processName_ << "() {\n";
    if (liveness_) liveness_->guess(out_);
    out_
         << "  /* `end`: a state without successors is not an error of its own"
         << (m_.validEnd ? " (the timeout option below checks valid_end)" : " (the IR has no valid_end)") << " */\n"
         << "end:\n  do\n";
    bool any = false;
    if (!m_.invariants.empty() && !options_.liveness) {
      any = true;
      std::vector<Expr> all;
      for (const ir::Invariant& inv : m_.invariants) all.push_back(inv.holds);
      std::vector<std::string> body;
      for (std::size_t i = 0; i < m_.invariants.size(); ++i) {
        const ir::Invariant& inv = m_.invariants[i];
        body.push_back(assertion(invariantFlags_[i], inv.holds));
      }
      if (m_.validEnd) {
        // Here `timeout` is false (this option is enabled), so the deadlock check is done here.
        std::vector<Expr> guards;
        for (const ir::Rule& r : m_.rules) guards.push_back(r.guard);
        body.push_back(cat("if\n         :: ", expr(Expr::unary(Op::Not, ir::disjunction(guards))), " -> ",
                           assertValidEnd(), "\n         :: else -> skip\n         fi"));
      }
      out_ << "  /* an invariant fails in this state (every state is checked, the initial one too) */\n";
      Expr holds = ir::conjunction(all);
      // As a guard only the truth value counts, so !!e is written e.
      std::string g = holds.op == Op::Not ? expr(holds.args[0]) : negation(holds);
      out_ << "  :: d_step { " << g << " ->\n";
      for (std::size_t i = 0; i < body.size(); ++i) out_ << "       " << body[i] << (i + 1 < body.size() ? ";\n" : "\n");
      out_ << "     }\n";
    }
    for (const ir::Rule& r : m_.rules) {
      any = true;
      for (std::size_t b = 0; b < r.branches.size(); ++b) {
        out_ << "  /* rule " << commentText(r.name);
        if (r.robot != ir::kNoRobot) out_ << " [" << commentText(m_.robots.at(static_cast<std::size_t>(r.robot))) << "]";
        if (r.kind != ir::RuleKind::Step) out_ << " {" << ir::kindName(r.kind) << "}";
        if (r.branches.size() > 1) {
          char buffer[32];
          auto end = std::to_chars(buffer, buffer + sizeof buffer, r.branches[b].probability).ptr;
          out_ << ", outcome " << (b + 1) << " of " << r.branches.size() << " (p = "
               << std::string_view(buffer, static_cast<std::size_t>(end - buffer)) << ")";
        }
        if (r.weaklyFair) out_ << ", fair";
        if (!r.origin.empty()) out_ << ", at " << commentText(r.origin.text());
        if (!r.label.empty()) out_ << ": " << commentText(r.label);
        out_ << " */\n";
        std::vector<std::string> body = assignments(r.branches[b]);
        if (options_.liveness) {
          if (body.size() == 1 && body[0] == "skip") body.clear();
          const std::vector<std::string> more = liveness_->step(static_cast<std::uint32_t>(&r - m_.rules.data()));
          body.insert(body.end(), more.begin(), more.end());
        }
        option("d_step", guard(r.guard), body);
      }
    }
    if (options_.liveness) {
      // semo's runs may stop where no fair rule is enabled (time passes); SPIN's must go on.
      std::vector<Expr> fair;
      for (const ir::Rule& r : m_.rules) {
        if (r.weaklyFair || r.stronglyFair) fair.push_back(r.guard);
      }
      any = true;
      out_ << "  /* time passes where no fair rule is enabled */\n";
      std::vector<std::string> body = liveness_->step(static_cast<std::uint32_t>(m_.rules.size()));
      option("d_step", negation(ir::disjunction(std::move(fair))), body);
    }
    if (m_.validEnd && !options_.liveness) {
      any = true;
      out_ << "  /* no rule is enabled: a deadlock unless valid_end holds */\n";
      out_ << "  :: atomic { timeout -> " << assertValidEnd() << " }\n";
    }
    if (!unread_.empty()) {
      any = true;
      std::vector<std::string> body;
      std::string names;
      for (std::size_t v : unread_) {
        body.push_back(cat(readSink_, " = ", varNames_[v]));
        names += cat(names.empty() ? "" : ", ", commentText(m_.variables[v].name));
      }
      out_ << "  /* never taken: it reads the variables nothing else reads (" << names << "), which SPIN\n"
           << "     would otherwise leave out of the state vector as write-only; semo's states include them */\n";
      option("d_step", "false", body);
    }
    if (!any) out_ << "  :: false  /* the model has no rule */\n";
    out_ << "  od\n}\n";
  }

  const ir::Model& m_;
  PromelaOptions options_;
  std::ostringstream out_;
  Names names_;
  std::vector<std::string> varNames_;
  std::vector<std::string> invariantFlags_;
  std::string validEndFlag_;
  std::vector<std::string> temporaries_;
  std::string processName_;
  std::optional<detail::PromelaLiveness> liveness_;  // PromelaOptions::liveness
  std::vector<std::size_t> unread_;  // variables nothing reads
  std::string readSink_;
};

}  // namespace

std::string toPromela(const ir::Model& model, const PromelaOptions& options) {
  return Writer(model, options).run();
}

}  // namespace semo::checker
