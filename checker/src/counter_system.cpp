// The abstract system of the counter abstraction (counter_system.hpp).
#include "counter_system.hpp"

#include <algorithm>

namespace semo::checker::counter {

namespace {

Truth and3(Truth a, Truth b) {
  if (a == Truth::False || b == Truth::False) return Truth::False;
  return a == Truth::True && b == Truth::True ? Truth::True : Truth::Unknown;
}
Truth or3(Truth a, Truth b) {
  if (a == Truth::True || b == Truth::True) return Truth::True;
  return a == Truth::False && b == Truth::False ? Truth::False : Truth::Unknown;
}
Truth not3(Truth a) { return a == Truth::True ? Truth::False : a == Truth::False ? Truth::True : Truth::Unknown; }

// An update's possible values beyond this many make the abstraction give up.
constexpr std::int64_t kMaxChoices = 64;

}  // namespace

System::System(const ir::Model& model, const Team& team, std::vector<char> explicitRobots, std::uint32_t threshold)
    : model_(model), team_(team), explicit_(std::move(explicitRobots)), threshold_(static_cast<std::int32_t>(threshold)),
      fairness_(Fairness::of(model)) {
  representative_ = team.robots.size();
  for (std::size_t r = 0; r < team.robots.size(); ++r) {
    if (explicit_[r] != 0) explicitOrder_.push_back(r);
    else if (representative_ == team.robots.size()) representative_ = r;
  }
  slotCount_ = team.slots.empty() ? 0 : team.slots[0].size();
  if (representative_ == team.robots.size()) error_ = "every robot of the team is named on its own";
}

std::uint32_t System::localId(const std::vector<std::int32_t>& local) {
  auto [it, fresh] = localIds_.try_emplace(local, static_cast<std::uint32_t>(locals_.size()));
  if (fresh) locals_.push_back(local);
  return it->second;
}

System::State System::pack(const std::vector<std::int32_t>& globals, const std::vector<std::vector<std::int32_t>>& explicitSlots,
                           const std::vector<std::pair<std::uint32_t, std::int32_t>>& counts) const {
  State s(globals);
  for (const auto& slots : explicitSlots) s.insert(s.end(), slots.begin(), slots.end());
  for (const auto& [local, count] : counts) {
    s.push_back(static_cast<std::int32_t>(local));
    s.push_back(count);
  }
  return s;
}

System::State System::initial() {
  std::vector<std::int32_t> globals;
  for (ir::VarId v : team_.globals) globals.push_back(model_.variables[v].init);
  std::vector<std::vector<std::int32_t>> explicitSlots;
  std::map<std::uint32_t, std::int32_t> counted;
  // Each count starts at what its definition gives for the robots' initial variables.
  for (const Team::Count& c : team_.counts) {
    std::int64_t counted = 0;
    for (std::size_t r = 0; r < team_.robots.size(); ++r) {
      std::vector<std::int32_t> slots;
      for (ir::VarId v : team_.slots[r]) slots.push_back(model_.variables[v].init);
      const auto t = evaluate(c.term[r], Env{&team_, static_cast<std::int32_t>(r), slots.data(), nullptr, nullptr, nullptr});
      counted += t && t->point() ? t->lo : -1'000'000;
    }
    if (counted != model_.variables[c.var].init) error_ = "count " + model_.variables[c.var].name + " does not start at its definition's value";
  }
  for (std::size_t r = 0; r < team_.robots.size(); ++r) {
    std::vector<std::int32_t> slots;
    for (ir::VarId v : team_.slots[r]) slots.push_back(model_.variables[v].init);
    if (explicit_[r] != 0) {
      explicitSlots.push_back(std::move(slots));
    } else {
      std::int32_t& c = counted[localId(slots)];
      c = std::min(c + 1, threshold_);
    }
  }
  return pack(globals, explicitSlots, {counted.begin(), counted.end()});
}

System::View System::view(const State& s) {
  View v;
  const std::size_t g = team_.globals.size();
  v.globals.assign(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(g));
  v.members.assign(team_.robots.size(), nullptr);
  std::size_t at = g;
  for (std::size_t r : explicitOrder_) {
    v.members[r] = s.data() + at;
    at += slotCount_;
  }
  for (; at + 1 < s.size(); at += 2) v.counts.emplace_back(static_cast<std::uint32_t>(s[at]), s[at + 1]);
  v.teamCounts.assign(team_.counts.size(), Range{0, 0});
  for (std::size_t c = 0; c < team_.counts.size(); ++c) {
    Range sum{0, 0};
    auto add = [&](Truth t, Range n) {
      if (t == Truth::True) sum = {sum.lo + n.lo, std::min(sum.hi + n.hi, kInfinity)};
      if (t == Truth::Unknown) sum = {sum.lo, std::min(sum.hi + n.hi, kInfinity)};
    };
    for (const auto& [local, count] : v.counts) {
      Env e{&team_, static_cast<std::int32_t>(representative_), locals_[local].data(), &v.members, nullptr, nullptr};
      const auto t = evaluate(team_.counts[c].term[representative_], e);
      add(t ? truthOf(*t) : Truth::Unknown, count < threshold_ ? Range{count, count} : Range{threshold_, kInfinity});
    }
    for (std::size_t r : explicitOrder_) {
      Env e{&team_, static_cast<std::int32_t>(r), v.members[r], &v.members, nullptr, nullptr};
      const auto t = evaluate(team_.counts[c].term[r], e);
      add(t ? truthOf(*t) : Truth::Unknown, Range{1, 1});
    }
    v.teamCounts[c] = sum;
  }
  return v;
}

Env System::env(const View& v, std::int32_t self, const std::int32_t* slots) const {
  return Env{&team_, self, slots, &v.members, v.globals.data(), v.teamCounts.data()};
}

bool System::fire(const ir::Rule& rule, const View& v, std::int32_t self, const std::int32_t* slots,
                  std::vector<std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>>& out) {
  const Env e = env(v, self, slots);
  for (const ir::Branch& b : rule.branches) {
    std::vector<std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>> partial;
    partial.emplace_back(slots != nullptr ? std::vector<std::int32_t>(slots, slots + slotCount_) : std::vector<std::int32_t>{}, v.globals);
    for (const ir::Assignment& a : b.assignments) {
      if (team_.countIndex[a.var] >= 0) continue;  // recomputed from the counts of local states
      const auto range = evaluate(a.value, e);
      const ir::Variable& var = model_.variables[a.var];
      if (!range) {
        error_ = "rule " + rule.name + ": the new value of " + var.name + " reads what the counts do not tell";
        return false;
      }
      const std::int64_t lo = std::max<std::int64_t>(range->lo, var.min), hi = std::min<std::int64_t>(range->hi, var.max);
      if (range->point() && (range->lo < var.min || range->lo > var.max)) {
        error_ = "rule " + rule.name + " sets " + var.name + " outside its range";
        return false;
      }
      if (hi - lo >= kMaxChoices) {
        error_ = "rule " + rule.name + ": the new value of " + var.name + " has too many possible values";
        return false;
      }
      const bool own = team_.memberOf[a.var] >= 0;
      if (own && team_.memberOf[a.var] != self) {
        error_ = "rule " + rule.name + " sets another robot's variable";
        return false;
      }
      std::vector<std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>> next;
      for (const auto& p : partial) {
        for (std::int64_t x = lo; x <= hi; ++x) {
          auto q = p;
          if (own) q.first[static_cast<std::size_t>(team_.slotOf[a.var])] = static_cast<std::int32_t>(x);
          else q.second[static_cast<std::size_t>(team_.globalIndex[a.var])] = static_cast<std::int32_t>(x);
          next.push_back(std::move(q));
        }
      }
      partial = std::move(next);
    }
    for (const auto& p : partial) {
      if (!countsFollow(rule, b, v, self, slots, p.first.empty() ? nullptr : p.first.data())) return false;
    }
    out.insert(out.end(), partial.begin(), partial.end());
  }
  return true;
}

// The abstraction recomputes each count from the local states, so it must be what the model's
// rules keep it at: a step changes a count by exactly what the robot's own term of it changes by
// (the count plus one when the robot starts being counted, ...), the same whatever the count was.
// Checked on every step taken, with the counts set to two sets of values.
bool System::countsFollow(const ir::Rule& rule, const ir::Branch& branch, const View& v, std::int32_t self, const std::int32_t* before,
                          const std::int32_t* after) {
  if (team_.counts.empty()) return true;
  auto term = [&](std::size_t c, const std::int32_t* slots) -> std::optional<std::int64_t> {
    if (self < 0) return 0;
    const auto t = evaluate(team_.counts[c].term[static_cast<std::size_t>(self)], Env{&team_, self, slots, &v.members, nullptr, nullptr});
    if (!t || !t->point()) return std::nullopt;
    return t->lo;
  };
  for (std::int64_t base : {7, 1000}) {
    std::vector<Range> points(team_.counts.size());
    for (std::size_t c = 0; c < points.size(); ++c) points[c] = Range{base + 3 * static_cast<std::int64_t>(c), base + 3 * static_cast<std::int64_t>(c)};
    const Env e{&team_, self, before, &v.members, v.globals.data(), points.data()};
    for (std::size_t c = 0; c < team_.counts.size(); ++c) {
      std::int64_t now = points[c].lo;
      for (const ir::Assignment& a : branch.assignments) {
        if (a.var != team_.counts[c].var) continue;
        const auto value = evaluate(a.value, e);
        if (!value || !value->point()) {
          error_ = "rule " + rule.name + ": the new value of " + model_.variables[a.var].name + " is not a count's step";
          return false;
        }
        now = value->lo;
      }
      const auto was = term(c, before), is = term(c, after);
      if (!was || !is || now - points[c].lo != *is - *was) {
        error_ = "rule " + rule.name + " changes " + model_.variables[team_.counts[c].var].name + " otherwise than its definition";
        return false;
      }
    }
  }
  return true;
}

System::Expansion System::expand(const State& s) {
  Expansion x;
  const View v = view(s);
  std::vector<std::vector<std::int32_t>> explicitSlots;
  for (std::size_t r : explicitOrder_) explicitSlots.emplace_back(v.members[r], v.members[r] + slotCount_);
  std::vector<std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>> outcomes;
  auto premise = [&](Label::Kind kind, std::int32_t where, std::uint32_t rule) {
    const std::uint32_t g = fairness_.groupOf[rule];
    if (g != Fairness::kNone) x.enabled.push_back({kind, where, g});
    x.someKnownEnabled = true;
  };
  auto guard = [&](const ir::Rule& rule, std::int32_t self, const std::int32_t* slots) -> std::optional<Truth> {
    const auto g = evaluate(rule.guard, env(v, self, slots));
    if (!g) {
      error_ = "rule " + rule.name + ": its guard reads what the counts do not tell";
      return std::nullopt;
    }
    return truthOf(*g);
  };
  // Robots counted in local state `local` (count `count`).
  for (const auto& [local, count] : v.counts) {
    const std::vector<std::int32_t> here = locals_[local];  // copied: localId may grow locals_
    for (std::uint32_t r : team_.rules[representative_]) {
      const ir::Rule& rule = model_.rules[r];
      const auto t = guard(rule, static_cast<std::int32_t>(representative_), here.data());
      if (!t) return x;
      if (*t == Truth::False) continue;
      if (*t == Truth::True) premise(Label::Kind::Counted, static_cast<std::int32_t>(local), r);
      outcomes.clear();
      if (!fire(rule, v, static_cast<std::int32_t>(representative_), here.data(), outcomes)) return x;
      for (auto& [slots, globals] : outcomes) {
        const std::uint32_t to = localId(slots);
        if (to == local) {
          x.steps.push_back({pack(globals, explicitSlots, v.counts), {Label::Kind::Counted, r, static_cast<std::int32_t>(local), static_cast<std::int32_t>(to)}});
          continue;
        }
        // One robot leaves `local`: "K or more" less one is K or more, or K - 1.
        std::vector<std::int32_t> lefts{count - 1};
        if (count == threshold_) lefts.push_back(count);
        for (std::int32_t left : lefts) {
          std::vector<std::pair<std::uint32_t, std::int32_t>> counts;
          bool entered = false;
          for (const auto& [l, c] : v.counts) {
            if (l == local) {
              if (left > 0) counts.emplace_back(l, left);
            } else if (l == to) {
              counts.emplace_back(l, std::min(c + 1, threshold_));
              entered = true;
            } else {
              counts.emplace_back(l, c);
            }
          }
          if (!entered) counts.insert(std::upper_bound(counts.begin(), counts.end(), std::make_pair(to, std::int32_t{0})), {to, 1});
          x.steps.push_back({pack(globals, explicitSlots, counts), {Label::Kind::Counted, r, static_cast<std::int32_t>(local), static_cast<std::int32_t>(to)}});
        }
      }
    }
  }
  // Robots kept exactly.
  for (std::size_t i = 0; i < explicitOrder_.size(); ++i) {
    const std::size_t robot = explicitOrder_[i];
    for (std::uint32_t r : team_.rules[robot]) {
      const ir::Rule& rule = model_.rules[r];
      const auto t = guard(rule, static_cast<std::int32_t>(robot), v.members[robot]);
      if (!t) return x;
      if (*t == Truth::False) continue;
      if (*t == Truth::True) premise(Label::Kind::Explicit, static_cast<std::int32_t>(robot), r);
      outcomes.clear();
      if (!fire(rule, v, static_cast<std::int32_t>(robot), v.members[robot], outcomes)) return x;
      for (auto& [slots, globals] : outcomes) {
        auto changed = explicitSlots;
        changed[i] = slots;
        x.steps.push_back({pack(globals, changed, v.counts), {Label::Kind::Explicit, r, static_cast<std::int32_t>(robot), static_cast<std::int32_t>(robot)}});
      }
    }
  }
  // Rules of no robot.
  for (std::uint32_t r : team_.globalRules) {
    const ir::Rule& rule = model_.rules[r];
    const auto t = guard(rule, -1, nullptr);
    if (!t) return x;
    if (*t == Truth::False) continue;
    if (*t == Truth::True) premise(Label::Kind::Global, 0, r);
    outcomes.clear();
    if (!fire(rule, v, -1, nullptr, outcomes)) return x;
    for (auto& [slots, globals] : outcomes) x.steps.push_back({pack(globals, explicitSlots, v.counts), {Label::Kind::Global, r, 0, 0}});
  }
  std::sort(x.enabled.begin(), x.enabled.end());
  x.enabled.erase(std::unique(x.enabled.begin(), x.enabled.end()), x.enabled.end());
  return x;
}

Truth System::holds(const ir::Expr& e, const State& s) {
  const View v = view(s);
  const auto r = evaluate(e, env(v, -1, nullptr));
  return r ? truthOf(*r) : Truth::Unknown;
}

Truth System::holds(const TeamFormula& f, const State& s) {
  const View v = view(s);
  auto eval = [&](auto& self, const TeamFormula& g) -> Truth {
    switch (g.kind) {
      case TeamFormula::Kind::Plain: {
        const auto r = evaluate(g.expr, env(v, -1, nullptr));
        return r ? truthOf(*r) : Truth::Unknown;
      }
      case TeamFormula::Kind::Every:
      case TeamFormula::Kind::Some: {
        const bool every = g.kind == TeamFormula::Kind::Every;
        Truth out = every ? Truth::True : Truth::False;
        for (const auto& [local, count] : v.counts) {
          const auto r = evaluate(g.expr, env(v, static_cast<std::int32_t>(representative_), locals_[local].data()));
          const Truth t = r ? truthOf(*r) : Truth::Unknown;
          out = every ? and3(out, t) : or3(out, t);
        }
        return out;
      }
      case TeamFormula::Kind::Not:
        return not3(self(self, g.parts[0]));
      case TeamFormula::Kind::And:
      case TeamFormula::Kind::Or: {
        const bool conj = g.kind == TeamFormula::Kind::And;
        Truth out = conj ? Truth::True : Truth::False;
        for (const TeamFormula& p : g.parts) out = conj ? and3(out, self(self, p)) : or3(out, self(self, p));
        return out;
      }
    }
    return Truth::Unknown;
  };
  return eval(eval, f);
}

}  // namespace semo::checker::counter
