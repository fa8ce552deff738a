#include "semo/checker/symmetry.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "symmetry_finder.hpp"

namespace semo::checker {

Symmetry Symmetry::find(const ir::Model& model, const SymmetryScope& scope) {
  Symmetry s;
  if (model.robots.size() < 2) return s;
  std::vector<Swap> swaps;
  for (detail::FoundClass& found : detail::findClasses(model, scope)) {
    Class c;
    c.robots = std::move(found.robots);
    c.blocks = std::move(found.blocks);
    c.firstSlot = s.slots_;
    c.firstSwap = swaps.size();
    for (std::size_t i = 0; i < found.variableMaps.size(); ++i) swaps.push_back({std::move(found.variableMaps[i]), std::move(found.ruleMaps[i])});
    s.slots_ += c.robots.size();
    s.classes_.push_back(std::move(c));
  }
  s.swaps_ = std::make_shared<const std::vector<Swap>>(std::move(swaps));
  if (s.classes_.empty()) return s;
  auto touch = std::make_shared<Touch>();
  std::vector<std::uint32_t> slotOf(model.variables.size(), UINT32_MAX);
  for (std::uint32_t c = 0; c < s.classes_.size(); ++c) {
    const Class& k = s.classes_[c];
    for (std::uint32_t p = 0; p < k.robots.size(); ++p) {
      for (ir::VarId v : k.blocks[p]) slotOf[v] = static_cast<std::uint32_t>(k.firstSlot + p);
      touch->slotClass.push_back(c);
      touch->slotPosition.push_back(p);
    }
  }
  touch->start.push_back(0);
  for (const ir::Rule& r : model.rules) {
    std::vector<std::uint32_t> slots;
    for (ir::VarId v : detail::variablesOf(r)) {
      if (slotOf[v] != UINT32_MAX) slots.push_back(slotOf[v]);
    }
    std::sort(slots.begin(), slots.end());
    slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
    touch->slots.insert(touch->slots.end(), slots.begin(), slots.end());
    touch->start.push_back(static_cast<std::uint32_t>(touch->slots.size()));
  }
  touch->rulesOf.resize(s.slots_);
  for (std::uint32_t r = 0; r + 1 < touch->start.size(); ++r) {
    for (std::uint32_t k = touch->start[r]; k < touch->start[r + 1]; ++k) touch->rulesOf[touch->slots[k]].push_back(r);
  }
  // The swaps of neighbours, which the safety search asks for per candidate rule (Symmetry::redundant).
  std::size_t neighbours = 0;
  for (const Class& k : s.classes_) neighbours += k.robots.size() - 1;
  if (neighbours * model.rules.size() * sizeof(std::uint32_t) <= (std::size_t{256} << 20)) {
    s.touch_ = touch;  // swappedWithPrevious composes generators until the tables are filled
    touch->withPrevious.resize(s.slots_);
    for (const Class& k : s.classes_) {
      for (std::size_t p = 1; p < k.robots.size(); ++p) {
        std::vector<std::uint32_t> map(model.rules.size());
        for (std::uint32_t r = 0; r < map.size(); ++r) map[r] = s.swappedWithPrevious(r, k.firstSlot + p);
        touch->withPrevious[k.firstSlot + p] = std::move(map);
      }
    }
  }
  s.touch_ = std::move(touch);
  return s;
}

bool Symmetry::equalNeighbours(const Value* values, std::vector<char>& equal) const {
  equal.assign(slots_, 0);
  bool any = false;
  for (const Class& c : classes_) {
    for (std::size_t p = 1; p < c.robots.size(); ++p) {
      const std::vector<ir::VarId>& a = c.blocks[p - 1];
      const std::vector<ir::VarId>& b = c.blocks[p];
      bool same = true;
      for (std::size_t j = 0; j < a.size() && same; ++j) same = values[a[j]] == values[b[j]];
      if (same) equal[c.firstSlot + p] = 1, any = true;
    }
  }
  return any;
}

const std::vector<std::uint32_t>& Symmetry::rulesTouching(std::size_t slot) const { return touch_->rulesOf[slot]; }

std::uint32_t Symmetry::swappedWithPrevious(std::uint32_t rule, std::size_t slot) const {
  if (slot < touch_->withPrevious.size() && !touch_->withPrevious[slot].empty()) return touch_->withPrevious[slot][rule];
  const Class& c = classes_[touch_->slotClass[slot]];
  const std::size_t b = touch_->slotPosition[slot], a = b - 1;
  // The generators swap position 0 with position i; (a b) is (0 a)(0 b)(0 a), or (0 b) for a = 0.
  auto star = [&](std::size_t i, std::uint32_t r) { return (*swaps_)[c.firstSwap + i - 1].rules[r]; };
  return a == 0 ? star(b, rule) : star(a, star(b, star(a, rule)));
}

bool Symmetry::redundant(std::uint32_t rule, const std::vector<char>& equal, std::uint32_t& lower) const {
  for (std::uint32_t k = touch_->start[rule]; k < touch_->start[rule + 1]; ++k) {
    const std::uint32_t slot = touch_->slots[k];
    // The swaps with the slot before and with the slot after, where those robots are equal.
    for (const std::size_t s : {static_cast<std::size_t>(slot), static_cast<std::size_t>(slot) + 1}) {
      if (s >= slots_ || equal[s] == 0 || touch_->slotClass[s] != touch_->slotClass[slot]) continue;
      const std::uint32_t image = swappedWithPrevious(rule, s);
      if (image < rule) {
        lower = image;
        return true;
      }
    }
  }
  return false;
}

std::vector<std::string> Symmetry::describe(const ir::Model& model) const {
  std::vector<std::string> out;
  for (const Class& c : classes_) {
    std::string line;
    for (std::size_t i = 0; i < c.robots.size(); ++i) line += (line.empty() ? "" : " ") + model.robots[static_cast<std::size_t>(c.robots[i])];
    // k! exactly while it fits in 64 bits (k <= 20), else as a power of ten.
    const std::size_t k = c.robots.size();
    std::string orderings;
    if (k <= 20) {
      std::uint64_t n = 1;
      for (std::size_t i = 2; i <= k; ++i) n *= i;
      orderings = std::to_string(n);
    } else {
      const double digits = std::lgamma(static_cast<double>(k) + 1) / std::log(10.0);
      const double exponent = std::floor(digits);
      orderings = fmt::format("{:.1f}e{}", std::pow(10.0, digits - exponent), static_cast<long long>(exponent));
    }
    out.push_back(line + " (" + std::to_string(k) + "! = " + orderings + " orderings)");
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
    // Each robot's values side by side (the comparisons then read one array), and the robots
    // sorted by them with a stable insertion sort: a successor of a canonical state differs from
    // it in one or two robots, so this costs about k comparisons where a general sort pays
    // k log k; and robots with equal values keep their order, so the permutation that canonicalises
    // moves as few robots as it must (fewer distinct permutations for the liveness product).
    scratch_.resize(k * width);
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t j = 0; j < width; ++j) scratch_[i * width + j] = values[c.blocks[i][j]];
    }
    const Value* key = scratch_.data();
    auto less = [key, width](std::size_t a, std::size_t b) {
      const Value* x = key + a * width;
      const Value* y = key + b * width;
      for (std::size_t j = 0; j < width; ++j) {
        if (x[j] != y[j]) return x[j] < y[j];
      }
      return false;
    };
    order_.resize(k);
    bool sorted = true;
    for (std::size_t i = 0; i < k; ++i) {
      order_[i] = i;
      if (i > 0 && less(i, i - 1)) sorted = false;
    }
    if (sorted) continue;
    for (std::size_t i = 1; i < k; ++i) {
      const std::size_t robot = order_[i];
      std::size_t at = i;
      while (at > 0 && less(robot, order_[at - 1])) {
        order_[at] = order_[at - 1];
        --at;
      }
      order_[at] = robot;
    }
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t j = 0; j < width; ++j) values[c.blocks[i][j]] = key[order_[i] * width + j];
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
  std::vector<ir::VarId> identity(any.size());
  for (ir::VarId v = 0; v < identity.size(); ++v) identity[v] = v;
  const std::string original = detail::canonicalText(e, identity);
  return std::all_of(swaps_->begin(), swaps_->end(), [&](const Swap& s) { return detail::canonicalText(e, s.variables) == original; });
}

}  // namespace semo::checker
