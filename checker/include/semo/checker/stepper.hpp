#pragma once
// Stepping through a model one rule at a time: the initial state, which rules are enabled, what a
// rule leads to, whether a state violates an invariant or is a deadlock. It evaluates with the
// explicit checker's compiled model (compiled_model.hpp), so a step here is exactly a step of the
// search; for replaying counterexamples (trace_reader.hpp), simulators and tests.
//
// A state is one plain int32 per IR variable, in the order of ir::Model::variables (the checker
// packs states into bits internally; a Stepper never does). Rules are indexed as in
// ir::Model::rules. A rule may have several outcomes (ir::Branch: a probabilistic choice, written
// by hand in IR files; translated missions give every rule one): `successor(s, rule)` is for rules
// with one outcome, `successor(s, {rule, branch})` chooses among several. Each outcome is a set of
// simultaneous assignments (every right-hand side reads the old state; the IR assigns a variable at
// most once per outcome).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

class Stepper {
 public:
  using State = std::vector<std::int32_t>;  // one value per IR variable, IR order

  // A rule and one of its outcomes (ir::Rule::branches).
  struct Choice {
    std::size_t rule = 0;
    std::size_t branch = 0;
    bool operator==(const Choice&) const = default;
  };

  // What an outcome does to a state, out-of-range values included (`state` then holds them).
  struct Outcome {
    bool enabled = false;             // the rule's guard holds
    State state;                      // the state after it (empty when not enabled)
    std::vector<ir::VarId> outOfRange;  // the variables it sets outside their declared range
    std::string message;              // why there is no successor, if there is none
  };

  // Compiles the model once. The Stepper keeps its own copy of the model.
  explicit Stepper(const ir::Model& model);
  ~Stepper();
  Stepper(Stepper&&) noexcept;
  Stepper& operator=(Stepper&&) noexcept;

  [[nodiscard]] const ir::Model& model() const;
  [[nodiscard]] std::size_t branches(std::size_t rule) const;  // how many outcomes the rule has

  [[nodiscard]] State initial() const;
  // A state's size must be the number of variables (std::invalid_argument otherwise); a rule or
  // branch index out of bounds is std::out_of_range. Values outside their ranges are accepted.
  [[nodiscard]] bool enabled(const State& s, std::size_t rule) const;
  [[nodiscard]] std::vector<std::size_t> enabledRules(const State& s) const;  // ascending

  // The state after the rule's only outcome; nullopt when the rule is not enabled, when an
  // assignment leaves its variable's range, or when the rule has several outcomes (choose one
  // with the overload below). `why` (if given) then says which.
  [[nodiscard]] std::optional<State> successor(const State& s, std::size_t rule, std::string* why = nullptr) const;
  [[nodiscard]] std::optional<State> successor(const State& s, Choice choice, std::string* why = nullptr) const;
  [[nodiscard]] Outcome apply(const State& s, Choice choice) const;
  // Every successor the explicit search generates from `s` (without symmetry reduction): per
  // enabled rule in rule order, per outcome, those within range.
  [[nodiscard]] std::vector<std::pair<Choice, State>> successors(const State& s) const;

  // An enabled rule (lowest index; for it, its lowest outcome) that leads from `from` to exactly `to`.
  [[nodiscard]] std::optional<std::size_t> findRule(const State& from, const State& to) const;
  [[nodiscard]] std::optional<Choice> findChoice(const State& from, const State& to) const;

  // Whether invariant `property` (an index into ir::Model::invariants) holds in `s`.
  [[nodiscard]] bool invariantHolds(const State& s, std::size_t property) const;
  // The model's valid_end; true in every state when the model has none.
  [[nodiscard]] bool validEnd(const State& s) const;
  // As deadlock_freedom is checked: no rule enabled and not a valid end. Never, without valid_end.
  [[nodiscard]] bool deadlocked(const State& s) const;

  // "a=1, b=true, pc=idle": every variable, values as traces show them (value names, booleans).
  [[nodiscard]] std::string describe(const State& s) const;
  // "b: false -> true, pc: idle -> busy": only the variables that differ ("" when none do).
  [[nodiscard]] std::string describeDifference(const State& a, const State& b) const;

 private:
  struct Impl;
  std::unique_ptr<const Impl> impl_;
  void checkState(const State& s) const;
};

}  // namespace semo::checker
