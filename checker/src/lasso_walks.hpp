#pragma once
// Hunting fair violations by random walks that close loops. A walk fixes a world (each sensed
// condition decided one way, chosen at random), then takes random enabled steps: fair rules
// uniformly, losses with a bias drawn per walk, crashes and other unfair environment steps rarely.
// A model whose robots settle into cycles soon comes back to states it has seen; every segment
// between two visits of one state is a loop, and the longest one the walk has (from the first visit
// of its current state) is the one most likely to treat every fairness group fairly. Such a lasso
// is judged by checkLasso (lasso_check.hpp) on the model itself, then shortened: loops of the stem
// cut out, and loops inside the loop cut out where what is left is still a fair violation. Only
// ever finds violations; the same seed gives the same walks. Once a walk has found a lasso, as many
// walks again look for a shorter one.
#include <cstdint>
#include <optional>
#include <string>

#include "semo/checker/trace.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

struct LassoWalkLimits {
  std::uint64_t seed = 1;
  std::uint32_t walks = 4000;
  // Short walks, many of them: a walk's stem is what the shortening has to cut down, and on
  // scouting walks of 1,024 steps found mode_agreement's lasso in 48 walks (0.9 s), walks of 8,192
  // in 355 (31 s).
  std::uint32_t stepsPerWalk = 1024;
  double seconds = 30;
};

struct LassoWalkOutcome {
  std::optional<Trace> lasso;  // a fair violation of `model`, checked and shortened
  std::uint32_t walks = 0;     // walks taken
  std::uint32_t lassoWalk = 0; // the walk whose lasso is reported (the first to find one, or a
                               // shorter one among as many walks again)
  std::uint64_t steps = 0;     // steps taken by all of them
  std::string why;             // no lasso: how the hunt ended
  double seconds = 0;
};

LassoWalkOutcome findLassoByWalks(const ir::Model& model, std::size_t property, const LassoWalkLimits& limits);

// A counterexample lasso made shorter: the stem's own loops cut out, then each loop inside the loop
// cut out when what is left is still a counterexample (checkLasso). `lasso` must be one.
Trace shortenLasso(const ir::Model& model, const Trace& lasso, const ir::Property& property);

}  // namespace semo::checker::detail
