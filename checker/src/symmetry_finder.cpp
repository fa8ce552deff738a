// Finding the interchangeable robots of a model (symmetry_finder.hpp): each candidate swap checked
// on the IR, by numbered canonical forms of what it moves.
#include "symmetry_finder.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

namespace semo::checker::detail {

namespace {

using ir::Expr;
using ir::Op;

std::vector<std::string> components(const std::string& name) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', start)) {
    out.push_back(name.substr(start, dot - start));
    start = dot + 1;
  }
  out.push_back(name.substr(start));
  return out;
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ".") + p;
  return out;
}

bool commutative(Op op) {
  switch (op) {
    case Op::And: case Op::Or: case Op::Eq: case Op::Ne: case Op::Add: case Op::Mul: case Op::Min: case Op::Max:
      return true;
    default:
      return false;
  }
}

bool associative(Op op) {
  return op == Op::And || op == Op::Or || op == Op::Add || op == Op::Mul || op == Op::Min || op == Op::Max;
}

void flatten(const Expr& e, Op op, std::vector<const Expr*>& out) {
  if (e.op == op) {
    for (const Expr& a : e.args) flatten(a, op, out);
  } else {
    out.push_back(&e);
  }
}

// A text for an expression, with variables renamed by `map`, that is the same for expressions
// equal up to the order of the operands of commutative operators.
std::string canon(const Expr& e, const VarMap& map) {
  switch (e.op) {
    case Op::Const: return "#" + std::to_string(e.value);
    case Op::Var: return "v" + std::to_string(map[static_cast<std::size_t>(e.value)]);
    default: break;
  }
  std::vector<std::string> parts;
  if (associative(e.op)) {
    std::vector<const Expr*> operands;
    flatten(e, e.op, operands);
    for (const Expr* a : operands) parts.push_back(canon(*a, map));
  } else {
    for (const Expr& a : e.args) parts.push_back(canon(a, map));
  }
  if (commutative(e.op)) std::sort(parts.begin(), parts.end());
  std::string out = "(" + std::to_string(static_cast<int>(e.op));
  for (const std::string& p : parts) out += " " + p;
  return out + ")";
}

// Canonical forms as numbers: an expression's form (operands of commutative operators in order,
// chains of an associative one flattened) numbered once, from its operands' numbers. Comparing a
// formula over a whole team under each of a hundred swaps compares numbers, not texts of
// megabytes. Under a swap a form never numbered (`add` false) is kUnknown: an expression whose
// form is no original one's cannot be equal to the original, and every part of an equal one is
// a part of the original, so looking up alone is exact.
class CanonTable {
 public:
  static constexpr std::uint32_t kUnknown = UINT32_MAX;

  // The swap the next lookups are under: the variables it moves. A part of the model that reads
  // none of them keeps the number it has as it is (remembered per node, with the range of the
  // variables it reads: a robot's variables are consecutive), so a guard over the whole team costs
  // a swap its operands, not its whole tree.
  void moving(const VarMap& map) {
    moved_.clear();
    for (ir::VarId v = 0; v < map.size(); ++v) {
      if (map[v] != v) moved_.push_back(v);
    }
  }

  // `add`: the model as it is (the identity), numbering new forms; else under the swap `moving`
  // was last told, looking up only.
  std::uint32_t of(const Expr& e, const VarMap& map, bool add) {
    if (!add) {
      auto it = memo_.find(&e);
      if (it != memo_.end() && !movesWithin(it->second.low, it->second.high)) return it->second.id;
    }
    std::vector<std::int64_t> key;
    Memo memo;
    switch (e.op) {
      case Op::Const: return number({0, e.value}, add);
      case Op::Var:
        memo.low = memo.high = static_cast<ir::VarId>(e.value);
        key = {1, map[static_cast<std::size_t>(e.value)]};
        break;
      default: {
        key.push_back(2 + static_cast<std::int64_t>(e.op));
        std::vector<const Expr*> operands;
        if (associative(e.op)) {
          flatten(e, e.op, operands);
        } else {
          for (const Expr& a : e.args) operands.push_back(&a);
        }
        for (const Expr* a : operands) {
          const std::uint32_t id = of(*a, map, add);
          if (id == kUnknown) return kUnknown;
          key.push_back(id);
          if (add) {
            auto it = memo_.find(a);
            if (it != memo_.end()) memo.low = std::min(memo.low, it->second.low), memo.high = std::max(memo.high, it->second.high);
          }
        }
        if (commutative(e.op)) std::sort(key.begin() + 1, key.end());
      }
    }
    memo.id = number(std::move(key), add);
    if (add) memo_.emplace(&e, memo);
    return memo.id;
  }

  std::uint32_t of(const ir::Ltl& f, const VarMap& map, bool add) {
    if (f.kind == ir::Ltl::Kind::Atom) {
      const std::uint32_t atom = of(f.atom, map, add);
      return atom == kUnknown ? kUnknown : number({-1, atom}, add);
    }
    std::vector<std::int64_t> key{-2 - static_cast<std::int64_t>(f.kind)};
    for (const ir::Ltl& a : f.args) {
      const std::uint32_t id = of(a, map, add);
      if (id == kUnknown) return kUnknown;
      key.push_back(id);
    }
    if (f.kind == ir::Ltl::Kind::And || f.kind == ir::Ltl::Kind::Or) std::sort(key.begin() + 1, key.end());
    return number(std::move(key), add);
  }

 private:
  struct KeyHash {
    std::size_t operator()(const std::vector<std::int64_t>& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (std::int64_t x : k) h = (h ^ static_cast<std::uint64_t>(x)) * 1099511628211ull;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };

  std::uint32_t number(std::vector<std::int64_t>&& key, bool add) {
    if (!add) {
      auto it = ids_.find(key);
      return it == ids_.end() ? kUnknown : it->second;
    }
    return ids_.emplace(std::move(key), static_cast<std::uint32_t>(ids_.size())).first->second;
  }

  struct Memo {
    std::uint32_t id = kUnknown;
    ir::VarId low = std::numeric_limits<ir::VarId>::max(), high = 0;  // the variables read: none when low > high
  };

  bool movesWithin(ir::VarId low, ir::VarId high) const {
    if (low > high) return false;
    auto it = std::lower_bound(moved_.begin(), moved_.end(), low);
    return it != moved_.end() && *it <= high;
  }

  std::unordered_map<std::vector<std::int64_t>, std::uint32_t, KeyHash> ids_;
  std::unordered_map<const Expr*, Memo> memo_;  // every node numbered as it is
  std::vector<ir::VarId> moved_;
};

// A rule's text: its kind, fairness, guard, where it senses and its outcomes, expressions by their
// numbers; nullopt when one is unknown (under a swap: then the rule is no rule of the model).
std::optional<std::string> ruleText(const ir::Rule& r, const VarMap& map, CanonTable& forms, bool add) {
  const std::uint32_t guard = forms.of(r.guard, map, add);
  if (guard == CanonTable::kUnknown) return std::nullopt;
  std::vector<std::string> branches;
  for (const ir::Branch& b : r.branches) {
    std::vector<std::string> updates;
    for (const ir::Assignment& a : b.assignments) {
      const std::uint32_t value = forms.of(a.value, map, add);
      if (value == CanonTable::kUnknown) return std::nullopt;
      updates.push_back("v" + std::to_string(map[a.var]) + ":=" + std::to_string(value));
    }
    std::sort(updates.begin(), updates.end());
    std::string text = std::to_string(b.probability);
    for (const std::string& u : updates) text += ";" + u;
    branches.push_back(std::move(text));
  }
  std::sort(branches.begin(), branches.end());
  std::string out = std::to_string(static_cast<int>(r.kind)) + (r.weaklyFair ? "w" : "") + (r.stronglyFair ? "s" : "") + "|" + std::to_string(guard);
  // Where it senses, without the robot (a place in the program, the same for every robot of a type).
  for (const ir::SensedOutcome& s : r.sensed) out += "|?" + s.point.substr(s.point.find('.') + 1) + (s.holds ? "+" : "-");
  for (const std::string& b : branches) out += "|" + b;
  return out;
}

// The variables a rule reads or writes: a swap that moves none of them leaves the rule's text alone.
std::vector<ir::VarId> ruleVariables(const ir::Rule& r) {
  std::vector<ir::VarId> out;
  std::vector<const Expr*> work{&r.guard};
  for (const ir::Branch& b : r.branches) {
    for (const ir::Assignment& a : b.assignments) {
      out.push_back(a.var);
      work.push_back(&a.value);
    }
  }
  while (!work.empty()) {  // an explicit stack: guards may be long
    const Expr* e = work.back();
    work.pop_back();
    if (e->op == Op::Var) out.push_back(static_cast<ir::VarId>(e->value));
    for (const Expr& a : e->args) work.push_back(&a);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

constexpr std::uint32_t kNoGroup = UINT32_MAX;

// Whether swapping two robots maps the model onto itself, and what it does to the rules.
//
// The model is the same under a swap when the multiset of its rules is (each rule's text with its
// variables renamed, and the texts of its fairness group, as fairness is per group: a swap must map
// groups onto groups), and each invariant, property and the valid end map to themselves. Texts are
// numbered once (a rule's own text, a group's sorted numbers), and a swap only recomputes the texts
// of the rules that read or write a robot it moves, and the numbers of their groups: the rest of
// the model is untouched. Each check then costs the swapped robots' share of the model, not the
// whole model (a team of 100 robots took 22 s, each swap comparing every rule's text).
class Finder {
 public:
  Finder(const ir::Model& m, const SymmetryScope& scope) : m_(m), scope_(scope) {
    for (ir::VarId v = 0; v < m.variables.size(); ++v) byName_[m.variables[v].name] = v;
    for (std::size_t r = 0; r < m.robots.size(); ++r) robotIndex_[m.robots[r]] = static_cast<std::int32_t>(r);
    identity_.resize(m.variables.size());
    for (ir::VarId v = 0; v < identity_.size(); ++v) identity_[v] = v;
    const std::size_t rules = m.rules.size();
    own_.resize(rules);
    group_.assign(rules, kNoGroup);
    users_.resize(m.variables.size());
    std::unordered_map<std::string, std::uint32_t> groupIndex;
    for (std::uint32_t r = 0; r < rules; ++r) {
      own_[r] = ownIds_.emplace(*ruleText(m.rules[r], identity_, forms_, true), static_cast<std::uint32_t>(ownIds_.size())).first->second;
      if (!m.rules[r].fairGroup.empty()) {
        auto [it, added] = groupIndex.emplace(m.rules[r].fairGroup, static_cast<std::uint32_t>(members_.size()));
        if (added) members_.emplace_back();
        group_[r] = it->second;
        members_[it->second].push_back(r);
      }
      for (ir::VarId v : ruleVariables(m.rules[r])) users_[v].push_back(r);
    }
    groupSig_.resize(members_.size());
    for (std::uint32_t g = 0; g < members_.size(); ++g) {
      std::vector<std::uint32_t> sig;
      for (std::uint32_t r : members_[g]) sig.push_back(own_[r]);
      std::sort(sig.begin(), sig.end());
      groupSig_[g] = sigIds_.emplace(std::move(sig), static_cast<std::uint32_t>(sigIds_.size())).first->second;
    }
    original_ = otherForms(identity_, true);
    ruleStamp_.assign(rules, 0);
    groupStamp_.assign(members_.size(), 0);
  }

  // What a verified swap does to the rules: rule r becomes out[r]. The rules it touches are paired
  // off by their texts, in order, so the map is a bijection; the others stay.
  std::vector<std::uint32_t> ruleMap(const VarMap& map) {
    std::vector<std::uint32_t> out(m_.rules.size());
    for (std::uint32_t r = 0; r < out.size(); ++r) out[r] = r;
    forms_.moving(map);
    const std::optional<Touched> t = touched(map);
    if (!t) return out;  // not reached: only verified swaps are mapped
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> byKey;
    for (std::uint32_t r : t->rules) byKey[key(own_[r], group_[r] == kNoGroup ? kNoGroup : groupSig_[group_[r]])].push_back(r);
    std::unordered_map<std::uint64_t, std::size_t> used;
    for (std::size_t i = 0; i < t->rules.size(); ++i) out[t->rules[i]] = byKey.at(t->keys[i]).at(used[t->keys[i]]++);
    return out;
  }
  // The swap of robots a and b as a permutation of the variables, if every variable has a twin.
  std::optional<VarMap> swap(std::int32_t a, std::int32_t b) const {
    const std::string& nameA = m_.robots[static_cast<std::size_t>(a)];
    const std::string& nameB = m_.robots[static_cast<std::size_t>(b)];
    VarMap map(m_.variables.size());
    for (ir::VarId v = 0; v < map.size(); ++v) {
      std::vector<std::string> parts = components(m_.variables[v].name);
      for (std::string& p : parts) {
        if (p == nameA) p = nameB;
        else if (p == nameB) p = nameA;
      }
      auto it = byName_.find(join(parts));
      if (it == byName_.end()) return std::nullopt;
      const ir::Variable& x = m_.variables[v];
      const ir::Variable& y = m_.variables[it->second];
      if (x.min != y.min || x.max != y.max || x.init != y.init) return std::nullopt;
      map[v] = it->second;
    }
    return map;
  }

  bool symmetric(std::int32_t a, std::int32_t b) {
    std::optional<VarMap> map = swap(a, b);
    if (!map) return false;
    forms_.moving(*map);
    if (otherForms(*map, false) != original_) return false;
    std::optional<Touched> t = touched(*map);
    if (!t) return false;
    std::vector<std::uint64_t> before;
    for (std::uint32_t r : t->rules) before.push_back(key(own_[r], group_[r] == kNoGroup ? kNoGroup : groupSig_[group_[r]]));
    std::sort(before.begin(), before.end());
    std::sort(t->keys.begin(), t->keys.end());
    return before == t->keys;
  }

  // The variables whose names mention robot r.
  std::vector<ir::VarId> varsOf(std::int32_t r) const {
    std::vector<ir::VarId> out;
    for (ir::VarId v = 0; v < m_.variables.size(); ++v) {
      for (const std::string& p : components(m_.variables[v].name)) {
        if (p == m_.robots[static_cast<std::size_t>(r)]) {
          out.push_back(v);
          break;
        }
      }
    }
    return out;
  }

  // Whether some variable names two robots of `robots`: then sorting whole robots is not enough.
  bool namesTwo(const std::vector<std::int32_t>& robots) const {
    for (const ir::Variable& v : m_.variables) {
      int count = 0;
      for (const std::string& p : components(v.name)) {
        auto it = robotIndex_.find(p);
        if (it != robotIndex_.end() && std::find(robots.begin(), robots.end(), it->second) != robots.end()) ++count;
      }
      if (count > 1) return true;
    }
    return false;
  }

  const ir::Model& m_;
  const SymmetryScope scope_;
  std::unordered_map<std::string, ir::VarId> byName_;
  std::unordered_map<std::string, std::int32_t> robotIndex_;

 private:
  // The invariants, properties and valid end by their forms' numbers: each must map to itself.
  std::vector<std::uint32_t> otherForms(const VarMap& map, bool add) {
    std::vector<std::uint32_t> out;
    if (scope_.invariants) {
      for (const ir::Invariant& inv : m_.invariants) out.push_back(forms_.of(inv.holds, map, add));
      if (m_.validEnd) out.push_back(forms_.of(*m_.validEnd, map, add));
    }
    if (scope_.properties) {
      for (const ir::Property& p : m_.properties) out.push_back(forms_.of(p.formula, map, add));
    } else if (scope_.property) {
      out.push_back(forms_.of(m_.properties.at(*scope_.property).formula, map, add));
    }
    return out;
  }

  static std::uint64_t key(std::uint32_t own, std::uint32_t sig) { return (static_cast<std::uint64_t>(own) << 32) | sig; }

  // The rules a swap may change (those reading or writing a variable it moves, and the rest of
  // their fairness groups), in index order, with the key (own text, group's texts) each has under
  // the swap. Nullopt when one of those texts is no rule's or no group's of the model: the swap is
  // then not a symmetry.
  struct Touched {
    std::vector<std::uint32_t> rules;
    std::vector<std::uint64_t> keys;
  };
  std::optional<Touched> touched(const VarMap& map) {
    ++stamp_;
    std::vector<std::uint32_t> affected, groups;
    for (ir::VarId v = 0; v < map.size(); ++v) {
      if (map[v] == v) continue;
      for (std::uint32_t r : users_[v]) {
        if (ruleStamp_[r] == stamp_) continue;
        ruleStamp_[r] = stamp_;
        affected.push_back(r);
        if (group_[r] != kNoGroup && groupStamp_[group_[r]] != stamp_) groupStamp_[group_[r]] = stamp_, groups.push_back(group_[r]);
      }
    }
    std::unordered_map<std::uint32_t, std::uint32_t> mappedOwn;  // of the affected rules
    for (std::uint32_t r : affected) {
      const std::optional<std::string> text = ruleText(m_.rules[r], map, forms_, false);
      if (!text) return std::nullopt;
      auto it = ownIds_.find(*text);
      if (it == ownIds_.end()) return std::nullopt;
      mappedOwn[r] = it->second;
    }
    auto ownOf = [&](std::uint32_t r) {
      auto it = mappedOwn.find(r);
      return it == mappedOwn.end() ? own_[r] : it->second;
    };
    std::unordered_map<std::uint32_t, std::uint32_t> mappedSig;  // of the groups of affected rules
    for (std::uint32_t g : groups) {
      std::vector<std::uint32_t> sig;
      for (std::uint32_t r : members_[g]) sig.push_back(ownOf(r));
      std::sort(sig.begin(), sig.end());
      auto it = sigIds_.find(sig);
      if (it == sigIds_.end()) return std::nullopt;
      mappedSig[g] = it->second;
      for (std::uint32_t r : members_[g]) ruleStamp_[r] = stamp_;  // the whole group is touched
    }
    Touched t;
    for (std::uint32_t r : affected) t.rules.push_back(r);
    for (std::uint32_t g : groups) {
      for (std::uint32_t r : members_[g]) t.rules.push_back(r);
    }
    std::sort(t.rules.begin(), t.rules.end());
    t.rules.erase(std::unique(t.rules.begin(), t.rules.end()), t.rules.end());
    for (std::uint32_t r : t.rules) t.keys.push_back(key(ownOf(r), group_[r] == kNoGroup ? kNoGroup : mappedSig.at(group_[r])));
    return t;
  }

  VarMap identity_;
  std::unordered_map<std::string, std::uint32_t> ownIds_;          // a rule's own text: its number
  std::map<std::vector<std::uint32_t>, std::uint32_t> sigIds_;      // a group's sorted rule numbers: its number
  std::vector<std::uint32_t> own_, group_, groupSig_;               // per rule, per rule, per group
  std::vector<std::vector<std::uint32_t>> members_, users_;         // per group, per variable: rules
  std::vector<std::uint64_t> ruleStamp_, groupStamp_;
  std::uint64_t stamp_ = 0;
  CanonTable forms_;
  std::vector<std::uint32_t> original_;
};

// Robots whose variables look alike (the same names after the robot's own, the same ranges).
std::vector<std::vector<std::int32_t>> lookalikes(const ir::Model& m, const Finder& f) {
  std::map<std::vector<std::string>, std::vector<std::int32_t>> bySignature;
  for (std::int32_t r = 0; r < static_cast<std::int32_t>(m.robots.size()); ++r) {
    std::vector<std::string> signature;
    for (ir::VarId v : f.varsOf(r)) {
      std::vector<std::string> parts = components(m.variables[v].name);
      for (std::string& p : parts) {
        if (p == m.robots[static_cast<std::size_t>(r)]) p = "*";
      }
      const ir::Variable& x = m.variables[v];
      signature.push_back(join(parts) + ":" + std::to_string(x.min) + ".." + std::to_string(x.max) + "=" + std::to_string(x.init));
    }
    if (signature.empty()) continue;
    std::sort(signature.begin(), signature.end());
    bySignature[signature].push_back(r);
  }
  std::vector<std::vector<std::int32_t>> out;
  for (auto& [signature, robots] : bySignature) {
    if (robots.size() > 1) out.push_back(robots);
  }
  return out;
}

}  // namespace

std::string canonicalText(const ir::Expr& e, const VarMap& map) { return canon(e, map); }

std::vector<ir::VarId> variablesOf(const ir::Rule& r) { return ruleVariables(r); }

std::vector<LookalikeClass> lookalikeClasses(const ir::Model& model) {
  std::unordered_map<std::string, std::int32_t> robotIndex;
  for (std::size_t r = 0; r < model.robots.size(); ++r) robotIndex.emplace(model.robots[r], static_cast<std::int32_t>(r));
  // Each variable that names one robot, by its name with the robot's left out, range and value.
  std::vector<std::vector<std::pair<std::string, ir::VarId>>> own(model.robots.size());
  for (ir::VarId v = 0; v < model.variables.size(); ++v) {
    std::vector<std::string> parts = components(model.variables[v].name);
    std::int32_t robot = -1;
    bool two = false;
    for (std::string& p : parts) {
      auto it = robotIndex.find(p);
      if (it == robotIndex.end()) continue;
      two = two || (robot >= 0 && robot != it->second);
      robot = it->second;
      p = "*";
    }
    if (robot < 0 || two) continue;
    const ir::Variable& x = model.variables[v];
    own[static_cast<std::size_t>(robot)].emplace_back(join(parts) + ":" + std::to_string(x.min) + ".." + std::to_string(x.max) + "=" + std::to_string(x.init), v);
  }
  std::map<std::vector<std::string>, std::size_t> bySignature;
  std::vector<LookalikeClass> classes;
  for (std::size_t r = 0; r < own.size(); ++r) {
    if (own[r].empty()) continue;
    std::sort(own[r].begin(), own[r].end());
    std::vector<std::string> signature;
    std::vector<ir::VarId> block;
    for (auto& [key, v] : own[r]) signature.push_back(std::move(key)), block.push_back(v);
    auto [it, added] = bySignature.emplace(std::move(signature), classes.size());
    if (added) classes.emplace_back();
    classes[it->second].robots.push_back(static_cast<std::int32_t>(r));
    classes[it->second].blocks.push_back(std::move(block));
  }
  std::erase_if(classes, [](const LookalikeClass& c) { return c.robots.size() < 2; });
  return classes;
}

std::vector<FoundClass> findClasses(const ir::Model& model, const SymmetryScope& scope) {
  std::vector<FoundClass> out;
  if (model.robots.size() < 2) return out;
  Finder f(model, scope);
  for (const std::vector<std::int32_t>& candidates : lookalikes(model, f)) {
    // Star transpositions (first r) generate the symmetric group of a class: a robot joins the
    // first class whose first member it can be swapped with.
    std::vector<std::vector<std::int32_t>> classes;
    for (std::int32_t r : candidates) {
      bool placed = false;
      for (std::vector<std::int32_t>& c : classes) {
        if (f.symmetric(c.front(), r)) {
          c.push_back(r);
          placed = true;
          break;
        }
      }
      if (!placed) classes.push_back({r});
    }
    for (std::vector<std::int32_t>& robots : classes) {
      if (robots.size() < 2 || f.namesTwo(robots)) continue;
      FoundClass c;
      c.robots = robots;
      c.blocks.push_back(f.varsOf(robots.front()));
      for (std::size_t i = 1; i < robots.size(); ++i) {
        VarMap map = *f.swap(robots.front(), robots[i]);
        std::vector<ir::VarId> block;
        for (ir::VarId v : c.blocks.front()) block.push_back(map[v]);
        c.blocks.push_back(std::move(block));
        c.ruleMaps.push_back(f.ruleMap(map));
        c.variableMaps.push_back(std::move(map));
      }
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace semo::checker::detail
