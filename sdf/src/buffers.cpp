#include "semo/sdf/buffers.hpp"

#include <algorithm>
#include <numeric>
#include <queue>
#include <set>

namespace semo::sdf {

namespace {

__extension__ typedef __int128 Wide;  // GCC and Clang: exact cross products of two 64-bit values

// a is a longer period (a lower throughput) than b.
bool slower(const Period& a, const Period& b) { return static_cast<Wide>(a.num) * b.den > static_cast<Wide>(b.num) * a.den; }

}  // namespace

std::int64_t smallestCapacity(const Channel& c) {
  if (c.selfLoop()) return 0;
  const std::int64_t g = std::gcd(c.production, c.consumption);
  return std::max(c.initialTokens, c.production + c.consumption - g + c.initialTokens % g);
}

ParetoFront bufferParetoFront(const Graph& g, const std::vector<std::int64_t>& q, std::uint64_t maxDistributions) {
  ParetoFront out;
  ThroughputResult unbounded = throughput(g, q);
  if (!unbounded.error.empty() || unbounded.deadlock) {
    out.error = unbounded.deadlock ? "the graph deadlocks even with unbounded channels" : unbounded.error;
    return out;
  }
  out.best = unbounded.period;
  const std::size_t m = g.channels.size();
  auto total = [&](const std::vector<std::int64_t>& caps) {
    std::int64_t sum = 0;
    for (std::size_t c = 0; c < m; ++c) sum += g.channels[c].selfLoop() ? 0 : caps[c];
    return sum;
  };
  std::vector<std::int64_t> start(m);
  for (std::size_t c = 0; c < m; ++c) start[c] = smallestCapacity(g.channels[c]);
  // Distributions by increasing total (ties in any fixed order); each is evaluated once.
  using Entry = std::pair<std::int64_t, std::vector<std::int64_t>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> frontier;
  std::set<std::vector<std::int64_t>> queued;
  frontier.push({total(start), start});
  queued.insert(start);
  ThroughputOptions options;
  options.capacities.resize(m);
  options.trackDependencies = true;
  bool haveThroughput = false;
  Period bestSoFar;
  while (!frontier.empty()) {
    auto [size, caps] = frontier.top();
    frontier.pop();
    if (++out.distributions > maxDistributions) {
      out.error = "more than " + std::to_string(maxDistributions) + " distributions explored";
      return out;
    }
    for (std::size_t c = 0; c < m; ++c) {
      options.capacities[c] = g.channels[c].selfLoop() ? std::optional<std::int64_t>() : std::optional<std::int64_t>(caps[c]);
    }
    ThroughputResult r = throughput(g, q, options);
    if (!r.error.empty()) {
      out.error = r.error;
      return out;
    }
    if (out.points.empty() && r.deadlock) out.points.push_back({size, caps, true, {}});
    if (!r.deadlock && (!haveThroughput || slower(bestSoFar, r.period))) {
      if (!out.points.empty() && out.points.back().total == size) out.points.pop_back();  // a better one of the same total
      out.points.push_back({size, caps, false, r.period});
      haveThroughput = true;
      bestSoFar = r.period;
      if (!slower(r.period, out.best)) return out;  // the maximal throughput is reached
    }
    // Deadlocked: the channels whose space held an actor back; else only the storage dependencies
    // on a critical cycle (if there are none, which should not happen below the best throughput,
    // every blocked channel, to stay exact).
    const std::vector<char>* enlarge = &r.spaceBlocked;
    if (!r.deadlock && std::find(r.spaceCritical.begin(), r.spaceCritical.end(), 1) != r.spaceCritical.end()) enlarge = &r.spaceCritical;
    for (std::size_t c = 0; c < m; ++c) {
      if (!(*enlarge)[c]) continue;
      std::vector<std::int64_t> larger = caps;
      larger[c] += std::gcd(g.channels[c].production, g.channels[c].consumption);
      if (queued.insert(larger).second) frontier.push({size + (larger[c] - caps[c]), std::move(larger)});
    }
  }
  out.error = "no enlargement raises the throughput further";  // cannot happen for a consistent graph
  return out;
}

}  // namespace semo::sdf
