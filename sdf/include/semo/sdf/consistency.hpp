#pragma once
// Consistency and one iteration of an SDF graph, in exact integer arithmetic:
// - the repetition vector q (the fewest firings per actor that return every channel to its token
//   count: q[src] * production = q[dst] * consumption on every channel), per connected component;
//   an inconsistent graph names a channel whose balance equation cannot hold;
// - whether one iteration can run from the initial tokens (deadlock freedom), and if so a
//   sequential schedule of it. Firing any enabled actor that still has firings left finds such a
//   schedule whenever one exists (the order does not matter: firings only add tokens for others).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/sdf/graph.hpp"

namespace semo::sdf {

struct RepetitionVector {
  std::vector<std::int64_t> firings;            // per actor; empty when inconsistent
  std::optional<std::size_t> conflictChannel;   // inconsistent: a channel that cannot balance
  std::string error;                            // why not (inconsistency, or a count past 64 bits)
  [[nodiscard]] bool consistent() const { return error.empty(); }
};

RepetitionVector repetitionVector(const Graph& g);

// `times` consecutive firings of one actor.
struct FiringRun {
  ActorId actor = 0;
  std::int64_t times = 0;
};

struct Iteration {
  bool deadlockFree = false;
  std::string error;                        // not run: an iteration's token counts would pass 64 bits
  std::vector<FiringRun> schedule;          // one iteration's firings, in order (the prefix run, on deadlock)
  std::vector<std::int64_t> tokensAtEnd;    // per channel, after the schedule
  std::vector<std::int64_t> maxTokens;      // per channel, the most tokens it held along the schedule
};

// `q` must be the graph's repetition vector.
Iteration runIteration(const Graph& g, const std::vector<std::int64_t>& q);

// "a 3b c": the schedule, each run as its count (when more than one) and the actor's name.
std::string scheduleText(const Graph& g, const std::vector<FiringRun>& schedule);

}  // namespace semo::sdf
