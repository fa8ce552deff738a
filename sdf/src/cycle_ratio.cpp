#include "semo/sdf/cycle_ratio.hpp"

#include <algorithm>
#include <numeric>

namespace semo::sdf {

namespace {

__extension__ typedef __int128 Wide;  // GCC and Clang: exact products of two 64-bit values

Wide floorDiv(Wide a, Wide b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0); }
Wide ceilDiv(Wide a, Wide b) { return -floorDiv(-a, b); }

constexpr std::uint32_t kNone = UINT32_MAX;

// A cycle's ratio, in lowest terms; delay > 0.
struct CycleRatio {
  std::int64_t time = 0, delay = 1;
};
bool greater(const CycleRatio& a, const CycleRatio& b) { return static_cast<Wide>(a.time) * b.delay > static_cast<Wide>(b.time) * a.delay; }
bool same(const CycleRatio& a, const CycleRatio& b) { return a.time == b.time && a.delay == b.delay; }

}  // namespace

HsdfExpansion::HsdfExpansion(const Graph& g, const std::vector<std::int64_t>& q, std::int64_t maxFirings) : g_(g), q_(q) {
  firstNode_.assign(g.actors.size() + 1, 0);
  Wide sum = 0;
  for (std::size_t a = 0; a < g.actors.size(); ++a) {
    sum += q[a];
    if (sum > maxFirings) {
      error_ = "an iteration has more than " + std::to_string(maxFirings) + " firings";
      return;
    }
    firstNode_[a + 1] = static_cast<std::size_t>(sum);
  }
  actorOfNode_.resize(static_cast<std::size_t>(sum));
  for (ActorId a = 0; a < g.actors.size(); ++a) {
    for (std::size_t v = firstNode_[a]; v < firstNode_[a + 1]; ++v) actorOfNode_[v] = a;
  }
  tokenEdges_.assign(actorOfNode_.size(), {});
  for (const Channel& c : g.channels) {
    // Consumer firing k needs the tokens up to (k + 1) * consumption; beyond the initial ones they
    // come from producer firing j (counted from this iteration's first; negative: an earlier one).
    for (std::int64_t k = 0; k < q[c.target]; ++k) {
      Wide j = ceilDiv(static_cast<Wide>(k + 1) * c.consumption - c.initialTokens, c.production) - 1;
      Wide iteration = floorDiv(j, q[c.source]);
      if (-iteration > INT64_MAX / 2) {
        error_ = "channel " + c.name + " holds too many initial tokens";
        return;
      }
      const auto producer = static_cast<std::size_t>(j - iteration * q[c.source]);
      tokenEdges_[firstNode_[c.target] + static_cast<std::size_t>(k)].push_back(
          {static_cast<std::uint32_t>(firstNode_[c.source] + producer), g.actors[c.source].executionTime, static_cast<std::int64_t>(-iteration), SIZE_MAX, 0});
    }
  }
}

CycleRatioResult HsdfExpansion::evaluate(const std::vector<std::optional<std::int64_t>>& capacities) const {
  CycleRatioResult out;
  if (!error_.empty()) {
    out.error = error_;
    return out;
  }
  const std::size_t n = actorOfNode_.size();
  // The edges of this distribution, per node (compressed rows): the token edges, then the space ones.
  std::vector<std::size_t> begin(n + 1, 0);
  for (std::size_t v = 0; v < n; ++v) begin[v + 1] = tokenEdges_[v].size();
  for (std::size_t c = 0; c < g_.channels.size(); ++c) {
    if (c >= capacities.size() || !capacities[c] || g_.channels[c].selfLoop()) continue;
    for (std::size_t v = firstNode_[g_.channels[c].source]; v < firstNode_[g_.channels[c].source + 1]; ++v) ++begin[v + 1];
  }
  for (std::size_t v = 0; v < n; ++v) begin[v + 1] += begin[v];
  std::vector<Edge> edges(begin[n]);
  std::vector<std::size_t> fill(begin.begin(), begin.end() - 1);
  for (std::size_t v = 0; v < n; ++v) {
    for (const Edge& e : tokenEdges_[v]) edges[fill[v]++] = e;
  }
  for (std::size_t c = 0; c < g_.channels.size(); ++c) {
    if (c >= capacities.size() || !capacities[c] || g_.channels[c].selfLoop()) continue;
    const Channel& ch = g_.channels[c];
    const std::int64_t capacity = *capacities[c];
    if (capacity < ch.initialTokens) {
      out.error = "channel " + ch.name + " holds more initial tokens than its capacity";
      return out;
    }
    // Producer firing k claims the space up to (k + 1) * production; beyond the capacity's free
    // space it is freed by consumer firing i (negative: of an earlier iteration).
    for (std::int64_t k = 0; k < q_[ch.source]; ++k) {
      Wide need = static_cast<Wide>(k + 1) * ch.production - (capacity - ch.initialTokens);
      Wide i = ceilDiv(need, ch.consumption) - 1;
      Wide iteration = floorDiv(i, q_[ch.target]);
      if (-iteration > INT64_MAX / 2) {
        out.error = "channel " + ch.name + "'s capacity is too large";
        return out;
      }
      const auto consumer = static_cast<std::size_t>(i - iteration * q_[ch.target]);
      // The edge moves once the capacity covers the need without consumer firing i.
      const Wide move = static_cast<Wide>(k + 1) * ch.production + ch.initialTokens - static_cast<Wide>(ch.consumption) * i;
      const std::size_t v = firstNode_[ch.source] + static_cast<std::size_t>(k);
      edges[fill[v]++] = {static_cast<std::uint32_t>(firstNode_[ch.target] + consumer), g_.actors[ch.target].executionTime,
                          static_cast<std::int64_t>(-iteration), c, static_cast<std::int64_t>(std::min<Wide>(move, INT64_MAX))};
    }
  }

  // Only nodes that reach a cycle matter: drop, repeatedly, the nodes with no edge left.
  std::vector<std::size_t> pointedBy(n + 1, 0), outDegree(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    outDegree[v] = begin[v + 1] - begin[v];
    for (std::size_t e = begin[v]; e < begin[v + 1]; ++e) ++pointedBy[edges[e].to + 1];
  }
  for (std::size_t v = 0; v < n; ++v) pointedBy[v + 1] += pointedBy[v];
  std::vector<std::uint32_t> sources(pointedBy[n]);
  {
    std::vector<std::size_t> at(pointedBy.begin(), pointedBy.end() - 1);
    for (std::size_t v = 0; v < n; ++v) {
      for (std::size_t e = begin[v]; e < begin[v + 1]; ++e) sources[at[edges[e].to]++] = static_cast<std::uint32_t>(v);
    }
  }
  std::vector<char> alive(n, 1);
  std::vector<std::size_t> dead;
  for (std::size_t v = 0; v < n; ++v) {
    if (outDegree[v] == 0) dead.push_back(v);
  }
  while (!dead.empty()) {
    std::size_t v = dead.back();
    dead.pop_back();
    alive[v] = 0;
    for (std::size_t s = pointedBy[v]; s < pointedBy[v + 1]; ++s) {
      if (--outDegree[sources[s]] == 0) dead.push_back(sources[s]);
    }
  }

  auto cycleOf = [&](const std::vector<std::size_t>& cycleEdges) {
    RatioCycle cycle;
    for (std::size_t e : cycleEdges) {
      if (edges[e].channel == SIZE_MAX) continue;
      auto known = std::find_if(cycle.space.begin(), cycle.space.end(), [&](const SpaceOnCycle& s) { return s.channel == edges[e].channel; });
      if (known == cycle.space.end()) cycle.space.push_back({edges[e].channel, edges[e].moveCapacity});
      else known->capacityThatMovesIt = std::min(known->capacityThatMovesIt, edges[e].moveCapacity);
    }
    std::sort(cycle.space.begin(), cycle.space.end(), [](const SpaceOnCycle& a, const SpaceOnCycle& b) { return a.channel < b.channel; });
    return cycle;
  };

  // A cycle of edges without delay: a deadlock (depth-first search for a back edge).
  {
    std::vector<char> colour(n, 0);  // 0 new, 1 on the path, 2 done
    std::vector<std::pair<std::size_t, std::size_t>> path;  // (node, next edge)
    for (std::size_t root = 0; root < n; ++root) {
      if (!alive[root] || colour[root]) continue;
      path.push_back({root, begin[root]});
      colour[root] = 1;
      while (!path.empty()) {
        auto& [v, e] = path.back();
        if (e == begin[v + 1]) {
          colour[v] = 2;
          path.pop_back();
          continue;
        }
        const std::size_t edge = e++;
        const std::uint32_t w = edges[edge].to;
        if (edges[edge].delay != 0 || !alive[w] || colour[w] == 2) continue;
        if (colour[w] == 1) {
          std::vector<std::size_t> cycleEdges{edge};
          for (std::size_t i = path.size() - 1; path[i].first != w; --i) cycleEdges.push_back(path[i - 1].second - 1);
          RatioCycle cycle = cycleOf(cycleEdges);
          cycle.deadlock = true;
          out.deadlock = true;
          out.cycles.push_back(std::move(cycle));
          return out;
        }
        colour[w] = 1;
        path.push_back({w, begin[w]});
      }
    }
  }

  // Howard's policy iteration: each node follows one edge (its policy); the path from a node ends in
  // a cycle, whose ratio is the node's, and the node's value is the weight minus ratio times delay
  // along the path (times the cycle's delay, to stay integral). A node switches to an edge leading to
  // a larger ratio, or else (same ratio) to a larger value; when none does, the largest ratio is
  // the maximum cycle ratio (Cochet-Terrasson, Cohen, Gaubert, Mc Gettrick and Quadrat, 1998).
  std::vector<std::size_t> policy(n, SIZE_MAX);
  for (std::size_t v = 0; v < n; ++v) {
    if (!alive[v]) continue;
    for (std::size_t e = begin[v]; e < begin[v + 1]; ++e) {
      if (!alive[edges[e].to]) continue;
      if (policy[v] == SIZE_MAX || edges[e].weight > edges[policy[v]].weight) policy[v] = e;
    }
  }
  std::vector<CycleRatio> ratio(n);
  std::vector<Wide> value(n);
  std::vector<std::uint32_t> visit(n, kNone);
  std::vector<std::size_t> cycleHeads;  // one node per policy cycle
  std::vector<std::uint32_t> walk;
  for (std::uint32_t round = 0;; ++round) {
    if (round > 100'000) {
      out.error = "the cycle ratio iteration does not settle";
      return out;
    }
    // Value determination.
    std::fill(visit.begin(), visit.end(), kNone);
    cycleHeads.clear();
    for (std::size_t start = 0; start < n; ++start) {
      if (!alive[start] || visit[start] != kNone) continue;
      walk.clear();
      std::size_t v = start;
      while (visit[v] == kNone) {
        visit[v] = static_cast<std::uint32_t>(start);
        walk.push_back(static_cast<std::uint32_t>(v));
        v = edges[policy[v]].to;
      }
      std::size_t tail = walk.size();  // walk[0, tail) get their values from their successor
      if (visit[v] == start) {
        // A new cycle, from v round to v.
        Wide time = 0, delay = 0;
        std::size_t u = v;
        do {
          time += edges[policy[u]].weight;
          delay += edges[policy[u]].delay;
          u = edges[policy[u]].to;
        } while (u != v);
        if (delay <= 0 || time > INT64_MAX || delay > INT64_MAX) {
          out.error = "a cycle's time or delay passes 64 bits";
          return out;
        }
        const auto d = static_cast<std::int64_t>(delay), t = static_cast<std::int64_t>(time);
        const std::int64_t common = std::gcd(t, d);
        const CycleRatio r{t / common, d / common};
        // The cycle's reference node: its smallest, which keeps its value while the cycle's ratio
        // stays (with several cycles of one ratio, values measured from new references could make
        // the policy go round; kept, each switch raises a value and the iteration ends).
        std::size_t head = v;
        for (std::size_t u = edges[policy[v]].to; u != v; u = edges[policy[u]].to) head = std::min(head, u);
        cycleHeads.push_back(head);
        if (!(round > 0 && same(ratio[head], r))) value[head] = 0;
        ratio[head] = r;
        tail = static_cast<std::size_t>(std::find(walk.begin(), walk.end(), v) - walk.begin());
        // Rotate the cycle's part of the walk to start at the reference.
        std::rotate(walk.begin() + static_cast<std::ptrdiff_t>(tail), std::find(walk.begin() + static_cast<std::ptrdiff_t>(tail), walk.end(), head), walk.end());
        // The cycle's other nodes, backwards from the reference.
        for (std::size_t i = walk.size(); i-- > tail + 1;) {
          const std::size_t x = walk[i];
          const Edge& e = edges[policy[x]];
          ratio[x] = r;
          value[x] = value[e.to] + static_cast<Wide>(e.weight) * r.delay - static_cast<Wide>(e.delay) * r.time;
        }
      }
      for (std::size_t i = tail; i-- > 0;) {
        const std::size_t x = walk[i];
        const Edge& e = edges[policy[x]];
        ratio[x] = ratio[e.to];
        value[x] = value[e.to] + static_cast<Wide>(e.weight) * ratio[x].delay - static_cast<Wide>(e.delay) * ratio[x].time;
      }
    }
    // Improvement: first the ratios, then (when no ratio improves) the values.
    bool changed = false;
    for (std::size_t v = 0; v < n; ++v) {
      if (!alive[v]) continue;
      std::size_t best = policy[v];
      for (std::size_t e = begin[v]; e < begin[v + 1]; ++e) {
        if (alive[edges[e].to] && greater(ratio[edges[e].to], ratio[edges[best].to])) best = e;
      }
      if (greater(ratio[edges[best].to], ratio[v])) {
        policy[v] = best;
        changed = true;
      }
    }
    if (!changed) {
      for (std::size_t v = 0; v < n; ++v) {
        if (!alive[v]) continue;
        std::size_t best = policy[v];
        Wide bestValue = value[v];
        for (std::size_t e = begin[v]; e < begin[v + 1]; ++e) {
          const std::uint32_t w = edges[e].to;
          if (!alive[w] || !same(ratio[w], ratio[v])) continue;
          Wide candidate = value[w] + static_cast<Wide>(edges[e].weight) * ratio[v].delay - static_cast<Wide>(edges[e].delay) * ratio[v].time;
          if (candidate > bestValue) {
            best = e;
            bestValue = candidate;
          }
        }
        if (best != policy[v]) {
          policy[v] = best;
          changed = true;
        }
      }
    }
    if (!changed) break;
  }
  for (std::size_t head : cycleHeads) {
    std::vector<std::size_t> cycleEdges;
    std::size_t u = head;
    do {
      cycleEdges.push_back(policy[u]);
      u = edges[policy[u]].to;
    } while (u != head);
    RatioCycle cycle = cycleOf(cycleEdges);
    cycle.ratio = {ratio[head].time, ratio[head].delay};
    out.cycles.push_back(std::move(cycle));
  }
  std::stable_sort(out.cycles.begin(), out.cycles.end(), [](const RatioCycle& a, const RatioCycle& b) {
    return greater({a.ratio.num, a.ratio.den}, {b.ratio.num, b.ratio.den});
  });
  out.period = out.cycles.empty() ? Period{0, 1} : out.cycles.front().ratio;
  return out;
}

}  // namespace semo::sdf
