#pragma once
// Symmetry reduction over interchangeable robots. Robots are interchangeable when swapping their
// variables (by name: `burger_0.mode` <-> `burger_1.mode`, ...) maps the model onto itself: every
// rule to a rule, every invariant, property and valid_end to itself. semo does not trust the
// translation for this: it checks each swap on the IR itself (with commutative operators
// compared in any order), and swaps that generate the whole symmetric group of a class suffice.
// The search then stores one state per orbit: the robots of a class sorted by their values.
#include <string>
#include <vector>

#include "semo/checker/compiled_model.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

class Symmetry {
 public:
  Symmetry() = default;
  // The interchangeable robots of `model` (none when it has no symmetry, or `enabled` is false).
  static Symmetry find(const ir::Model& model);

  [[nodiscard]] bool empty() const { return classes_.empty(); }
  // One line per class for the report: "burger_0 burger_1 burger_2 (3! = 6 orderings)".
  [[nodiscard]] std::vector<std::string> describe(const ir::Model& model) const;
  // Rewrites `values` into the representative of its orbit.
  void canonicalize(Value* values) const;

 private:
  struct Class {
    std::vector<std::int32_t> robots;
    std::vector<std::vector<ir::VarId>> blocks;  // blocks[i][j]: the j-th variable of robots[i]
  };
  std::vector<Class> classes_;
  mutable std::vector<Value> scratch_;
  mutable std::vector<std::size_t> order_;
};

}  // namespace semo::checker
