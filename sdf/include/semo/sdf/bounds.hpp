#pragma once
// Buffer bounds for one scenario of a task graph, chosen from the throughput-buffer Pareto front
// and proven with Z3:
// - deadlock-free bounds: the smallest total with which an iteration can run (the front's first
//   point with a throughput); each channel one token smaller deadlocks;
// - maximal-throughput bounds: the smallest total reaching the throughput of unbounded channels
//   (the front's last point); each channel one token smaller deadlocks or lowers the throughput.
// The proofs, each a Z3 query whose "unsat" is the proof:
// - safety: the static schedule found with the chosen capacities, repeated for any number of
//   iterations n (n a free variable of the query), never takes more tokens from a channel than it
//   holds nor puts more in it than its capacity;
// - minimality, deadlock: with one token less on the channel, no order of one iteration's
//   firings respects every channel's tokens and capacities (sequential orders suffice: with
//   capacities as reverse channels the graph is again an SDF graph, which runs an iteration in
//   some order whenever it runs at all);
// - minimality, throughput: where one token less does not deadlock, the exact period of the
//   self-timed execution (throughput.hpp) with it is longer; that is a computation, not a Z3
//   proof, and the result says which of the two each channel got.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "semo/sdf/buffers.hpp"
#include "semo/sdf/consistency.hpp"
#include "semo/sdf/graph.hpp"

namespace semo::sdf {

// The graph with each bounded channel's free space as a reverse channel (capacity minus initial
// tokens); self-loops and unbounded (negative) capacities get none.
Graph withCapacities(const Graph& g, const std::vector<std::int64_t>& capacities);

enum class ProofStatus { Proven, Refuted, Unknown };
const char* proofStatusName(ProofStatus s);

struct ChannelMinimality {
  std::size_t channel = 0;
  enum class Outcome { Deadlocks, SlowerPeriod, NotMinimal, Unknown } outcome = Outcome::Unknown;
  Period periodWithOneLess;  // SlowerPeriod
  std::string note;          // Unknown: why
};

struct ChosenBounds {
  std::vector<std::int64_t> capacities;  // per channel (self-loops 0)
  std::int64_t total = 0;
  Period period;
  std::vector<FiringRun> schedule;       // one iteration, respecting the capacities
  ProofStatus safety = ProofStatus::Unknown;
  std::string safetyNote;
  ProofStatus minimality = ProofStatus::Unknown;  // Proven when every channel's outcome is
  std::vector<ChannelMinimality> channels;        // per bounded channel
  std::string minimalityNote;                     // Unknown without channels: why (not asked for)
};

struct BoundsOptions {
  std::uint64_t maxDistributions = 200'000;
  unsigned timeoutMs = 10'000;            // per Z3 query
  std::uint64_t maxFiringsForProof = 4000;  // iterations with more firings are not encoded (Unknown)
  // Minimality is a claim about memory (no channel could be smaller), not about running: what runs
  // needs only the schedule proven safe within the capacities. Its queries (one per channel) are
  // nine tenths of the time, so those who only run the graph (the simulator) leave them out; the
  // minimality is then Unknown, with a note saying it was not asked for.
  bool proveMinimality = true;
  // Told as each robot's graph is analysed (for progress lines); may be empty.
  std::function<void(const std::string&)> onPhase;
};

struct ScenarioBounds {
  ParetoFront front;
  bool haveBounds = false;  // the front reached a throughput (else `error`)
  ChosenBounds deadlockFree, maxThroughput;
  std::string error;
};

// `q` the repetition vector of a consistent graph that is deadlock free with unbounded channels.
ScenarioBounds chooseAndProveBounds(const Graph& g, const std::vector<std::int64_t>& q, const BoundsOptions& options = {});

// The Z3 queries on their own (for the tests).
ProofStatus proveScheduleSafe(const Graph& g, const std::vector<std::int64_t>& capacities, const std::vector<FiringRun>& schedule,
                              unsigned timeoutMs, std::string* note = nullptr);
// Proven: no iteration can run (the graph with these capacities deadlocks); Refuted: one can.
ProofStatus proveIterationImpossible(const Graph& g, const std::vector<std::int64_t>& q, const std::vector<std::int64_t>& capacities,
                                     unsigned timeoutMs);

}  // namespace semo::sdf
