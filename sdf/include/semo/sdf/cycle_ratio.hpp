#pragma once
// The period of self-timed execution as the maximum cycle ratio of the homogeneous (HSDF)
// expansion: one node per firing of an iteration, and per firing, per input channel, an edge from
// the firing that produces the last token it needs (its weight the producer's execution time, its
// delay the iterations between the two firings). A bounded channel adds its free space as a channel
// back (SDF3's model: claimed by the producer's start, freed by the consumer's end): per producer
// firing, an edge from the consumer firing that frees the last space it needs. Every firing of an
// actor takes as long, and tokens are consumed in order, so in the self-timed execution the firings
// of an actor start and end in order, and a firing waits exactly for those last tokens and spaces;
// the execution is then the max-plus recurrence of this graph, whose growth rate is the largest
// ratio of execution time to delay over its cycles (for every actor, of the cycles upstream of it;
// the slowest sets the graph's period, as throughput() takes the slowest component). A cycle
// without delay is a deadlock.
//
// The ratio is found by Howard's policy iteration in exact integer arithmetic (a cycle's ratio is a
// fraction of two integers; a node's value relative to its cycle is kept multiplied by that cycle's
// delay, so every comparison is exact), and the cycles it ends with say which channels' space the
// critical cycle waits for.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/sdf/graph.hpp"
#include "semo/sdf/throughput.hpp"

namespace semo::sdf {

// A bounded channel's space on a cycle of the expansion, and the capacity from which that space
// arrives from an earlier consumer firing (the edge moves and the cycle, as it is, is gone). With a
// smaller capacity the space arrives no earlier, so the cycle still holds the execution back.
struct SpaceOnCycle {
  std::size_t channel = 0;
  std::int64_t capacityThatMovesIt = 0;
};

struct RatioCycle {
  bool deadlock = false;  // no delay on the cycle
  Period ratio;           // execution time over delay (when not a deadlock)
  std::vector<SpaceOnCycle> space;  // per bounded channel on the cycle (once; the smallest capacity that moves one of its edges)
};

struct CycleRatioResult {
  bool deadlock = false;
  Period period;                   // the maximum cycle ratio (0 when the expansion has no cycle)
  std::string error;               // not decided (sizes or values past the limits)
  std::vector<RatioCycle> cycles;  // a deadlock's cycle, or the policy's cycles, the critical one first
};

class HsdfExpansion {
 public:
  // `q` must be the graph's repetition vector. Fails (error()) when an iteration has more than
  // `maxFirings` firings.
  HsdfExpansion(const Graph& g, const std::vector<std::int64_t>& q, std::int64_t maxFirings = 5'000'000);
  [[nodiscard]] const std::string& error() const { return error_; }
  [[nodiscard]] std::size_t firings() const { return actorOfNode_.size(); }

  // Per channel, the capacity (nullopt: unbounded; self-loops are never bounded).
  [[nodiscard]] CycleRatioResult evaluate(const std::vector<std::optional<std::int64_t>>& capacities) const;

 private:
  struct Edge {
    std::uint32_t to;             // the firing waited for
    std::int64_t weight;          // its execution time
    std::int64_t delay;           // iterations between the two firings
    std::size_t channel;          // a bounded channel's space, or SIZE_MAX for tokens
    std::int64_t moveCapacity;    // space edges: the capacity from which it moves
  };
  const Graph& g_;
  const std::vector<std::int64_t>& q_;
  std::vector<std::size_t> firstNode_;      // per actor
  std::vector<ActorId> actorOfNode_;
  std::vector<std::vector<Edge>> tokenEdges_;  // per node: the token dependencies (fixed)
  std::string error_;
};

}  // namespace semo::sdf
