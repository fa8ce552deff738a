// Property-directed slicing (slicing.hpp): the over-approximation of guards and updates by what
// the kept variables alone can tell.
#include "semo/checker/slicing.hpp"

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/fairness.hpp"

#include <algorithm>
#include <optional>

namespace semo::checker {

namespace {

using ir::Expr;
using ir::Op;

// Alternatives beyond this many are given up for "any value": the slice stays small to build and
// to explore, and a refinement keeps the variables instead.
constexpr std::size_t kMaxAlternatives = 16;
constexpr std::size_t kMaxOutcomes = 4096;
constexpr std::int64_t kMaxRange = 64;

bool sameExpr(const Expr& a, const Expr& b) {
  if (a.op != b.op || a.value != b.value || a.args.size() != b.args.size()) return false;
  for (std::size_t k = 0; k < a.args.size(); ++k) {
    if (!sameExpr(a.args[k], b.args[k])) return false;
  }
  return true;
}

bool isComparison(Op op) { return op == Op::Eq || op == Op::Ne || op == Op::Lt || op == Op::Le || op == Op::Gt || op == Op::Ge; }
bool isConnective(Op op) { return op == Op::Not || op == Op::And || op == Op::Or || op == Op::Implies; }

// 0 or 1, as the IR's connectives and comparisons give.
bool zeroOrOne(const Expr& e) {
  return isComparison(e.op) || isConnective(e.op) || (e.op == Op::Const && (e.value == 0 || e.value == 1));
}

const Expr kTrue = Expr::constant(1);
const Expr kFalse = Expr::constant(0);

Expr truth(Expr e) { return zeroOrOne(e) ? e : Expr::binary(Op::Ne, std::move(e), Expr::constant(0)); }

Expr mkNot(Expr a) {
  if (a.op == Op::Const) return Expr::constant(a.value == 0 ? 1 : 0);
  return Expr::unary(Op::Not, std::move(a));
}
Expr mkAnd(Expr a, Expr b) {
  if (a.op == Op::Const) return a.value == 0 ? kFalse : truth(std::move(b));
  if (b.op == Op::Const) return b.value == 0 ? kFalse : truth(std::move(a));
  return Expr::binary(Op::And, std::move(a), std::move(b));
}
Expr mkOr(Expr a, Expr b) {
  if (a.op == Op::Const) return a.value != 0 ? kTrue : truth(std::move(b));
  if (b.op == Op::Const) return b.value != 0 ? kTrue : truth(std::move(a));
  return Expr::binary(Op::Or, std::move(a), std::move(b));
}

void addAlternative(std::vector<Expr>& to, Expr e) {
  for (const Expr& x : to) {
    if (sameExpr(x, e)) return;
  }
  to.push_back(std::move(e));
}

class Abstractor {
 public:
  Abstractor(const std::vector<char>& keep, const std::vector<std::int32_t>& newId) : keep_(keep), newId_(newId) {}

  [[nodiscard]] bool exact(const Expr& e) const {
    if (e.op == Op::Var) return keep_[static_cast<std::size_t>(e.value)] != 0;
    return std::all_of(e.args.begin(), e.args.end(), [&](const Expr& a) { return exact(a); });
  }

  [[nodiscard]] Expr rename(const Expr& e) const {
    if (e.op == Op::Var) return Expr::var(static_cast<ir::VarId>(newId_[static_cast<std::size_t>(e.value)]));
    Expr out{e.op, e.value, {}};
    out.args.reserve(e.args.size());
    for (const Expr& a : e.args) out.args.push_back(rename(a));
    return out;
  }

  // A condition on the kept variables implied by e (as a truth value) whatever the removed ones hold.
  [[nodiscard]] Expr upper(const Expr& e) const { return bound(e, true); }
  // A condition on the kept variables that implies e.
  [[nodiscard]] Expr lower(const Expr& e) const { return bound(e, false); }

  // Expressions over the kept variables one of which has e's value, whatever the removed
  // variables hold; nullopt when there are too many to list (any value).
  [[nodiscard]] std::optional<std::vector<Expr>> alternatives(const Expr& e) const {
    if (exact(e)) return std::vector<Expr>{rename(e)};
    if (e.op == Op::Var) return std::nullopt;
    if (isComparison(e.op) || isConnective(e.op)) {
      std::vector<Expr> out;
      addAlternative(out, truth(lower(e)));
      addAlternative(out, truth(upper(e)));
      return out;
    }
    if (e.op == Op::Ite) {
      auto then = alternatives(e.args[1]), otherwise = alternatives(e.args[2]);
      if (!then || !otherwise) return std::nullopt;
      std::vector<Expr> out;
      if (exact(e.args[0]) && then->size() * otherwise->size() <= kMaxAlternatives) {
        Expr c = rename(e.args[0]);
        for (const Expr& a : *then) {
          for (const Expr& b : *otherwise) addAlternative(out, Expr::ite(c, a, b));
        }
        return out;
      }
      for (Expr& a : *then) addAlternative(out, std::move(a));
      for (Expr& b : *otherwise) addAlternative(out, std::move(b));
      if (out.size() > kMaxAlternatives) return std::nullopt;
      return out;
    }
    // Arithmetic: every combination of its operands' alternatives.
    std::vector<std::vector<Expr>> operands;
    std::size_t combinations = 1;
    for (const Expr& a : e.args) {
      auto alts = alternatives(a);
      if (!alts) return std::nullopt;
      combinations *= alts->size();
      if (combinations > kMaxAlternatives) return std::nullopt;
      operands.push_back(std::move(*alts));
    }
    std::vector<Expr> out;
    std::vector<std::size_t> pick(operands.size(), 0);
    for (std::size_t n = 0; n < combinations; ++n) {
      Expr x{e.op, e.value, {}};
      for (std::size_t k = 0; k < operands.size(); ++k) x.args.push_back(operands[k][pick[k]]);
      addAlternative(out, std::move(x));
      for (std::size_t k = 0; k < pick.size() && ++pick[k] == operands[k].size(); ++k) pick[k] = 0;
    }
    return out;
  }

 private:
  // up: an over-approximation (implied by e); else an under-approximation (implies e).
  [[nodiscard]] Expr bound(const Expr& e, bool up) const {
    if (exact(e)) return rename(e);
    switch (e.op) {
      case Op::Not: return mkNot(bound(e.args[0], !up));
      case Op::And: return mkAnd(bound(e.args[0], up), bound(e.args[1], up));
      case Op::Or: return mkOr(bound(e.args[0], up), bound(e.args[1], up));
      case Op::Implies: return mkOr(mkNot(bound(e.args[0], !up)), bound(e.args[1], up));
      case Op::Ite: {
        if (exact(e.args[0])) return Expr::ite(rename(e.args[0]), truth(bound(e.args[1], up)), truth(bound(e.args[2], up)));
        // Either branch may be taken.
        return up ? mkOr(bound(e.args[1], up), bound(e.args[2], up)) : mkAnd(bound(e.args[1], up), bound(e.args[2], up));
      }
      default: break;
    }
    if (isComparison(e.op)) {
      auto left = alternatives(e.args[0]), right = alternatives(e.args[1]);
      if (left && right && left->size() * right->size() <= kMaxAlternatives) {
        Expr out = up ? kFalse : kTrue;
        for (const Expr& a : *left) {
          for (const Expr& b : *right) {
            Expr c = Expr::binary(e.op, a, b);
            out = up ? mkOr(std::move(out), std::move(c)) : mkAnd(std::move(out), std::move(c));
          }
        }
        return out;
      }
      return up ? kTrue : kFalse;
    }
    // A number read as a truth value.
    auto alts = alternatives(e);
    if (!alts) return up ? kTrue : kFalse;
    Expr out = up ? kFalse : kTrue;
    for (const Expr& a : *alts) out = up ? mkOr(std::move(out), truth(a)) : mkAnd(std::move(out), truth(a));
    return out;
  }

  const std::vector<char>& keep_;
  const std::vector<std::int32_t>& newId_;
};

ir::Ltl renameLtl(const ir::Ltl& f, const Abstractor& a) {
  ir::Ltl out{f.kind, {}, {}};
  if (f.kind == ir::Ltl::Kind::Atom) out.atom = a.rename(f.atom);
  for (const ir::Ltl& g : f.args) out.args.push_back(renameLtl(g, a));
  return out;
}

}  // namespace

void markVariablesRead(const ir::Expr& e, std::vector<char>& mark) {
  if (e.op == Op::Var) mark[static_cast<std::size_t>(e.value)] = 1;
  for (const Expr& a : e.args) markVariablesRead(a, mark);
}

void markVariablesRead(const ir::Ltl& f, std::vector<char>& mark) {
  if (f.kind == ir::Ltl::Kind::Atom) markVariablesRead(f.atom, mark);
  for (const ir::Ltl& g : f.args) markVariablesRead(g, mark);
}

bool usesNext(const ir::Ltl& f) {
  if (f.kind == ir::Ltl::Kind::Next) return true;
  return std::any_of(f.args.begin(), f.args.end(), [](const ir::Ltl& g) { return usesNext(g); });
}

namespace {

// Whether the slice sees exactly when a group is enabled: the disjunction of its rules' guards
// weakened to the kept variables (which holds wherever one of the guards may) holds only where,
// whatever the removed variables hold, one of the guards does. Decided by going through the values
// of the variables the guards read (when they have at most 65,536 combinations; otherwise no).
bool enabledExactly(const ir::Model& model, const std::vector<std::uint32_t>& members, const std::vector<char>& neverFires,
                    const std::vector<char>& keep, const std::vector<std::int32_t>& newId, const Abstractor& abs) {
  constexpr std::uint64_t kMaxCombinations = 1u << 16;
  std::vector<char> reads(model.variables.size(), 0);
  std::vector<Program> guards, weakened;
  for (std::uint32_t r : members) {
    if (r < neverFires.size() && neverFires[r] != 0) continue;
    markVariablesRead(model.rules[r].guard, reads);
    guards.emplace_back(model.rules[r].guard);
    weakened.emplace_back(abs.upper(model.rules[r].guard));
  }
  std::vector<ir::VarId> kept, removed;
  std::uint64_t combinations = 1;
  for (ir::VarId v = 0; v < reads.size(); ++v) {
    if (reads[v] == 0) continue;
    (keep[v] != 0 ? kept : removed).push_back(v);
    combinations *= static_cast<std::uint64_t>(static_cast<std::int64_t>(model.variables[v].max) - model.variables[v].min + 1);
    if (combinations > kMaxCombinations) return false;
  }
  std::vector<Value> values(model.variables.size(), 0), sliceValues(keep.size(), 0);
  // Odometer over a list of variables; false once every combination has been seen.
  auto first = [&](const std::vector<ir::VarId>& vars) {
    for (ir::VarId v : vars) values[v] = model.variables[v].min;
  };
  auto next = [&](const std::vector<ir::VarId>& vars) {
    for (ir::VarId v : vars) {
      if (values[v] < model.variables[v].max) {
        ++values[v];
        return true;
      }
      values[v] = model.variables[v].min;
    }
    return false;
  };
  auto any = [](const std::vector<Program>& ps, const Value* at) {
    return std::any_of(ps.begin(), ps.end(), [&](const Program& p) { return p.eval(at) != 0; });
  };
  first(kept);
  do {
    for (ir::VarId v : kept) sliceValues[static_cast<std::size_t>(newId[v])] = values[v];
    if (!any(weakened, sliceValues.data())) continue;
    first(removed);
    do {
      if (!any(guards, values.data())) return false;
    } while (next(removed));
  } while (next(kept));
  return true;
}

}  // namespace

// The slice keeping `keep`, without a property; rules marked in `neverFires` are left out.
Slice sliceVariables(const ir::Model& model, const std::vector<char>& keep, const std::vector<char>& neverFires) {
  auto dead = [&](std::uint32_t r) { return r < neverFires.size() && neverFires[r] != 0; };
  Slice out;
  std::vector<std::int32_t> newId(model.variables.size(), -1);
  for (ir::VarId v = 0; v < model.variables.size(); ++v) {
    if (!keep[v]) continue;
    newId[v] = static_cast<std::int32_t>(out.variables.size());
    out.variables.push_back(v);
    out.model.variables.push_back(model.variables[v]);
  }
  out.model.robots = model.robots;
  out.model.assumptions = model.assumptions;
  const Abstractor abs(keep, newId);
  std::vector<char> coarse(model.variables.size(), 0);
  // A rule is kept when it assigns a kept variable, or nothing at all: a step that changes nothing
  // (a robot calling a service again while it waits) is a stutter of the slice too, and keeping it
  // lets the slice see the fairness group it belongs to.
  auto assignsKept = [&](const ir::Rule& rule) {
    bool assignsAny = false;
    for (const ir::Branch& b : rule.branches) {
      for (const ir::Assignment& a : b.assignments) {
        if (keep[a.var]) return true;
        assignsAny = true;
      }
    }
    return !assignsAny;
  };
  // A group keeps its fairness only when the slice sees every rule of it, and sees exactly when the
  // group is enabled: else it cannot tell whether the group stays enabled, nor whether it was
  // taken. Each guard exact will do; so will guards that split on removed variables, as the
  // branches of an `if` on a removed condition do, when their disjunction is exact
  // (enabledExactly).
  const Fairness fairness = Fairness::of(model);
  std::vector<char> groupKept(fairness.groups(), 1);
  for (std::uint32_t g = 0; g < fairness.groups(); ++g) {
    bool allExact = true;
    for (std::uint32_t r : fairness.members[g]) {
      if (dead(r)) continue;
      if (!assignsKept(model.rules[r])) groupKept[g] = 0;
      allExact = allExact && abs.exact(model.rules[r].guard);
    }
    if (groupKept[g] != 0 && !allExact && !enabledExactly(model, fairness.members[g], neverFires, keep, newId, abs)) groupKept[g] = 0;
  }

  for (std::uint32_t r = 0; r < model.rules.size(); ++r) {
    const ir::Rule& rule = model.rules[r];
    if (dead(r)) {
      ++out.neverFire;
      continue;
    }
    if (!assignsKept(rule)) {
      ++out.leftOut;
      continue;
    }
    ir::Rule s;
    s.name = rule.name;
    s.robot = rule.robot;
    s.kind = rule.kind;
    s.origin = rule.origin;
    s.label = rule.label;
    const bool exactGuard = abs.exact(rule.guard);
    s.guard = abs.upper(rule.guard);
    const bool fair = fairness.groupOf[r] != Fairness::kNone && groupKept[fairness.groupOf[r]] != 0;
    s.weaklyFair = fair && rule.weaklyFair;
    s.stronglyFair = fair && rule.stronglyFair;
    s.fairGroup = rule.fairGroup;
    s.sensed = rule.sensed;
    if (!fair && (rule.weaklyFair || rule.stronglyFair)) ++out.fairnessDropped;
    bool exactUpdates = true;
    for (const ir::Branch& b : rule.branches) {
      // Each kept assignment with its possible new values; the outcomes are their combinations.
      std::vector<std::pair<ir::VarId, std::vector<Expr>>> choices;
      std::size_t outcomes = 1;
      for (const ir::Assignment& a : b.assignments) {
        if (!keep[a.var]) continue;
        std::vector<Expr> values;
        if (abs.exact(a.value)) {
          values.push_back(abs.rename(a.value));
        } else {
          exactUpdates = false;
          const ir::Variable& var = model.variables[a.var];
          if (auto alts = abs.alternatives(a.value)) {
            values = std::move(*alts);
          } else if (static_cast<std::int64_t>(var.max) - var.min < kMaxRange) {
            for (std::int32_t x = var.min; x <= var.max; ++x) values.push_back(Expr::constant(x));
          } else {
            out.tooCoarse = true;
            markVariablesRead(a.value, coarse);
            values.push_back(abs.rename(Expr::var(a.var)));  // unused: the slice is refined first
          }
        }
        outcomes *= values.size();
        if (outcomes > kMaxOutcomes) {
          out.tooCoarse = true;
          markVariablesRead(a.value, coarse);
          outcomes = kMaxOutcomes;
          values.resize(1);
        }
        choices.emplace_back(static_cast<ir::VarId>(newId[a.var]), std::move(values));
      }
      std::vector<std::size_t> pick(choices.size(), 0);
      std::size_t count = 1;
      for (const auto& c : choices) count *= c.second.size();
      for (std::size_t n = 0; n < count; ++n) {
        ir::Branch nb;
        nb.probability = b.probability / static_cast<double>(count);
        for (std::size_t k = 0; k < choices.size(); ++k) nb.assignments.push_back({choices[k].first, choices[k].second[pick[k]]});
        s.branches.push_back(std::move(nb));
        for (std::size_t k = 0; k < pick.size() && ++pick[k] == choices[k].second.size(); ++k) pick[k] = 0;
      }
    }
    out.model.rules.push_back(std::move(s));
    out.rules.push_back(r);
    out.exactGuard.push_back(exactGuard ? 1 : 0);
    out.exactUpdates.push_back(exactUpdates ? 1 : 0);
  }
  for (ir::VarId v = 0; v < coarse.size(); ++v) {
    if (coarse[v] && !keep[v]) out.coarseReads.push_back(v);
  }
  return out;
}

Slice sliceModel(const ir::Model& model, std::size_t property, std::vector<char> keep, const std::vector<char>& neverFires) {
  const ir::Property& prop = model.properties.at(property);
  keep.resize(model.variables.size(), 0);
  markVariablesRead(prop.formula, keep);
  std::vector<std::int32_t> newId(model.variables.size(), -1);
  Slice out = sliceVariables(model, keep, neverFires);
  for (std::size_t k = 0; k < out.variables.size(); ++k) newId[out.variables[k]] = static_cast<std::int32_t>(k);
  const Abstractor abs(keep, newId);
  out.model.properties.push_back({prop.name, prop.origin, renameLtl(prop.formula, abs), prop.settled});
  return out;
}

ir::Expr seenThrough(const ir::Expr& e, const Slice& slice, std::size_t modelVariables) {
  std::vector<char> keep(modelVariables, 0);
  std::vector<std::int32_t> newId(modelVariables, -1);
  for (std::size_t k = 0; k < slice.variables.size(); ++k) {
    keep[slice.variables[k]] = 1;
    newId[slice.variables[k]] = static_cast<std::int32_t>(k);
  }
  return Abstractor(keep, newId).upper(e);
}

std::vector<char> coneOfInfluence(const ir::Model& model, std::size_t property, const std::vector<char>& neverFires) {
  std::vector<char> cone(model.variables.size(), 0);
  markVariablesRead(model.properties.at(property).formula, cone);
  // Round after round over the rules until none adds a variable: a few rounds on a mission, each
  // linear in the model's size.
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t k = 0; k < model.rules.size(); ++k) {
      if (k < neverFires.size() && neverFires[k] != 0) continue;
      const ir::Rule& r = model.rules[k];
      bool assigns = false;
      for (const ir::Branch& b : r.branches) {
        for (const ir::Assignment& a : b.assignments) assigns = assigns || cone[a.var] != 0;
      }
      if (!assigns) continue;
      std::vector<char> reads(model.variables.size(), 0);
      markVariablesRead(r.guard, reads);
      for (const ir::Branch& b : r.branches) {
        for (const ir::Assignment& a : b.assignments) {
          if (cone[a.var] != 0) markVariablesRead(a.value, reads);
        }
      }
      for (std::size_t v = 0; v < reads.size(); ++v) {
        if (reads[v] != 0 && cone[v] == 0) cone[v] = 1, grew = true;
      }
    }
  }
  return cone;
}

std::size_t withoutUnfairEnvironment(Slice& slice) {
  std::size_t removed = 0, kept = 0;
  for (std::size_t j = 0; j < slice.model.rules.size(); ++j) {
    const ir::Rule& r = slice.model.rules[j];
    const bool environment = r.kind == ir::RuleKind::Crash || r.kind == ir::RuleKind::Environment;
    if (environment && !r.weaklyFair && !r.stronglyFair && r.fairGroup.empty()) {
      ++removed;
      continue;
    }
    if (kept != j) {
      slice.model.rules[kept] = std::move(slice.model.rules[j]);
      slice.rules[kept] = slice.rules[j];
      slice.exactGuard[kept] = slice.exactGuard[j];
      slice.exactUpdates[kept] = slice.exactUpdates[j];
    }
    ++kept;
  }
  slice.model.rules.resize(kept);
  slice.rules.resize(kept);
  slice.exactGuard.resize(kept);
  slice.exactUpdates.resize(kept);
  return removed;
}

}  // namespace semo::checker
