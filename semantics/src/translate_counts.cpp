// Counts of a large team (specs/semantics.md, "Counts of a large team"). A robot's rule that asks
// about its teammates (is any of them still forming the group block? does any hold facts to teach?)
// reads one count of the team instead of one condition per teammate, so that the model of a team
// of N robots has O(N) rules of constant size rather than O(N^2) terms. A count is a variable of
// the team: how many of its live robots have their knowledge count, or their program counter of a
// plan, among some values. It is a function of the robots' variables (it adds no state), kept so
// by every rule that changes one of them (maintainCounts).
#include <algorithm>

#include "translator.hpp"

namespace semo::detail {

namespace {

bool isConst(const Expr& e) { return e.op == Op::Const; }

// x is one of `values` (ascending): folded when x is a constant.
Expr member(const std::vector<std::int32_t>& values, Expr x) {
  if (isConst(x)) return Expr::constant(std::binary_search(values.begin(), values.end(), x.value) ? 1 : 0);
  if (values.size() == 1) return eq(std::move(x), values.front());
  if (values.back() - values.front() + 1 == static_cast<std::int32_t>(values.size())) {
    return ir::conjunction({Expr::binary(Op::Ge, x, Expr::constant(values.front())), Expr::binary(Op::Le, x, Expr::constant(values.back()))});
  }
  std::vector<Expr> any;
  for (std::int32_t v : values) any.push_back(eq(x, v));
  return ir::disjunction(std::move(any));
}

// a && b, folded when either is a constant.
Expr both(Expr a, Expr b) {
  if (isConst(a)) return a.value == 0 ? Expr::constant(0) : std::move(b);
  if (isConst(b)) return b.value == 0 ? Expr::constant(0) : std::move(a);
  return ir::conjunction({std::move(a), std::move(b)});
}

// What a guard fixes, from its top-level conjuncts: `v == c` pins v to c, `v` to 1, `!v` to 0.
// A few per guard: a list, not a table over every variable of the model.
using Pins = std::vector<std::pair<ir::VarId, std::int32_t>>;
void pins(const Expr& guard, Pins& out) {
  std::vector<const Expr*> pending{&guard};
  while (!pending.empty()) {
    const Expr* e = pending.back();
    pending.pop_back();
    if (e->op == Op::And) {
      for (const Expr& a : e->args) pending.push_back(&a);
    } else if (e->op == Op::Var) {
      out.emplace_back(static_cast<ir::VarId>(e->value), 1);
    } else if (e->op == Op::Not && e->args[0].op == Op::Var) {
      out.emplace_back(static_cast<ir::VarId>(e->args[0].value), 0);
    } else if (e->op == Op::Eq && e->args[0].op == Op::Var && isConst(e->args[1])) {
      out.emplace_back(static_cast<ir::VarId>(e->args[0].value), e->args[1].value);
    }
  }
}

}  // namespace

ir::VarId Translator::teamCount(Index team, VariableRole::Kind role, std::size_t planIndex, const std::string& knowledge,
                                std::vector<std::int32_t> values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  // Asked once per robot's rule: found by what it counts, without going through the team.
  const CountKey key{team, role, planIndex, knowledge, values};
  if (auto known = countIndex_.find(key); known != countIndex_.end()) return known->second;
  std::vector<std::optional<ir::VarId>> of;
  for (Index r : m_.teams[team].robots) {
    if (role == VariableRole::Kind::Holding) {
      auto k = vars_[r].knows.find(knowledge);
      of.push_back(k == vars_[r].knows.end() ? std::nullopt : std::optional<ir::VarId>(k->second));
    } else {
      of.push_back(vars_[r].pc[planIndex]);
    }
  }
  std::string name = m_.teams[team].name + (role == VariableRole::Kind::Holding ? ".holding." + knowledge : ".at." + m_.teams[team].plans[planIndex]);
  std::int32_t init = 0, robots = 0;
  for (std::size_t i = 0; i < of.size(); ++i) {
    if (!of[i]) continue;
    ++robots;
    const ir::Variable& v = out_.variables[*of[i]];
    if (std::binary_search(values.begin(), values.end(), v.init)) ++init;  // every robot starts alive
  }
  for (std::int32_t v : values) name += "." + std::to_string(v);
  VariableRole meaning(role, model::kNone, team, role == VariableRole::Kind::AtPoints ? static_cast<Index>(planIndex) : model::kNone,
                       role == VariableRole::Kind::Holding ? knowledge : std::string());
  meaning.values = values;
  ir::VarId var = addVar(std::move(name), 0, robots, init, ir::kNoRobot, std::move(meaning));
  out_.variables.back().isBool = false;
  counts_.push_back({var, team, std::move(of), std::move(values)});
  countIndex_.emplace(key, var);
  return var;
}

const Translator::TeamCount& Translator::countOf(ir::VarId var) const {  // a handful per team
  return *std::find_if(counts_.begin(), counts_.end(), [&](const TeamCount& c) { return c.var == var; });
}

Expr Translator::othersCounted(ir::VarId count, Index robot, Expr own) const {
  const TeamCount& c = countOf(count);
  if (!c.of[m_.robots[robot].indexInTeam]) return Expr::var(count);
  Expr self = member(c.values, std::move(own));
  if (isConst(self) && self.value == 0) return Expr::var(count);
  return Expr::binary(Op::Sub, Expr::var(count), std::move(self));
}

std::vector<Expr> Translator::countDefinitions() const {
  std::vector<Expr> out;
  for (const TeamCount& c : counts_) {
    Expr sum = Expr::constant(0);
    for (std::size_t i = 0; i < c.of.size(); ++i) {
      if (!c.of[i]) continue;
      const std::optional<ir::VarId> alive = vars_[m_.teams[c.team].robots[i]].alive;
      Expr counted = both(alive ? Expr::var(*alive) : Expr::constant(1), member(c.values, Expr::var(*c.of[i])));
      sum = Expr::binary(Op::Add, std::move(sum), Expr::ite(std::move(counted), Expr::constant(1), Expr::constant(0)));
    }
    out.push_back(Expr::binary(Op::Eq, Expr::var(c.var), std::move(sum)));
  }
  return out;
}

void Translator::maintainCounts() {
  if (counts_.empty()) return;
  // variable -> (count, robot's place in its team) that it feeds
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> feeds(out_.variables.size());
  for (std::size_t ci = 0; ci < counts_.size(); ++ci) {
    const TeamCount& c = counts_[ci];
    for (std::size_t i = 0; i < c.of.size(); ++i) {
      if (!c.of[i]) continue;
      feeds[*c.of[i]].push_back({ci, i});
      if (auto a = vars_[m_.teams[c.team].robots[i]].alive) feeds[*a].push_back({ci, i});
    }
  }
  Pins pinned;
  for (ir::Rule& rule : out_.rules) {
    bool touches = false;
    for (const ir::Branch& b : rule.branches) {
      for (const ir::Assignment& a : b.assignments) touches = touches || !feeds[a.var].empty();
    }
    if (!touches) continue;
    pinned.clear();
    pins(rule.guard, pinned);
    auto before = [&](ir::VarId v) {
      for (const auto& [var, value] : pinned) {
        if (var == v) return Expr::constant(value);
      }
      return Expr::var(v);
    };
    for (ir::Branch& b : rule.branches) {
      std::vector<std::pair<std::size_t, std::size_t>> touched;
      for (const ir::Assignment& a : b.assignments) touched.insert(touched.end(), feeds[a.var].begin(), feeds[a.var].end());
      std::sort(touched.begin(), touched.end());
      touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
      auto after = [&](ir::VarId v) {
        for (const ir::Assignment& a : b.assignments) {
          if (a.var == v) return a.value;
        }
        return before(v);
      };
      std::vector<ir::Assignment> updates;
      for (std::size_t k = 0; k < touched.size();) {
        const std::size_t ci = touched[k].first;
        const TeamCount& c = counts_[ci];
        std::int32_t delta = 0;
        std::vector<Expr> plus, minus;
        for (; k < touched.size() && touched[k].first == ci; ++k) {
          const std::optional<ir::VarId> alive = vars_[m_.teams[c.team].robots[touched[k].second]].alive;
          const ir::VarId x = *c.of[touched[k].second];
          Expr was = both(alive ? before(*alive) : Expr::constant(1), member(c.values, before(x)));
          Expr is = both(alive ? after(*alive) : Expr::constant(1), member(c.values, after(x)));
          if (isConst(was) && isConst(is)) {
            delta += (is.value != 0 ? 1 : 0) - (was.value != 0 ? 1 : 0);
            continue;
          }
          if (isConst(is)) delta += is.value != 0 ? 1 : 0;
          else plus.push_back(std::move(is));
          if (isConst(was)) delta -= was.value != 0 ? 1 : 0;
          else minus.push_back(std::move(was));
        }
        if (delta == 0 && plus.empty() && minus.empty()) continue;
        Expr value = Expr::var(c.var);
        for (Expr& p : plus) value = Expr::binary(Op::Add, std::move(value), std::move(p));
        for (Expr& m : minus) value = Expr::binary(Op::Sub, std::move(value), std::move(m));
        if (delta > 0) value = Expr::binary(Op::Add, std::move(value), Expr::constant(delta));
        if (delta < 0) value = Expr::binary(Op::Sub, std::move(value), Expr::constant(-delta));
        updates.push_back({c.var, std::move(value)});
      }
      for (ir::Assignment& u : updates) b.assignments.push_back(std::move(u));
    }
  }
}

}  // namespace semo::detail
