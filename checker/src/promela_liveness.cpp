// The LTL properties of the Promela export (PromelaOptions::liveness; specs/ir.md, section 7):
// one `ltl` claim per property under semo's fairness, with the bookkeeping the model keeps so that
// each claim's premise stays three conjuncts whatever the number of fairness groups.
#include "promela_liveness.hpp"

#include <algorithm>

#include "promela_text.hpp"
#include "semo/checker/compiled_model.hpp"

namespace semo::checker::detail {

PromelaLiveness::PromelaLiveness(const ir::Model& model, PromelaText text) : m_(model), text_(std::move(text)) {}

void PromelaLiveness::declare(std::ostream& out) {
  lastVar_ = text_.fresh("semo_last");
  for (const ir::Property& p : m_.properties) claimNames_.push_back(text_.fresh("p_" + p.name));
  const std::size_t stutter = m_.rules.size() + 1;
  out << "/* ---- the rule of the last step (its index + 1; " << stutter << ": time passing; 0: none yet), for the\n"
      << "   claims' fairness */\n"
      << (stutter <= 255 ? "byte " : "short ") << lastVar_ << " = 0;\n";
  atoms(out);
  bookkeeping(out);
}

// Each atom of the properties as a flag the model keeps (set by every step, initialised to its
// value in the initial state), so that a claim names it: SPIN's translator rejects a formula past
// a few thousand characters, which a knowledge_convergence over ten robots exceeds.
void PromelaLiveness::atoms(std::ostream& out) {
  std::vector<const ir::Expr*> found;
  auto collect = [&](auto&& self, const ir::Ltl& f) -> void {
    if (f.kind == ir::Ltl::Kind::Atom) found.push_back(&f.atom);
    for (const ir::Ltl& a : f.args) self(self, a);
  };
  for (const ir::Property& p : m_.properties) collect(collect, p.formula);
  std::vector<Value> initial;
  for (const ir::Variable& v : m_.variables) initial.push_back(v.init);
  std::string updates;
  for (const ir::Expr* e : found) {
    const std::string text = text_.expr(*e);
    if (atomNames_.count(text) != 0) continue;
    const std::string name = text_.fresh("semo_atom_" + std::to_string(atomNames_.size()));
    atomNames_.emplace(text, name);
    const bool holds = Program(*e).eval(initial.data()) != 0;
    out << "bool " << name << " = " << (holds ? 1 : 0) << ";  /* an atom of the properties, as of the last step */\n";
    updates += cat(updates.empty() ? "" : ";\n", "  ", name, " = (", text, ")");
  }
  if (updates.empty()) return;
  atomsInline_ = text_.fresh("semo_atoms");
  out << "inline " << atomsInline_ << "() {\n" << updates << "\n}\n";
}

// A formula in SPIN's LTL syntax, atoms as Promela expressions.
std::string PromelaLiveness::ltl(const ir::Ltl& f) const {
  using K = ir::Ltl::Kind;
  auto unary = [&](const char* op) { return cat(op, " (", ltl(f.args[0]), ")"); };
  auto binary = [&](const char* op) { return cat("(", ltl(f.args[0]), ") ", op, " (", ltl(f.args[1]), ")"); };
  switch (f.kind) {
    case K::Atom: return atomNames_.at(text_.expr(f.atom));
    case K::Not: return unary("!");
    case K::And: return binary("&&");
    case K::Or: return binary("||");
    case K::Implies: return binary("->");
    case K::Next: return unary("X");
    case K::Always: return unary("[]");
    case K::Eventually: return unary("<>");
    case K::Until: return binary("U");
    case K::Release: return binary("V");
  }
  return "true";
}

// The last step was one of `rules`.
std::string PromelaLiveness::lastIn(const std::vector<std::uint32_t>& rules) const {
  std::string out;
  for (std::uint32_t r : rules) out += cat(out.empty() ? "" : " || ", lastVar_, " == ", std::to_string(r + 1));
  return out.empty() ? "false" : cat("(", out, ")");
}

// One of `rules` is enabled.
ir::Expr PromelaLiveness::enabledExpr(const std::vector<std::uint32_t>& rules) const {
  std::vector<ir::Expr> guards;
  for (std::uint32_t r : rules) guards.push_back(m_.rules[r].guard);
  return ir::disjunction(std::move(guards));
}

std::string PromelaLiveness::enabledAny(const std::vector<std::uint32_t>& rules) const {
  return cat("(", text_.expr(enabledExpr(rules)), ")");
}

void PromelaLiveness::claims(std::ostream& out) const {
  out << "\n/* ---- LTL properties under semo's fairness (specs/ir.md): pan -a -N <claim> */\n";
  for (const ir::Property& p : m_.properties) {
    std::vector<std::string> assumed;
    if (!fairFlag_.empty()) assumed.push_back(cat("[]<> ", fairFlag_));
    if (!quietFlag_.empty()) assumed.push_back(cat("<>[] !", quietFlag_));
    if (p.settled && !switchFlag_.empty()) assumed.push_back(cat("<>[] !", switchFlag_));
    std::string assumption;
    for (const std::string& a : assumed) assumption += cat(assumption.empty() ? "" : " && ", a);
    out << "ltl " << claimNames_.at(static_cast<std::size_t>(&p - m_.properties.data())) << " {  /* " << commentText(p.name)
         << " */\n  ";
    if (assumed.empty()) {
      out << ltl(p.formula) << "\n}\n";
    } else {
      out << "(" << assumption << ")\n  -> (" << ltl(p.formula) << ")\n}\n";
    }
  }
}

// semo's fairness and settling as flags the model computes at each step, so that a claim's
// premise is at most `[]<> semo_fair && <>[] !semo_quiet && <>[] !semo_switched`: SPIN's
// translation of LTL to an automaton grows exponentially with the number of conjuncts written
// out per group (three strongly fair groups took minutes), the model's bookkeeping only linearly.
// - A weakly fair group is taken infinitely often or found disabled infinitely often,
//   `[]<> (!enabled || taken)`, which is `<>[] enabled -> []<> taken`.
// - A strongly fair group (`[]<> enabled -> []<> taken`) is either enabled only finitely often or
//   taken infinitely often; the model guesses which at the start (`semo_busy_k`, then constant):
//   busy, `[]<> taken`; not busy, from some point on never enabled (`semo_quiet` marks a step
//   after which it is).
// - The `[]<>` conditions are met one after another: the phase waits at condition k until it
//   holds after a step, then moves on; `semo_fair` marks the step that completes a round. All hold
//   infinitely often exactly when rounds complete infinitely often (the usual way to turn a
//   generalized Büchi condition into a plain one).
// - A sensed condition is settled when from some point on it is decided one way only, that is,
//   when its answer changes finitely often: `semo_said_k` keeps its last answer and
//   `semo_switched` marks a step that changed one.
// The guess is a step before the loop that changes no variable of the model, harmless to the
// IR's formulas, which have no `X` and so cannot tell a repeated state.
void PromelaLiveness::bookkeeping(std::ostream& out) {
  const Fairness fairness = Fairness::of(m_);
  std::vector<std::string> phaseConditions, quietConditions;
  for (std::uint32_t g = 0; g < fairness.groups(); ++g) {
    const std::vector<std::uint32_t>& members = fairness.members[g];
    if (!fairness.strong[g]) {
      phaseConditions.push_back(cat(text_.negation(enabledExpr(members)), " || ", lastIn(members)));
      continue;
    }
    const std::string busy = text_.fresh("semo_busy_" + std::to_string(g));
    busyFlags_.push_back(busy);
    phaseConditions.push_back(cat("!", busy, " || ", lastIn(members)));
    quietConditions.push_back(cat("!", busy, " && ", enabledAny(members)));
  }
  const bool settledProperty =
      std::any_of(m_.properties.begin(), m_.properties.end(), [](const ir::Property& p) { return p.settled; });
  if (settledProperty) {
    sensing_ = Sensing::in(m_);
    for (std::size_t k = 0; k < sensing_.points; ++k) saidVars_.push_back(text_.fresh("semo_said_" + std::to_string(k)));
    if (!saidVars_.empty()) switchFlag_ = text_.fresh("semo_switched");
  }
  for (const std::string& b : busyFlags_) out << "bool " << b << ";  /* guessed: this strongly fair group is taken for ever */\n";
  for (const std::string& v : saidVars_) out << "byte " << v << " = 0;  /* a sensed condition's last answer: 1 false, 2 true */\n";
  if (!switchFlag_.empty()) out << "bool " << switchFlag_ << " = 0;  /* this step changed a sensed condition's answer */\n";
  if (!phaseConditions.empty()) {
    phaseVar_ = text_.fresh("semo_phase");
    fairFlag_ = text_.fresh("semo_fair");
    out << (phaseConditions.size() < 255 ? "byte " : "short ") << phaseVar_ << " = 0;  /* the fairness condition waited for */\n"
         << "bool " << fairFlag_ << " = 0;  /* this step completed a round over the " << phaseConditions.size()
         << " fairness conditions */\n";
  }
  if (!quietConditions.empty()) {
    quietFlag_ = text_.fresh("semo_quiet");
    out << "bool " << quietFlag_ << " = 0;  /* a group guessed not busy is enabled */\n";
  }
  if (phaseConditions.empty()) {
    out << "\n";
    return;
  }
  bookkeeping_ = text_.fresh("semo_fairness");
  out << "inline " << bookkeeping_ << "() {\n  if\n";
  for (std::size_t k = 0; k < phaseConditions.size(); ++k) {
    out << "  :: " << phaseVar_ << " == " << k << " && (" << phaseConditions[k] << ") -> " << phaseVar_ << " = " << (k + 1) << "\n";
  }
  out << "  :: else -> skip\n  fi;\n  if\n"
       << "  :: " << phaseVar_ << " == " << phaseConditions.size() << " -> " << phaseVar_ << " = 0; " << fairFlag_ << " = 1\n"
       << "  :: else -> " << fairFlag_ << " = 0\n  fi" << (quietFlag_.empty() ? "" : ";") << "\n";
  if (!quietFlag_.empty()) {
    std::string any;
    for (const std::string& q : quietConditions) any += cat(any.empty() ? "" : " || ", "(", q, ")");
    out << "  " << quietFlag_ << " = (" << any << ")\n";
  }
  out << "}\n\n";
}

// What a step adds to its rule's assignments: the sensed answers it gives, the rule itself, the
// fairness bookkeeping.
std::vector<std::string> PromelaLiveness::step(std::uint32_t rule) const {
  std::vector<std::string> body;
  if (!switchFlag_.empty()) {
    std::string changed;
    std::vector<std::string> said;
    if (rule < sensing_.of.size()) {
      for (const Sensing::Decision& d : sensing_.of[rule]) {
        const std::string& v = saidVars_[d.point];
        const char* answer = d.holds ? "2" : "1";
        changed += cat(changed.empty() ? "" : " || ", "(", v, " != 0 && ", v, " != ", answer, ")");
        said.push_back(cat(v, " = ", answer));
      }
    }
    body.push_back(cat(switchFlag_, " = ", changed.empty() ? "0" : cat("(", changed, ")")));
    body.insert(body.end(), said.begin(), said.end());
  }
  body.push_back(cat(lastVar_, " = ", std::to_string(rule + 1)));
  if (!bookkeeping_.empty()) body.push_back(bookkeeping_ + "()");
  if (!atomsInline_.empty()) body.push_back(atomsInline_ + "()");
  return body;
}

// The strongly fair groups' guess, before the loop.
void PromelaLiveness::guess(std::ostream& out) const {
  if (busyFlags_.empty()) return;
  out << "  /* guess which strongly fair groups are taken for ever (the others must end up disabled) */\n";
  for (const std::string& b : busyFlags_) out << "  if\n  :: " << b << " = 1\n  :: " << b << " = 0\n  fi;\n";
}

}  // namespace semo::checker::detail
