#pragma once
// Round models: how the runtime spreads knowledge, written as IR for the quantitative engine
// (markov.hpp). The translation's IR lets a robot learn a fact at any time (which is what the
// qualitative properties need); the runtime gossips in rounds, one every dissemination period, and
// those rounds are what "how many rounds until every robot knows" counts. specs/quantitative.md.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "semo/checker/markov.hpp"
#include "semo/checker/statistical.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct SpreadParameters {
  std::size_t robots = 2;         // the robots working in the group service, in the team's order
  std::size_t firstKnower = 0;    // which of them holds the fact at the start
  double lossPerCopy = 0;         // probability that one copy of one message is lost
  std::int64_t retransmissions = 0;  // extra copies of each message (lost only if all are)
};

// One fact spreading as Team::gossip spreads it: each round, the robots in the team's order, each
// that holds the fact sends it to each other robot in order, received unless every copy is lost;
// a robot that learnt it earlier in the round sends it later in the same round. Variables
// `knows[i]` and `phase` (0: a round begins, the rule `round`; then one phase per message). No
// robot crashes and every robot stays in the service.
ir::Model knowledgeSpreadModel(const SpreadParameters& p);

struct SpreadAnswer {
  std::size_t states = 0;
  std::vector<double> withinRounds;  // P(every robot knows within t rounds), t = 0 .. horizon
  QuantitativeResult expectedRounds;
};

SpreadAnswer analyzeSpread(const SpreadParameters& p, std::size_t horizonRounds, const MarkovLimits& limits = {});

// The same question answered from simulated runs of the same round model (statistical.hpp), for
// teams whose round model has too many states (it keeps a bit per robot): units are rounds.
SampledAnswer sampleSpread(const SpreadParameters& p, SamplingOptions options);

// Losses in a row on one link: each period's message lost independently with probability `loss`;
// the variable `run` counts the losses since the last message that got through, and the target is
// `length` of them in a row (a heartbeat burst the model does not assume, a false takeover).
ir::Model lossRunModel(std::size_t length, double loss);

struct LossRunAnswer {
  std::vector<double> withinPeriods;  // P(`length` losses in a row within t periods), t = 0 .. horizon
  QuantitativeResult expectedPeriods;
};

LossRunAnswer analyzeLossRun(std::size_t length, double loss, std::size_t horizonPeriods);

}  // namespace semo::checker
