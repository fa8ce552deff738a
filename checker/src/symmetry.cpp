#include "semo/checker/symmetry.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <unordered_map>

namespace semo::checker {

namespace {

using ir::Expr;
using ir::Op;
using VarMap = std::vector<ir::VarId>;  // a permutation of the variables

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

std::string canon(const ir::Ltl& f, const VarMap& map) {
  if (f.kind == ir::Ltl::Kind::Atom) return canon(f.atom, map);
  std::vector<std::string> parts;
  for (const ir::Ltl& a : f.args) parts.push_back(canon(a, map));
  if (f.kind == ir::Ltl::Kind::And || f.kind == ir::Ltl::Kind::Or) std::sort(parts.begin(), parts.end());
  std::string out = std::string("[") + ir::ltlKeyword(f.kind);
  for (const std::string& p : parts) out += " " + p;
  return out + "]";
}

std::string canon(const ir::Rule& r, const VarMap& map) {
  std::vector<std::string> branches;
  for (const ir::Branch& b : r.branches) {
    std::vector<std::string> updates;
    for (const ir::Assignment& a : b.assignments) updates.push_back("v" + std::to_string(map[a.var]) + ":=" + canon(a.value, map));
    std::sort(updates.begin(), updates.end());
    std::string text = std::to_string(b.probability);
    for (const std::string& u : updates) text += ";" + u;
    branches.push_back(std::move(text));
  }
  std::sort(branches.begin(), branches.end());
  std::string out = std::to_string(static_cast<int>(r.kind)) + (r.weaklyFair ? "w" : "") + (r.stronglyFair ? "s" : "") + "|" +
                    canon(r.guard, map);
  // Where it senses, without the robot (a place in the program, the same for every robot of a type).
  for (const ir::SensedOutcome& s : r.sensed) out += "|?" + s.point.substr(s.point.find('.') + 1) + (s.holds ? "+" : "-");
  for (const std::string& b : branches) out += "|" + b;
  return out;
}

// Every rule's text, with the texts of the rules of its fairness group (sorted): a swap must map
// the groups onto groups, as fairness is per group.
std::vector<std::string> ruleTexts(const ir::Model& m, const VarMap& map) {
  std::vector<std::string> own;
  for (const ir::Rule& r : m.rules) own.push_back(canon(r, map));
  std::unordered_map<std::string, std::vector<std::string>> groups;
  for (std::size_t r = 0; r < m.rules.size(); ++r) {
    if (!m.rules[r].fairGroup.empty()) groups[m.rules[r].fairGroup].push_back(own[r]);
  }
  std::unordered_map<std::string, std::string> signature;
  for (auto& [name, texts] : groups) {
    std::sort(texts.begin(), texts.end());
    std::string sig = "{";
    for (const std::string& t : texts) sig += t + ";";
    signature[name] = sig + "}";
  }
  std::vector<std::string> out;
  for (std::size_t r = 0; r < m.rules.size(); ++r) {
    out.push_back(m.rules[r].fairGroup.empty() ? own[r] : own[r] + "|g" + signature[m.rules[r].fairGroup]);
  }
  return out;
}

// Everything the search and the verdicts depend on, as texts; per item, so that each invariant
// and property must map to itself.
struct ModelText {
  std::vector<std::string> rules;  // sorted: the rule set as a multiset
  std::vector<std::string> invariants, properties;
  std::string validEnd;
};

ModelText text(const ir::Model& m, const VarMap& map) {
  ModelText t;
  t.rules = ruleTexts(m, map);
  std::sort(t.rules.begin(), t.rules.end());
  for (const ir::Invariant& inv : m.invariants) t.invariants.push_back(canon(inv.holds, map));
  for (const ir::Property& p : m.properties) t.properties.push_back(canon(p.formula, map));
  if (m.validEnd) t.validEnd = canon(*m.validEnd, map);
  return t;
}

bool operator==(const ModelText& a, const ModelText& b) {
  return a.rules == b.rules && a.invariants == b.invariants && a.properties == b.properties && a.validEnd == b.validEnd;
}

class Finder {
 public:
  explicit Finder(const ir::Model& m) : m_(m) {
    for (ir::VarId v = 0; v < m.variables.size(); ++v) byName_[m.variables[v].name] = v;
    for (std::size_t r = 0; r < m.robots.size(); ++r) robotIndex_[m.robots[r]] = static_cast<std::int32_t>(r);
    VarMap identity(m.variables.size());
    for (ir::VarId v = 0; v < identity.size(); ++v) identity[v] = v;
    original_ = text(m, identity);
    std::vector<std::string> texts = ruleTexts(m, identity);
    for (std::uint32_t r = 0; r < m.rules.size(); ++r) ruleIndex_[texts[r]].push_back(r);
  }

  // What a verified swap does to the rules: rule r becomes rules[r]. Rules with the same text are
  // paired off in order, so the map is a bijection.
  std::vector<std::uint32_t> ruleMap(const VarMap& map) const {
    std::unordered_map<std::string, std::size_t> used;
    std::vector<std::uint32_t> out(m_.rules.size());
    const std::vector<std::string> texts = ruleTexts(m_, map);
    for (std::uint32_t r = 0; r < m_.rules.size(); ++r) {
      const std::string& t = texts[r];
      out[r] = ruleIndex_.at(t).at(used[t]++);
    }
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

  bool symmetric(std::int32_t a, std::int32_t b) const {
    std::optional<VarMap> map = swap(a, b);
    return map && text(m_, *map) == original_;
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
  std::unordered_map<std::string, ir::VarId> byName_;
  std::unordered_map<std::string, std::int32_t> robotIndex_;
  ModelText original_;
  std::unordered_map<std::string, std::vector<std::uint32_t>> ruleIndex_;  // by text: the rules
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

Symmetry Symmetry::find(const ir::Model& model) {
  Symmetry s;
  if (model.robots.size() < 2) return s;
  Finder f(model);
  std::vector<Swap> swaps;
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
      Class c;
      c.robots = robots;
      c.firstSlot = s.slots_;
      c.firstSwap = swaps.size();
      c.blocks.push_back(f.varsOf(robots.front()));
      for (std::size_t i = 1; i < robots.size(); ++i) {
        VarMap map = *f.swap(robots.front(), robots[i]);
        std::vector<ir::VarId> block;
        for (ir::VarId v : c.blocks.front()) block.push_back(map[v]);
        c.blocks.push_back(std::move(block));
        swaps.push_back({map, f.ruleMap(map)});
      }
      s.slots_ += robots.size();
      s.classes_.push_back(std::move(c));
    }
  }
  s.swaps_ = std::make_shared<const std::vector<Swap>>(std::move(swaps));
  return s;
}

std::vector<std::string> Symmetry::describe(const ir::Model& model) const {
  std::vector<std::string> out;
  for (const Class& c : classes_) {
    std::string line;
    std::uint64_t orderings = 1;
    for (std::size_t i = 0; i < c.robots.size(); ++i) {
      line += (line.empty() ? "" : " ") + model.robots[static_cast<std::size_t>(c.robots[i])];
      orderings *= i + 1;
    }
    out.push_back(line + " (" + std::to_string(c.robots.size()) + "! = " + std::to_string(orderings) + " orderings)");
  }
  return out;
}

void Symmetry::canonicalize(Value* values) const { canonicalize(values, nullptr); }

void Symmetry::canonicalize(Value* values, Permutation& moved) const {
  moved.resize(slots_);
  for (std::size_t i = 0; i < slots_; ++i) moved[i] = static_cast<std::uint16_t>(i);
  canonicalize(values, &moved);
}

void Symmetry::canonicalize(Value* values, Permutation* moved) const {
  for (const Class& c : classes_) {
    const std::size_t k = c.robots.size(), width = c.blocks.front().size();
    order_.resize(k);
    for (std::size_t i = 0; i < k; ++i) order_[i] = i;
    auto less = [&](std::size_t a, std::size_t b) {
      for (std::size_t j = 0; j < width; ++j) {
        Value x = values[c.blocks[a][j]], y = values[c.blocks[b][j]];
        if (x != y) return x < y;
      }
      return false;
    };
    if (std::is_sorted(order_.begin(), order_.end(), less)) continue;
    std::sort(order_.begin(), order_.end(), less);
    scratch_.resize(k * width);
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t j = 0; j < width; ++j) scratch_[i * width + j] = values[c.blocks[order_[i]][j]];
    }
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t j = 0; j < width; ++j) values[c.blocks[i][j]] = scratch_[i * width + j];
    }
    // The robot found at position order_[i] now sits at position i.
    if (moved != nullptr) {
      for (std::size_t i = 0; i < k; ++i) (*moved)[c.firstSlot + order_[i]] = static_cast<std::uint16_t>(c.firstSlot + i);
    }
  }
}

Symmetry::Swaps Symmetry::decompose(const Permutation& p) const {
  // A cycle a1 -> a2 -> ... -> am is the swaps (a1 a2), (a1 a3), ..., (a1 am), applied in that
  // order; a swap of two positions other than the first is (0 a)(0 b)(0 a).
  Swaps out;
  std::vector<char> done(p.size(), 0);
  for (const Class& c : classes_) {
    auto star = [&](std::size_t position) { out.push_back(static_cast<std::uint32_t>(c.firstSwap + position - 1)); };
    auto transpose = [&](std::size_t a, std::size_t b) {
      if (a == 0) star(b);
      else if (b == 0) star(a);
      else star(a), star(b), star(a);
    };
    for (std::size_t i = 0; i < c.robots.size(); ++i) {
      std::size_t start = c.firstSlot + i;
      if (done[start]) continue;
      done[start] = 1;
      for (std::size_t next = p[start]; next != start; next = p[next]) {
        done[next] = 1;
        transpose(start - c.firstSlot, next - c.firstSlot);
      }
    }
  }
  return out;
}

std::uint32_t Symmetry::image(std::uint32_t rule, const Swaps& swaps) const {
  for (std::uint32_t s : swaps) rule = (*swaps_)[s].rules[rule];
  return rule;
}

bool Symmetry::invariant(const ir::Expr& e) const {
  if (classes_.empty()) return true;
  const std::vector<ir::VarId>& any = swaps_->front().variables;
  VarMap identity(any.size());
  for (ir::VarId v = 0; v < identity.size(); ++v) identity[v] = v;
  const std::string original = canon(e, identity);
  return std::all_of(swaps_->begin(), swaps_->end(), [&](const Swap& s) { return canon(e, s.variables) == original; });
}

}  // namespace semo::checker
