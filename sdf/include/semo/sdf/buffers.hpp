#pragma once
// Buffer capacities and the throughput they allow. Per channel, the smallest capacity with which it
// alone never deadlocks is p + c - g + (d mod g) (rates p, c, g = gcd(p, c), d initial tokens; at
// least d), and capacities between multiples of g above it change nothing. The Pareto front (the
// smallest total for each throughput reached, up to the maximal, unbounded, throughput) is found
// exactly by learning from cycles (buffers.cpp says why nothing is missed): each distribution's
// period is the maximum cycle ratio of the HSDF expansion with space edges (cycle_ratio.hpp, equal
// to the self-timed period of throughput.hpp), a cycle that holds a target period back says which
// channels must grow, and an exact cover search picks the cheapest distribution that grows them;
// what is learnt holds for the images of a distribution under the graph's automorphisms
// (automorphisms.hpp) too. Totals count every channel but self-loops, as SDF3 does.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/sdf/graph.hpp"
#include "semo/sdf/throughput.hpp"

namespace semo::sdf {

// The per-channel lower bound above (self-loops: 0, never bounded).
std::int64_t smallestCapacity(const Channel& c);

struct BufferPoint {
  std::int64_t total = 0;                 // summed over the channels that are not self-loops
  std::vector<std::int64_t> capacities;   // per channel (self-loops 0: not bounded)
  bool deadlock = false;                  // no throughput with these capacities
  Period period;
};

struct ParetoFront {
  std::vector<BufferPoint> points;  // increasing total, decreasing period; the first may deadlock
  Period best;                      // the period with unbounded channels
  std::uint64_t distributions = 0;  // distributions whose throughput was computed
  std::string error;                // not finished (a limit), or no throughput at all; empty: the front is exact and complete
};

ParetoFront bufferParetoFront(const Graph& g, const std::vector<std::int64_t>& q, std::uint64_t maxDistributions = 1'000'000);

}  // namespace semo::sdf
