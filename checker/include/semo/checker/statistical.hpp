#pragma once
// Estimates from simulated runs, for models whose reachable states do not fit the quantitative
// engine (markov.hpp). Runs of the IR itself (the Stepper's steps, so a step is the search's step),
// each outcome drawn with its probability; where several rules are enabled, one is drawn uniformly
// (a scheduler of its own, neither the minimum nor the maximum: the answer says when this
// happened). Never exact: every figure comes with its confidence band. specs/quantitative.md.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct SamplingOptions {
  std::size_t runs = 10'000;
  std::uint64_t seed = 1;
  std::size_t horizon = 20;          // P(within t units) for t = 0 .. horizon
  bool withinSteps = false;          // P(within t steps of any rule) instead, as markov.hpp's bounded reachability
  std::size_t maxUnits = 100'000;    // a run still short of the target after this many units stops
  std::size_t maxSteps = 100'000'000;  // and after this many steps of any rule
  std::function<void(std::size_t runsDone)> progress = {};  // called about once a second, if set
};

struct SampledAnswer {
  std::size_t runs = 0;
  std::vector<double> within;  // the fraction of runs that reached the target within t units (or steps)
  // Dvoretzky-Kiefer-Wolfowitz: with 95 % confidence every `within[t]` is within `band` of the
  // true probability, for all t at once (sqrt(ln(2 / 0.05) / (2 runs))).
  double band = 0;
  std::size_t unfinished = 0;  // runs that ended (no rule enabled) or stopped before the target
  double meanUnits = 0;        // over the runs that reached it; meaningful when unfinished == 0
  double meanHalfWidth = 0;    // 95 % interval of the mean by the normal approximation
  bool scheduled = false;      // some state of some run enabled several rules (drawn uniformly)
  std::string method;
};

// Units are steps of the rules `unitRule` marks (rule index; e.g. the rule that starts a round).
// Out-of-range steps are a MarkovError, as in the exact engine.
SampledAnswer sampleRuns(const ir::Model& model, const ir::Expr& target, const std::vector<char>& unitRule,
                         const SamplingOptions& options);

}  // namespace semo::checker
