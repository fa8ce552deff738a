#pragma once
// Symmetry reduction over interchangeable robots. Robots are interchangeable when swapping their
// variables (by name: `burger_0.mode` <-> `burger_1.mode`, ...) maps the model onto itself: every
// rule to a rule, every invariant, property and valid_end to itself. semo does not trust the
// translation for this: it checks each swap on the IR itself (with commutative operators
// compared in any order), and swaps that generate the whole symmetric group of a class suffice.
// The search then stores one state per orbit: the robots of a class sorted by their values.
//
// The liveness engine also needs to know *how* a state was permuted, and what the rules become
// under a permutation (fairness is per rule): `canonicalize` can report the permutation, and
// `image` maps a rule through one, as a product of the verified swaps.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "semo/checker/compiled_model.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

// What a symmetry must leave as it is besides the rules and their fairness: by default everything
// the model says (its invariants, LTL properties and valid end); a safety search needs only the
// invariants and the valid end, one LTL property's product only that property. The fewer of them,
// the more robots may be interchangeable (the swarm's all_turn_back names legged_0).
struct SymmetryScope {
  bool invariants = true;     // the invariants and the valid end
  bool properties = true;     // every LTL property
  std::optional<std::size_t> property;  // this LTL property (with `properties` false)
  static SymmetryScope safety() { return {true, false, std::nullopt}; }
  static SymmetryScope liveness(std::size_t p) { return {false, false, p}; }
};

class Symmetry {
 public:
  Symmetry() = default;
  // The interchangeable robots of `model` (none when it has no symmetry), for what `scope` names.
  static Symmetry find(const ir::Model& model, const SymmetryScope& scope = {});

  [[nodiscard]] bool empty() const { return classes_.empty(); }
  // One line per class for the report: "burger_0 burger_1 burger_2 (3! = 6 orderings)".
  [[nodiscard]] std::vector<std::string> describe(const ir::Model& model) const;
  // Rewrites `values` into the representative of its orbit.
  void canonicalize(Value* values) const;

  // Slots number the robots of the classes, class by class. A permutation maps each slot to the
  // slot its robot's values move to.
  using Permutation = std::vector<std::uint16_t>;
  // The swaps (generator numbers) whose product, first applied first, is a permutation.
  using Swaps = std::vector<std::uint32_t>;
  [[nodiscard]] std::size_t slots() const { return slots_; }
  // As above, and `moved` is the permutation that was applied.
  void canonicalize(Value* values, Permutation& moved) const;
  [[nodiscard]] Swaps decompose(const Permutation& p) const;
  // The rule `rule` becomes when the robots are permuted by the product of `swaps`.
  [[nodiscard]] std::uint32_t image(std::uint32_t rule, const Swaps& swaps) const;
  // Whether every permutation leaves the value of `e` unchanged (e.g. a property's atom).
  [[nodiscard]] bool invariant(const ir::Expr& e) const;

  // For expanding a canonical state: two robots of a class in neighbouring positions with equal
  // values can be swapped without changing the state, so a rule and its image under that swap
  // lead to the same canonical successors. `equalNeighbours` marks, per slot, whether its robot's
  // values equal those of the slot before it in its class (false when no slot is so marked, the
  // usual case in a small team). `redundant` says whether such a swap maps `rule` to a lower rule
  // (`lower`), whose successors the search has then already generated from this state: the rule
  // with the lowest number of each orbit of the stabiliser is never redundant, so no successor is
  // lost, and the expansion of a swarm's state costs its distinct robots, not all of them.
  bool equalNeighbours(const Value* values, std::vector<char>& equal) const;
  [[nodiscard]] bool redundant(std::uint32_t rule, const std::vector<char>& equal, std::uint32_t& lower) const;
  // The rule under the swap of the robots in slot `slot` and the slot before it (same class), and
  // the rules that read or write the variables of the robot in `slot` (the others it leaves alone).
  [[nodiscard]] std::uint32_t swappedWithPrevious(std::uint32_t rule, std::size_t slot) const;
  [[nodiscard]] const std::vector<std::uint32_t>& rulesTouching(std::size_t slot) const;

 private:
  struct Class {
    std::vector<std::int32_t> robots;
    std::vector<std::vector<ir::VarId>> blocks;  // blocks[i][j]: the j-th variable of robots[i]
    std::size_t firstSlot = 0, firstSwap = 0;
  };
  // Per generator (the swap of a class's first robot with its i-th, i >= 1): what it does to the
  // variables and to the rules. Shared: the engines copy a Symmetry per thread.
  struct Swap {
    std::vector<ir::VarId> variables;
    std::vector<std::uint32_t> rules;
  };
  void canonicalize(Value* values, Permutation* moved) const;

  // Per rule, the slots of the robots whose variables it reads or writes (rules[start[r] ..
  // start[r + 1]]); per slot, its class and position. Shared, as the swaps.
  struct Touch {
    std::vector<std::uint32_t> start, slots;
    std::vector<std::uint32_t> slotClass, slotPosition;
    // Per slot, the rules under the swap with the slot before (rules.size() entries per slot, the
    // first slot of a class empty): one lookup where composing generators takes three. Left empty
    // when it would take more than 256 MB (then composed).
    std::vector<std::vector<std::uint32_t>> withPrevious;
    std::vector<std::vector<std::uint32_t>> rulesOf;  // per slot: the rules with it among their slots
  };
  std::vector<Class> classes_;
  std::shared_ptr<const std::vector<Swap>> swaps_;
  std::shared_ptr<const Touch> touch_;
  std::size_t slots_ = 0;
  mutable std::vector<Value> scratch_;
  mutable std::vector<std::size_t> order_;
};

}  // namespace semo::checker
