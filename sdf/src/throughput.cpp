#include "semo/sdf/throughput.hpp"

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace semo::sdf {

namespace {

__extension__ typedef __int128 Wide;  // GCC and Clang: exact cross products of two 64-bit values

struct StateHash {
  std::size_t operator()(const std::vector<std::int64_t>& s) const noexcept {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int64_t v : s) h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

// The strongly connected component of each node of a directed graph (successor lists), numbered
// from 0 (Tarjan's algorithm, iterative: no recursion depth limit).
std::vector<std::size_t> strongComponents(const std::vector<std::vector<std::size_t>>& next, std::size_t& count) {
  const std::size_t n = next.size();
  std::vector<std::size_t> index(n, SIZE_MAX), low(n, 0), component(n, SIZE_MAX);
  std::vector<char> onStack(n, 0);
  std::vector<std::size_t> stack;
  std::vector<std::pair<std::size_t, std::size_t>> calls;  // (node, next successor to look at)
  std::size_t counter = 0;
  count = 0;
  for (std::size_t root = 0; root < n; ++root) {
    if (index[root] != SIZE_MAX) continue;
    calls.push_back({root, 0});
    while (!calls.empty()) {
      auto& [v, k] = calls.back();
      if (k == 0 && index[v] == SIZE_MAX) {
        index[v] = low[v] = counter++;
        stack.push_back(v);
        onStack[v] = 1;
      }
      if (k < next[v].size()) {
        std::size_t w = next[v][k++];
        if (index[w] == SIZE_MAX) calls.push_back({w, 0});
        else if (onStack[w]) low[v] = std::min(low[v], index[w]);
        continue;
      }
      if (low[v] == index[v]) {
        std::size_t w = 0;
        do {
          w = stack.back();
          stack.pop_back();
          onStack[w] = 0;
          component[w] = count;
        } while (w != v);
        ++count;
      }
      std::size_t done = v;
      calls.pop_back();
      if (!calls.empty()) low[calls.back().first] = std::min(low[calls.back().first], low[done]);
    }
  }
  return component;
}

// The strongly connected components of the graph, each with the channels inside it. A bounded
// channel also leads back from its target to its source (its free space flows that way). Only
// these limit the throughput: with unbounded channels, a component downstream of a faster one just
// lets tokens pile up in front of it.
std::vector<std::pair<std::vector<ActorId>, std::vector<std::size_t>>> components(const Graph& g, const ThroughputOptions& options) {
  const std::size_t n = g.actors.size();
  std::vector<std::vector<std::size_t>> next(n);
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    const Channel& ch = g.channels[c];
    next[ch.source].push_back(ch.target);
    if (c < options.capacities.size() && options.capacities[c] && !ch.selfLoop()) next[ch.target].push_back(ch.source);
  }
  std::size_t count = 0;
  const std::vector<std::size_t> component = strongComponents(next, count);
  std::vector<std::pair<std::vector<ActorId>, std::vector<std::size_t>>> out(count);
  for (ActorId a = 0; a < n; ++a) out[component[a]].first.push_back(a);
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (component[g.channels[c].source] == component[g.channels[c].target]) out[component[g.channels[c].source]].second.push_back(c);
  }
  return out;
}

class SelfTimed {
 public:
  SelfTimed(const Graph& g, const std::vector<ActorId>& actors, const std::vector<std::size_t>& channels,
            const std::vector<std::int64_t>& q, const ThroughputOptions& options)
      : g_(g), actors_(actors), channels_(channels), q_(q), options_(options) {
    localIndex_.assign(g.actors.size(), 0);
    for (std::size_t i = 0; i < actors.size(); ++i) localIndex_[actors[i]] = i;
    inputs_.resize(actors.size());
    outputs_.resize(actors.size());
    for (std::size_t i = 0; i < channels.size(); ++i) {
      const Channel& c = g.channels[channels[i]];
      inputs_[localIndex_[c.target]].push_back(i);
      outputs_[localIndex_[c.source]].push_back(i);
    }
  }

  ThroughputResult run() {
    ThroughputResult out;
    const std::size_t m = channels_.size();
    tokens_.assign(m, 0);
    space_.assign(m, -1);
    for (std::size_t i = 0; i < m; ++i) {
      const Channel& c = g_.channels[channels_[i]];
      tokens_[i] = c.initialTokens;
      if (i < m && channels_[i] < options_.capacities.size() && options_.capacities[channels_[i]] && !c.selfLoop()) {
        space_[i] = *options_.capacities[channels_[i]] - c.initialTokens;
        if (space_[i] < 0) {
          out.error = "channel " + c.name + " holds more initial tokens than its capacity";
          return out;
        }
      }
    }
    active_.assign(actors_.size(), {});
    struct Seen {
      std::int64_t time, completed;
    };
    std::unordered_map<std::vector<std::int64_t>, Seen, StateHash> seen;
    std::int64_t time = 0;
    std::vector<std::int64_t> key;
    for (;;) {
      if (!startFirings(out)) return out;
      bool busy = std::any_of(active_.begin(), active_.end(), [](const auto& a) { return !a.empty(); });
      if (!busy) {
        out.deadlock = true;
        out.states = seen.size();
        return out;
      }
      key = tokens_;
      for (std::size_t i = 0; i < m; ++i) {
        if (space_[i] >= 0) key.push_back(space_[i]);
      }
      for (const std::vector<std::int64_t>& a : active_) {
        key.push_back(static_cast<std::int64_t>(a.size()));
        key.insert(key.end(), a.begin(), a.end());
      }
      auto [it, fresh] = seen.try_emplace(key, Seen{time, completedRef_});
      if (!fresh) {
        // Whole iterations lie between two equal states of a consistent connected graph.
        std::int64_t iterations = (completedRef_ - it->second.completed) / q_[actors_[0]];
        std::int64_t elapsed = time - it->second.time;
        std::int64_t d = std::gcd(elapsed, iterations);
        out.period = {elapsed / d, iterations / d};
        out.states = seen.size();
        return out;
      }
      if (seen.size() > options_.maxStates) {
        out.error = "more than " + std::to_string(options_.maxStates) + " states before the execution repeats";
        out.states = seen.size();
        return out;
      }
      std::int64_t step = INT64_MAX;
      for (const std::vector<std::int64_t>& a : active_) {
        if (!a.empty()) step = std::min(step, a.front());
      }
      if (time > INT64_MAX - step) {
        out.error = "the time of the execution passes 64 bits";
        return out;
      }
      time += step;
      for (std::size_t a = 0; a < actors_.size(); ++a) {
        std::vector<std::int64_t>& left = active_[a];
        std::size_t done = 0;
        for (std::int64_t& r : left) {
          r -= step;
          if (r == 0) ++done;
        }
        if (done == 0) continue;
        left.erase(left.begin(), left.begin() + static_cast<std::ptrdiff_t>(done));  // sorted: the finished come first
        finish(a, static_cast<std::int64_t>(done));
      }
    }
  }

 private:
  // Starts every firing that can start now (zero-time firings finish at once, and may enable more).
  bool startFirings(ThroughputResult& out) {
    for (bool changed = true; changed;) {
      changed = false;
      for (std::size_t a = 0; a < actors_.size(); ++a) {
        std::int64_t times = INT64_MAX;
        for (std::size_t i : inputs_[a]) times = std::min(times, tokens_[i] / g_.channels[channels_[i]].consumption);
        for (std::size_t i : outputs_[a]) {
          if (space_[i] >= 0) times = std::min(times, space_[i] / g_.channels[channels_[i]].production);
        }
        if (times == 0) continue;
        if (times > kMaxConcurrent) {
          out.error = "actor " + g_.actors[actors_[a]].name + " can start unboundedly many firings at once (no input channel or " +
                      "self-loop limits it)";
          return false;
        }
        changed = true;
        for (std::size_t i : inputs_[a]) tokens_[i] -= times * g_.channels[channels_[i]].consumption;
        for (std::size_t i : outputs_[a]) {
          if (space_[i] >= 0) space_[i] -= times * g_.channels[channels_[i]].production;
        }
        const std::int64_t duration = g_.actors[actors_[a]].executionTime;
        if (duration == 0) {
          finish(a, times);
          if (++zeroTimeRounds_ > kMaxConcurrent) {
            out.error = "zero-time firings never stop at one instant";
            return false;
          }
          continue;
        }
        std::vector<std::int64_t>& left = active_[a];
        left.insert(left.end(), static_cast<std::size_t>(times), duration);
        std::sort(left.begin(), left.end());
      }
    }
    zeroTimeRounds_ = 0;
    return true;
  }

  void finish(std::size_t a, std::int64_t times) {
    for (std::size_t i : outputs_[a]) tokens_[i] += times * g_.channels[channels_[i]].production;
    for (std::size_t i : inputs_[a]) {
      if (space_[i] >= 0) space_[i] += times * g_.channels[channels_[i]].consumption;
    }
    if (a == 0) completedRef_ += times;
  }

  static constexpr std::int64_t kMaxConcurrent = 1'000'000;

  const Graph& g_;
  const std::vector<ActorId>& actors_;
  const std::vector<std::size_t>& channels_;
  const std::vector<std::int64_t>& q_;
  const ThroughputOptions& options_;
  std::vector<std::size_t> localIndex_;                     // per actor of the graph: its index here
  std::vector<std::vector<std::size_t>> inputs_, outputs_;  // per local actor: local channel indices
  std::vector<std::int64_t> tokens_, space_;                // per local channel; space -1: unbounded
  std::vector<std::vector<std::int64_t>> active_;           // per local actor: remaining times, sorted
  std::int64_t completedRef_ = 0;                           // firings finished by the component's first actor
  std::int64_t zeroTimeRounds_ = 0;
};

}  // namespace

ThroughputResult throughput(const Graph& g, const std::vector<std::int64_t>& q, const ThroughputOptions& options) {
  ThroughputResult slowest;
  bool first = true;
  for (const auto& [actors, channels] : components(g, options)) {
    // An actor alone, with nothing to wait for (no self-loop), limits nothing: it may fire at once
    // as often as tokens arrive.
    if (channels.empty()) continue;
    // The component's own iteration: q restricted to it and divided by their gcd; one iteration
    // of the graph is `share` of them.
    std::int64_t share = 0;
    for (ActorId a : actors) share = std::gcd(share, q[a]);
    std::vector<std::int64_t> local = q;
    for (ActorId a : actors) local[a] /= share;
    ThroughputResult r = SelfTimed(g, actors, channels, local, options).run();
    if (r.error.empty() && !r.deadlock) {
      Wide num = static_cast<Wide>(r.period.num) * share;
      std::int64_t d = std::gcd(static_cast<std::int64_t>(num % r.period.den), r.period.den);  // gcd(num, den)
      num /= d;
      if (num > INT64_MAX) {
        r.error = "the period passes 64 bits";
      } else {
        r.period = {static_cast<std::int64_t>(num), r.period.den / d};
      }
    }
    slowest.states += r.states;
    if (!r.error.empty() || r.deadlock) {
      r.states = slowest.states;
      return r;
    }
    Wide mine = static_cast<Wide>(r.period.num) * slowest.period.den, theirs = static_cast<Wide>(slowest.period.num) * r.period.den;
    if (first || mine > theirs) slowest.period = r.period;
    first = false;
  }
  return slowest;
}

}  // namespace semo::sdf
