#pragma once
// Throughput by self-timed execution (the state-space method of Ghamarian et al., which SDF3 uses):
// every actor starts a firing as soon as its input tokens (and, with capacities, the space on its
// output channels) are there, possibly several at once unless a self-loop limits it; the execution
// is deterministic, so its states eventually repeat, and the time between two occurrences of a
// state divided by the iterations completed in between is the period (the inverse of the
// throughput). Exact: times are integers and the period a fraction.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/sdf/graph.hpp"

namespace semo::sdf {

struct Period {
  std::int64_t num = 0, den = 1;  // time units per iteration (lowest terms)
  [[nodiscard]] double value() const { return static_cast<double>(num) / static_cast<double>(den); }
  friend bool operator==(const Period&, const Period&) = default;
};

struct ThroughputResult {
  bool deadlock = false;          // the execution stops: throughput 0
  Period period;                  // when not deadlocked
  std::uint64_t states = 0;       // states stored before the first repetition
  std::string error;              // not decided (a limit, or counts past 64 bits)
};

struct ThroughputOptions {
  // Per channel, the most tokens it may hold (nullopt: unbounded). Self-loops are never bounded.
  std::vector<std::optional<std::int64_t>> capacities;
  std::uint64_t maxStates = 10'000'000;
};

// `q` must be the graph's repetition vector; a graph of several components is as slow as its
// slowest component.
ThroughputResult throughput(const Graph& g, const std::vector<std::int64_t>& q, const ThroughputOptions& options = {});

}  // namespace semo::sdf
