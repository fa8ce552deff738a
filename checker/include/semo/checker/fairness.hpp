#pragma once
// The fairness constraints of a model, one per group of rules (specs/ir.md, "Fairness groups"):
// a weakly fair group that is enabled (some rule of it is) in every state from some point on has
// some rule of it taken again and again; a strongly fair group (one strongly fair rule) enabled
// again and again is taken again and again. A weakly fair rule without a group is a group alone.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct Fairness {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> groupOf;              // per rule: its group, or kNone (not fair)
  std::vector<std::vector<std::uint32_t>> members;  // per group: its rules, ascending
  std::vector<char> strong;                         // per group

  static Fairness of(const ir::Model& model);
  [[nodiscard]] std::size_t groups() const { return members.size(); }
};

// The sensed conditions of a model (ir::Rule::sensed), numbered: what a settling world
// (ir::Property::settled) constrains. A loop of a run on a settling world decides each of them one
// way only.
struct Sensing {
  struct Decision {
    std::uint32_t point;
    bool holds;
  };
  std::vector<std::vector<Decision>> of;  // per rule
  std::size_t points = 0;
  std::vector<std::string> names;         // per point: its name (ir::SensedOutcome::point)

  static Sensing in(const ir::Model& model);
  // Whether a rule's decisions agree with `allowed` (per point: -1 either way, 0 or 1 that way).
  [[nodiscard]] bool agrees(std::uint32_t rule, const std::vector<std::int8_t>& allowed) const {
    for (const Decision& d : of[rule]) {
      if (allowed[d.point] >= 0 && allowed[d.point] != static_cast<std::int8_t>(d.holds)) return false;
    }
    return true;
  }
};

}  // namespace semo::checker
