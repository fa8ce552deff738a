// The team seen as counts (counter_team.hpp).
#include "counter_team.hpp"

#include <algorithm>
#include <map>

namespace semo::checker::counter {

namespace {

using ir::Expr;
using ir::Op;

std::int64_t clampAdd(std::int64_t a, std::int64_t b) { return std::clamp(a + b, -kInfinity, kInfinity); }

std::int64_t clampMul(std::int64_t a, std::int64_t b) {
  if (a == 0 || b == 0) return 0;
  const bool negative = (a < 0) != (b < 0);
  if (std::abs(a) >= kInfinity || std::abs(b) >= kInfinity || std::abs(a) > kInfinity / std::abs(b)) return negative ? -kInfinity : kInfinity;
  return a * b;
}

Range truthRange(Truth t) { return t == Truth::True ? Range{1, 1} : t == Truth::False ? Range{0, 0} : Range{0, 1}; }

Truth notTruth(Truth t) { return t == Truth::True ? Truth::False : t == Truth::False ? Truth::True : Truth::Unknown; }

void flatten(const Expr& e, Op op, std::vector<const Expr*>& out) {
  if (e.op == op) {
    for (const Expr& a : e.args) flatten(a, op, out);
    return;
  }
  out.push_back(&e);
}

void collectRobots(const Expr& e, const Team& team, std::vector<std::size_t>& robots) {
  if (e.op == Op::Var) {
    const std::int32_t m = team.memberOf[static_cast<std::size_t>(e.value)];
    if (m >= 0) robots.push_back(static_cast<std::size_t>(m));
    return;
  }
  for (const Expr& a : e.args) collectRobots(a, team, robots);
}

// The robots whose variables `e` reads, ascending: a cost in the size of `e`, not of the team (a
// property over 100,000 robots has 100,000 parts).
std::vector<std::size_t> robotsRead(const Expr& e, const Team& team) {
  std::vector<std::size_t> robots;
  collectRobots(e, team, robots);
  std::sort(robots.begin(), robots.end());
  robots.erase(std::unique(robots.begin(), robots.end()), robots.end());
  return robots;
}

// Whether `e` (of robot a) is `f` (of robot b) with a's variables for b's.
bool sameRenamed(const Expr& e, const Expr& f, const Team& team, std::size_t a, std::size_t b) {
  if (e.op != f.op || e.args.size() != f.args.size()) return false;
  if (e.op == Op::Var) {
    const auto x = static_cast<std::size_t>(e.value), y = static_cast<std::size_t>(f.value);
    if (team.memberOf[x] < 0 || team.memberOf[y] < 0) return x == y;
    return static_cast<std::size_t>(team.memberOf[x]) == a && static_cast<std::size_t>(team.memberOf[y]) == b && team.slotOf[x] == team.slotOf[y];
  }
  if (e.value != f.value) return false;
  for (std::size_t k = 0; k < e.args.size(); ++k) {
    if (!sameRenamed(e.args[k], f.args[k], team, a, b)) return false;
  }
  return true;
}

// `e` with robot `from`'s variables replaced by robot `to`'s (other robots' variables kept).
Expr renamed(const Expr& e, const Team& team, std::size_t from, std::size_t to) {
  if (e.op == Op::Var) {
    const auto x = static_cast<std::size_t>(e.value);
    if (team.memberOf[x] != static_cast<std::int32_t>(from)) return e;
    return Expr::var(team.slots[to][static_cast<std::size_t>(team.slotOf[x])]);
  }
  Expr out{e.op, e.value, {}};
  out.args.reserve(e.args.size());
  for (const Expr& a : e.args) out.args.push_back(renamed(a, team, from, to));
  return out;
}

// A key equal for two expressions, each of one counted robot, exactly when one is the other with
// the robots renamed.
void templateKey(const Expr& e, const Team& team, std::size_t robot, std::string& out) {
  if (e.op == Op::Var) {
    const auto x = static_cast<std::size_t>(e.value);
    out += team.memberOf[x] != static_cast<std::int32_t>(robot) ? "v" + std::to_string(x) : "s" + std::to_string(team.slotOf[x]);
    return;
  }
  out += "(" + std::to_string(static_cast<int>(e.op)) + ":" + std::to_string(e.value);
  for (const Expr& a : e.args) {
    out += ' ';
    templateKey(a, team, robot, out);
  }
  out += ')';
}

std::string withoutRobot(const std::string& name, const std::string& robot) {
  return name.compare(0, robot.size() + 1, robot + ".") == 0 ? name.substr(robot.size() + 1) : name;
}

bool onlyOwn(const Expr& e, const Team& team, std::int32_t robot) {
  if (e.op == Op::Var) {
    const std::int32_t m = team.memberOf[static_cast<std::size_t>(e.value)];
    return m < 0 || m == robot;
  }
  return std::all_of(e.args.begin(), e.args.end(), [&](const Expr& a) { return onlyOwn(a, team, robot); });
}

}  // namespace

Truth truthOf(Range r) {
  if (r.lo == 0 && r.hi == 0) return Truth::False;
  if (r.lo > 0 || r.hi < 0) return Truth::True;
  return Truth::Unknown;
}

std::optional<Team> teamOf(const ir::Model& model, const std::vector<ir::Expr>& countDefinitions, std::string& why) {
  Team team;
  const std::size_t n = model.variables.size();
  team.memberOf.assign(n, -1);
  team.slotOf.assign(n, -1);
  team.globalIndex.assign(n, -1);
  team.countIndex.assign(n, -1);
  if (model.robots.size() < 2 || countDefinitions.empty()) {
    why = "the model has no team counts (a team of more than 8 robots has them)";
    return std::nullopt;
  }
  for (std::size_t r = 0; r < model.robots.size(); ++r) team.robots.push_back(static_cast<std::int32_t>(r));
  team.slots.resize(model.robots.size());
  team.rules.resize(model.robots.size());
  for (ir::VarId v = 0; v < n; ++v) {
    const std::int32_t r = model.variables[v].robot;
    if (r < 0) continue;
    team.memberOf[v] = r;
    team.slotOf[v] = static_cast<std::int32_t>(team.slots[static_cast<std::size_t>(r)].size());
    team.slots[static_cast<std::size_t>(r)].push_back(v);
  }
  for (const Expr& d : countDefinitions) {
    if (d.op != Op::Eq || d.args.size() != 2 || d.args[0].op != Op::Var) {
      why = "a count's definition is not `count == sum`";
      return std::nullopt;
    }
    Team::Count c;
    c.var = static_cast<ir::VarId>(d.args[0].value);
    if (c.var >= n || model.variables[c.var].robot >= 0) {
      why = "a count is a robot's variable";
      return std::nullopt;
    }
    c.term.assign(model.robots.size(), Expr::constant(0));
    std::vector<const Expr*> terms;
    flatten(d.args[1], Op::Add, terms);
    for (const Expr* t : terms) {
      if (t->op == Op::Const && t->value == 0) continue;
      const std::vector<std::size_t> reads = robotsRead(*t, team);
      if (reads.size() != 1) {
        why = "a term of a count reads more than one robot";
        return std::nullopt;
      }
      c.term[reads[0]] = *t;
    }
    team.countIndex[c.var] = static_cast<std::int32_t>(team.counts.size());
    team.counts.push_back(std::move(c));
  }
  for (ir::VarId v = 0; v < n; ++v) {
    if (team.memberOf[v] >= 0 || team.countIndex[v] >= 0) continue;
    team.globalIndex[v] = static_cast<std::int32_t>(team.globals.size());
    team.globals.push_back(v);
  }
  for (std::uint32_t k = 0; k < model.rules.size(); ++k) {
    const ir::Rule& rule = model.rules[k];
    const std::int32_t owner = rule.robot;
    if (owner < 0) {
      team.globalRules.push_back(k);
    } else {
      team.rules[static_cast<std::size_t>(owner)].push_back(k);
    }
    bool own = onlyOwn(rule.guard, team, owner);
    for (const ir::Branch& b : rule.branches) {
      for (const ir::Assignment& a : b.assignments) {
        own = own && (team.memberOf[a.var] < 0 || team.memberOf[a.var] == owner) && onlyOwn(a.value, team, owner);
      }
    }
    if (!own) {
      why = "rule " + rule.name + " reads or writes another robot's variables";
      return std::nullopt;
    }
  }
  return team;
}

bool sameTemplate(const ir::Model& model, const Team& team, std::size_t a, std::size_t b, std::string& why) {
  const std::string& na = model.robots[static_cast<std::size_t>(team.robots[a])];
  const std::string& nb = model.robots[static_cast<std::size_t>(team.robots[b])];
  const auto& sa = team.slots[a];
  const auto& sb = team.slots[b];
  if (sa.size() != sb.size()) {
    why = na + " and " + nb + " have different variables";
    return false;
  }
  for (std::size_t k = 0; k < sa.size(); ++k) {
    const ir::Variable& x = model.variables[sa[k]];
    const ir::Variable& y = model.variables[sb[k]];
    if (withoutRobot(x.name, na) != withoutRobot(y.name, nb) || x.min != y.min || x.max != y.max || x.init != y.init) {
      why = "variable " + x.name + " is not " + y.name + " renamed";
      return false;
    }
  }
  const auto& ra = team.rules[a];
  const auto& rb = team.rules[b];
  if (ra.size() != rb.size()) {
    why = na + " and " + nb + " have different rules";
    return false;
  }
  for (std::size_t k = 0; k < ra.size(); ++k) {
    const ir::Rule& x = model.rules[ra[k]];
    const ir::Rule& y = model.rules[rb[k]];
    bool same = x.kind == y.kind && x.weaklyFair == y.weaklyFair && x.stronglyFair == y.stronglyFair &&
                withoutRobot(x.fairGroup, na) == withoutRobot(y.fairGroup, nb) && x.branches.size() == y.branches.size() &&
                sameRenamed(x.guard, y.guard, team, a, b);
    for (std::size_t j = 0; same && j < x.branches.size(); ++j) {
      const auto& xa = x.branches[j].assignments;
      const auto& ya = y.branches[j].assignments;
      same = xa.size() == ya.size();
      for (std::size_t i = 0; same && i < xa.size(); ++i) {
        same = sameRenamed(Expr::var(xa[i].var), Expr::var(ya[i].var), team, a, b) && sameRenamed(xa[i].value, ya[i].value, team, a, b);
      }
    }
    if (!same) {
      why = "rule " + x.name + " is not " + y.name + " renamed";
      return false;
    }
  }
  for (const Team::Count& c : team.counts) {
    if (!sameRenamed(c.term[a], c.term[b], team, a, b)) {
      why = "count " + model.variables[c.var].name + " counts " + na + " and " + nb + " differently";
      return false;
    }
  }
  return true;
}

std::optional<Range> evaluate(const ir::Expr& e, const Env& env) {
  const Team& team = *env.team;
  switch (e.op) {
    case Op::Const:
      return Range{e.value, e.value};
    case Op::Var: {
      const auto v = static_cast<std::size_t>(e.value);
      const std::int32_t m = team.memberOf[v];
      if (m >= 0) {
        const std::int32_t* slots = m == env.self ? env.selfSlots : (env.members != nullptr ? (*env.members)[static_cast<std::size_t>(m)] : nullptr);
        if (slots == nullptr) return std::nullopt;
        const std::int32_t x = slots[team.slotOf[v]];
        return Range{x, x};
      }
      if (team.countIndex[v] >= 0) {
        if (env.counts == nullptr) return std::nullopt;
        return env.counts[team.countIndex[v]];
      }
      if (env.globals == nullptr) return std::nullopt;
      const std::int32_t x = env.globals[team.globalIndex[v]];
      return Range{x, x};
    }
    default:
      break;
  }
  std::vector<Range> a;
  a.reserve(e.args.size());
  // The connectives and Ite decide from their first operand where they can (a guard's `alive &&`
  // keeps the rest from being read where the robot is not known).
  if (e.op == Op::And || e.op == Op::Or || e.op == Op::Implies) {
    auto first = evaluate(e.args[0], env);
    if (!first) return std::nullopt;
    Truth l = truthOf(*first);
    if (e.op == Op::Implies) l = notTruth(l);
    if (l == (e.op == Op::And ? Truth::False : Truth::True)) return truthRange(l);
    auto second = evaluate(e.args[1], env);
    if (!second) return std::nullopt;
    const Truth r = truthOf(*second);
    if (e.op == Op::And) return truthRange(l == Truth::True ? r : r == Truth::False ? Truth::False : Truth::Unknown);
    return truthRange(l == Truth::False ? r : r == Truth::True ? Truth::True : Truth::Unknown);
  }
  if (e.op == Op::Ite) {
    auto c = evaluate(e.args[0], env);
    if (!c) return std::nullopt;
    const Truth t = truthOf(*c);
    if (t != Truth::Unknown) return evaluate(e.args[t == Truth::True ? 1 : 2], env);
    auto x = evaluate(e.args[1], env), y = evaluate(e.args[2], env);
    if (!x || !y) return std::nullopt;
    return Range{std::min(x->lo, y->lo), std::max(x->hi, y->hi)};
  }
  for (const Expr& arg : e.args) {
    auto r = evaluate(arg, env);
    if (!r) return std::nullopt;
    a.push_back(*r);
  }
  auto compare = [&](auto holds, auto never) -> Range {
    if (holds(a[0], a[1])) return {1, 1};
    if (never(a[0], a[1])) return {0, 0};
    return {0, 1};
  };
  switch (e.op) {
    case Op::Not:
      return truthRange(notTruth(truthOf(a[0])));
    case Op::Neg:
      return Range{-a[0].hi, -a[0].lo};
    case Op::Add:
      return Range{clampAdd(a[0].lo, a[1].lo), clampAdd(a[0].hi, a[1].hi)};
    case Op::Sub:
      return Range{clampAdd(a[0].lo, -a[1].hi), clampAdd(a[0].hi, -a[1].lo)};
    case Op::Mul: {
      const std::int64_t p[4] = {clampMul(a[0].lo, a[1].lo), clampMul(a[0].lo, a[1].hi), clampMul(a[0].hi, a[1].lo), clampMul(a[0].hi, a[1].hi)};
      return Range{*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
    }
    case Op::Min:
      return Range{std::min(a[0].lo, a[1].lo), std::min(a[0].hi, a[1].hi)};
    case Op::Max:
      return Range{std::max(a[0].lo, a[1].lo), std::max(a[0].hi, a[1].hi)};
    case Op::Div:
    case Op::Mod:
      // Exact values only (the IR's division truncates; a zero divisor gives 0, as the search).
      if (!a[0].point() || !a[1].point()) return std::nullopt;
      if (a[1].lo == 0) return Range{0, 0};
      return e.op == Op::Div ? Range{a[0].lo / a[1].lo, a[0].lo / a[1].lo} : Range{a[0].lo % a[1].lo, a[0].lo % a[1].lo};
    case Op::Eq:
      return compare([](Range x, Range y) { return x.point() && y.point() && x.lo == y.lo; }, [](Range x, Range y) { return x.hi < y.lo || y.hi < x.lo; });
    case Op::Ne:
      return compare([](Range x, Range y) { return x.hi < y.lo || y.hi < x.lo; }, [](Range x, Range y) { return x.point() && y.point() && x.lo == y.lo; });
    case Op::Lt:
      return compare([](Range x, Range y) { return x.hi < y.lo; }, [](Range x, Range y) { return x.lo >= y.hi; });
    case Op::Le:
      return compare([](Range x, Range y) { return x.hi <= y.lo; }, [](Range x, Range y) { return x.lo > y.hi; });
    case Op::Gt:
      return compare([](Range x, Range y) { return x.lo > y.hi; }, [](Range x, Range y) { return x.hi <= y.lo; });
    case Op::Ge:
      return compare([](Range x, Range y) { return x.lo >= y.hi; }, [](Range x, Range y) { return x.hi < y.lo; });
    default:
      return std::nullopt;
  }
}

std::optional<TeamFormula> teamFormula(const ir::Model& model, const Team& team, const ir::Expr& e, const std::vector<char>& explicitRobots,
                                       std::size_t representative, std::vector<std::size_t>& individual) {
  std::vector<std::size_t> countedRead;
  for (std::size_t r : robotsRead(e, team)) {
    if (explicitRobots[r] == 0) countedRead.push_back(r);
  }
  if (countedRead.empty()) return TeamFormula{TeamFormula::Kind::Plain, e, {}};
  if (e.op == Op::Not) {
    auto inner = teamFormula(model, team, e.args[0], explicitRobots, representative, individual);
    if (!inner) return std::nullopt;
    return TeamFormula{TeamFormula::Kind::Not, {}, {std::move(*inner)}};
  }
  if (e.op == Op::Implies) {
    return teamFormula(model, team, Expr::binary(Op::Or, Expr::unary(Op::Not, e.args[0]), e.args[1]), explicitRobots, representative, individual);
  }
  if (e.op != Op::And && e.op != Op::Or) {
    individual.insert(individual.end(), countedRead.begin(), countedRead.end());
    return std::nullopt;
  }
  std::vector<const Expr*> parts;
  flatten(e, e.op, parts);
  TeamFormula out{e.op == Op::And ? TeamFormula::Kind::And : TeamFormula::Kind::Or, {}, {}};
  // Parts naming one counted robot each, grouped by what they say of it.
  std::map<std::string, std::vector<std::pair<std::size_t, const Expr*>>> byTemplate;
  std::vector<std::string> order;
  bool ok = true;
  for (const Expr* p : parts) {
    countedRead.clear();
    for (std::size_t r : robotsRead(*p, team)) {
      if (explicitRobots[r] == 0) countedRead.push_back(r);
    }
    if (countedRead.size() != 1) {
      auto sub = teamFormula(model, team, *p, explicitRobots, representative, individual);
      if (!sub) {
        ok = false;
        continue;
      }
      out.parts.push_back(std::move(*sub));
      continue;
    }
    std::string key;
    templateKey(*p, team, countedRead[0], key);
    auto [it, fresh] = byTemplate.try_emplace(key);
    if (fresh) order.push_back(key);
    it->second.emplace_back(countedRead[0], p);
  }
  std::size_t countedRobots = 0;
  for (char x : explicitRobots) countedRobots += x == 0 ? 1 : 0;
  for (const std::string& key : order) {
    const auto& group = byTemplate[key];
    std::vector<char> seen(team.robots.size(), 0);
    for (const auto& [r, p] : group) seen[r] = 1;
    if (group.size() != countedRobots || static_cast<std::size_t>(std::count(seen.begin(), seen.end(), 1)) != countedRobots) {
      for (const auto& [r, p] : group) individual.push_back(r);
      ok = false;
      continue;
    }
    const std::size_t from = group.front().first;
    out.parts.push_back({out.kind == TeamFormula::Kind::And ? TeamFormula::Kind::Every : TeamFormula::Kind::Some,
                         renamed(*group.front().second, team, from, representative), {}});
  }
  if (!ok) return std::nullopt;
  return out;
}

}  // namespace semo::checker::counter
