#pragma once
// How likely and how soon: the IR read as a Markov decision process. Each reachable state offers
// one action per enabled rule (the interleaving: which robot moves is a scheduler's choice), and an
// action leads to its outcomes with their probabilities (ir::Branch). A state where no rule is
// enabled stays where it is (a run that ends stays in its last state). When every reachable state
// offers at most one action the model is a Markov chain and answers are exact up to floating
// point (sparse LU); otherwise they are the minimum and maximum over all schedulers, by value
// iteration. specs/quantitative.md gives the definitions and the published models the tests
// reproduce.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct MarkovModel {
  std::vector<std::vector<std::int32_t>> states;  // index 0: the initial state
  // State s offers the actions [actionStart[s], actionStart[s + 1]); action a is a step of rule
  // actionRule[a] and leads to successor[k] with probability[k] for k in
  // [outcomeStart[a], outcomeStart[a + 1]) (outcomes leading to one state are merged).
  std::vector<std::uint32_t> actionStart, actionRule, outcomeStart, successor;
  std::vector<double> probability;

  [[nodiscard]] std::size_t size() const { return states.size(); }
  [[nodiscard]] std::size_t actions() const { return actionRule.size(); }
  // Every state offers at most one action: a Markov chain (no scheduler to range over).
  [[nodiscard]] bool deterministic() const;
};

struct MarkovLimits {
  std::size_t maxStates = 5'000'000;
};

// A model too large for the limits (limitReached), or a step that leaves a declared range.
struct MarkovError : std::runtime_error {
  explicit MarkovError(const std::string& what, bool limit = false, bool states = false)
      : std::runtime_error(what), limitReached(limit), tooManyStates(states) {}
  bool limitReached = false;
  bool tooManyStates = false;  // the limit reached is MarkovLimits::maxStates (simulated runs may still answer)
};

// The reachable states and their actions, breadth-first from the initial state.
MarkovModel buildMarkovModel(const ir::Model& model, const MarkovLimits& limits = {});

// Per state: whether `condition` (an expression of the model) holds.
std::vector<char> statesWhere(const MarkovModel& m, const ir::Expr& condition);

enum class Optimum { Min, Max };

// P(target reached within t steps) from the initial state, for t = 0 .. horizon. A horizon beyond
// 10,000,000 steps or 5e9 transition visits is a MarkovError (limitReached), not a long wait.
std::vector<double> boundedReachability(const MarkovModel& m, const std::vector<char>& target, std::size_t horizon,
                                        Optimum optimum = Optimum::Max);

struct QuantitativeResult {
  double value = 0;
  bool infinite = false;  // an expectation: the target is missed with positive probability
  // The true value lies in [lower, upper]: both equal `value` for an exact answer; an interval
  // iteration's bounds; a value iteration from below gives lower = value and upper = infinity.
  double lower = 0, upper = 0;
  std::string method;  // how it was computed, and to what precision
};

// P(target eventually reached) from the initial state. On an MDP by interval iteration: a lower
// and an upper bound iterated until they are within `precision` of each other (the end components
// collapsed for Max, so that the upper bound converges); the answer is their midpoint.
QuantitativeResult reachability(const MarkovModel& m, const std::vector<char>& target, Optimum optimum = Optimum::Max,
                                double precision = 1e-9);

// The maximal end components among the states `within` marks: per state, its component's number
// (-1 for none). A component is a set of states and actions that a scheduler can keep to for ever
// with probability 1, each state reaching every other; a state with a self-loop action is one.
std::vector<std::int64_t> maximalEndComponents(const MarkovModel& m, const std::vector<char>& within);

// The expected total reward until the target is reached, a step of rule r earning rewardOfRule[r]
// (for example 1 for every rule: the expected number of steps). Infinite where the target is
// missed with positive probability (for Min: under every scheduler; for Max: under some).
QuantitativeResult expectedReward(const MarkovModel& m, const std::vector<char>& target, const std::vector<double>& rewardOfRule,
                                  Optimum optimum = Optimum::Min);

}  // namespace semo::checker
