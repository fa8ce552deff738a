#pragma once
// Buffer capacities and the throughput they allow. Per channel, the smallest capacity with which it
// alone never deadlocks is p + c - g + (d mod g) (rates p, c, g = gcd(p, c), d initial tokens; at
// least d), and capacities between multiples of g above it change nothing. The exploration walks
// distributions in order of total size from those bounds, enlarging only channels whose space held
// an actor back (throughput.hpp), so each total size's best throughput is found, and with it the
// Pareto front: the smallest total for each throughput reached, up to the maximal (unbounded)
// throughput. Totals count every channel but self-loops, as SDF3 does.
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
  std::string error;                // not finished (a limit), or no throughput at all
};

ParetoFront bufferParetoFront(const Graph& g, const std::vector<std::int64_t>& q, std::uint64_t maxDistributions = 1'000'000);

}  // namespace semo::sdf
