#pragma once
// Explicit-state breadth-first search for safety properties on the IR. BFS order makes every
// counterexample a shortest one. A property is "proven" only when the whole reachable state space
// was explored; reaching a limit leaves the unviolated properties "unknown" with the coverage said.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "semo/checker/trace.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct Progress {
  std::uint64_t states = 0, transitions = 0, bytes = 0;
  std::uint32_t depth = 0;
  double seconds = 0;
  // The states are counted in a set held as decision diagrams, not enumerated one by one: a rate
  // would mean nothing, and the depth is the round of the fixpoint being computed.
  bool counted = false;
};

// The threads a search takes when none are asked for: SEMO_THREADS when it is a whole number from
// 1 to 256 (threadsSettingError() says when it is not), else one per processor this process may
// run on (its affinity mask, which taskset and containers narrow). A test runner that runs two
// checks at once on two cores sets SEMO_THREADS=1: four threads on two cores took 15 % more
// processor time (two checks of patrol side by side: 45 s against 39, 2026-11-29), as the search's
// threads wait for each other by spinning first.
unsigned defaultThreads();
// Why SEMO_THREADS is not a thread count; empty when it is one, or unset or empty.
std::string threadsSettingError();

struct SearchLimits {
  std::uint64_t maxStates = 50'000'000;
  std::uint64_t maxMemoryBytes = 8ull << 30;
  // Explore only the states within this many steps of the initial state (bounded search: never
  // "proven" unless no path is longer). States at the bound are checked against the invariants but
  // not expanded, as in SPIN's breadth-first search with -m.
  std::uint32_t maxDepth = UINT32_MAX;
  // Store one state per orbit of interchangeable robots (checker/symmetry.hpp); the verdicts are
  // the same, the counts are of orbits.
  bool symmetry = true;
  // Threads that generate and insert successors; results do not depend on it (defaultThreads()).
  unsigned threads = 1;
  // Called about once a second during a long search (never for searches under a second).
  std::function<void(const Progress&)> onProgress;
  // Told as each long phase starts or ends (a liveness property's search, its verdict), for
  // progress lines; may be called from several threads at once, may be empty.
  std::function<void(const std::string&)> onPhase;
};

enum class Verdict { Proven, Violated, Unknown };
const char* verdictName(Verdict v);

struct PropertyResult {
  std::string name;
  std::string origin;
  Verdict verdict = Verdict::Unknown;
  std::optional<Trace> counterexample;
};

struct SearchResult {
  std::vector<PropertyResult> properties;  // the invariants in order, then deadlock_freedom if asked
  std::uint64_t states = 0;
  std::uint64_t transitions = 0;
  // Of those, the ones not generated: a lower rule's image under a swap of two equal robots gave
  // the same successors (Symmetry::redundant).
  std::uint64_t transitionsSkipped = 0;
  std::uint32_t depth = 0;       // BFS levels explored
  bool complete = false;         // the whole reachable state space was explored
  std::string limitReached;      // why the search stopped early, if it did
  bool depthBounded = false;     // stopped by maxDepth: every state within that many steps was explored
  std::uint64_t bytesPerState = 0;
  std::uint64_t peakBytes = 0;
  double seconds = 0;
  std::optional<Trace> rangeError;  // an update leaving a variable's range: a modelling error
  std::vector<std::string> symmetry;  // the classes of interchangeable robots used, if any
};

SearchResult checkSafety(const ir::Model& model, const SearchLimits& limits);

}  // namespace semo::checker
