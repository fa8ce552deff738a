#include "semo/sdf/consistency.hpp"

#include <algorithm>
#include <numeric>
#include <optional>

namespace semo::sdf {

namespace {

__extension__ typedef __int128 Wide;  // GCC and Clang: products of two 64-bit counts, exactly

constexpr Wide kMax = INT64_MAX;

// A positive rational in lowest terms, or nullopt past 64 bits.
struct Rate {
  std::int64_t num = 0, den = 1;
};

std::optional<Rate> reduced(Wide num, Wide den) {
  Wide a = num, b = den;
  while (b != 0) {
    Wide t = a % b;
    a = b;
    b = t;
  }
  num /= a;
  den /= a;
  if (num > kMax || den > kMax) return std::nullopt;
  return Rate{static_cast<std::int64_t>(num), static_cast<std::int64_t>(den)};
}

// A flat single-appearance schedule (every actor's firings in one run) exists exactly when the
// channels whose initial tokens do not already cover the consumer's whole iteration form no cycle
// (self-loops aside, which need only one firing's worth): then any topological order of them is
// one, since a consumer run after its producer's run finds d + q[src] * p = d + q[dst] * c tokens.
// Returns such an order (the smallest index first among the ready), or nullopt.
std::optional<std::vector<ActorId>> flatSingleAppearanceOrder(const Graph& g, const std::vector<std::int64_t>& q) {
  const std::size_t n = g.actors.size();
  std::vector<std::vector<ActorId>> successors(n);
  std::vector<std::size_t> waitingFor(n, 0);
  for (const Channel& ch : g.channels) {
    if (ch.selfLoop()) {
      if (q[ch.source] > 0 && ch.initialTokens < ch.consumption) return std::nullopt;
      continue;
    }
    if (static_cast<Wide>(ch.initialTokens) >= static_cast<Wide>(q[ch.target]) * ch.consumption) continue;
    successors[ch.source].push_back(ch.target);
    ++waitingFor[ch.target];
  }
  std::vector<ActorId> order;
  std::vector<ActorId> ready;
  for (ActorId a = 0; a < n; ++a) {
    if (waitingFor[a] == 0) ready.push_back(a);
  }
  while (!ready.empty()) {
    const auto smallest = std::min_element(ready.begin(), ready.end());
    const ActorId a = *smallest;
    ready.erase(smallest);
    order.push_back(a);
    for (ActorId b : successors[a]) {
      if (--waitingFor[b] == 0) ready.push_back(b);
    }
  }
  if (order.size() != n) return std::nullopt;
  return order;
}

}  // namespace

RepetitionVector repetitionVector(const Graph& g) {
  RepetitionVector out;
  const std::size_t n = g.actors.size();
  std::vector<std::vector<std::size_t>> touching(n);
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    touching[g.channels[c].source].push_back(c);
    if (!g.channels[c].selfLoop()) touching[g.channels[c].target].push_back(c);
  }
  std::vector<Rate> rate(n);
  std::vector<char> seen(n, 0);
  std::vector<std::int64_t> firings(n, 0);
  for (ActorId root = 0; root < n; ++root) {
    if (seen[root]) continue;
    // Rates relative to the root along a spanning tree, every other channel checked against them.
    std::vector<ActorId> component{root};
    seen[root] = 1;
    rate[root] = {1, 1};
    for (std::size_t next = 0; next < component.size(); ++next) {
      ActorId a = component[next];
      for (std::size_t c : touching[a]) {
        const Channel& ch = g.channels[c];
        // rate(target) * consumption = rate(source) * production
        bool forward = ch.source == a;
        ActorId other = forward ? ch.target : ch.source;
        Wide num = static_cast<Wide>(rate[a].num) * (forward ? ch.production : ch.consumption);
        Wide den = static_cast<Wide>(rate[a].den) * (forward ? ch.consumption : ch.production);
        std::optional<Rate> r = reduced(num, den);
        if (!r) {
          out.error = "the repetition counts exceed 64 bits (at channel " + ch.name + ")";
          return out;
        }
        if (!seen[other]) {
          seen[other] = 1;
          rate[other] = *r;
          component.push_back(other);
        } else if (rate[other].num != r->num || rate[other].den != r->den) {
          out.conflictChannel = c;
          out.error = "inconsistent: channel " + ch.name + " (" + g.actors[ch.source].name + " produces " +
                      std::to_string(ch.production) + ", " + g.actors[ch.target].name + " consumes " +
                      std::to_string(ch.consumption) + ") cannot balance with the other channels' rates";
          return out;
        }
      }
    }
    // Scale the component to the smallest integers.
    Wide common = 1;
    for (ActorId a : component) {
      Wide d = rate[a].den;
      common = common / std::gcd(static_cast<std::int64_t>(common), static_cast<std::int64_t>(d)) * d;
      if (common > kMax) {
        out.error = "the repetition counts exceed 64 bits";
        return out;
      }
    }
    std::int64_t divisor = 0;
    for (ActorId a : component) {
      Wide q = static_cast<Wide>(rate[a].num) * (common / rate[a].den);
      if (q > kMax) {
        out.error = "the repetition counts exceed 64 bits";
        return out;
      }
      firings[a] = static_cast<std::int64_t>(q);
      divisor = std::gcd(divisor, firings[a]);
    }
    for (ActorId a : component) firings[a] /= divisor;
  }
  out.firings = std::move(firings);
  return out;
}

Iteration runIteration(const Graph& g, const std::vector<std::int64_t>& q) {
  Iteration out;
  const std::size_t n = g.actors.size();
  std::vector<std::vector<std::size_t>> inputs(n), outputs(n);
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    inputs[g.channels[c].target].push_back(c);
    outputs[g.channels[c].source].push_back(c);
  }
  for (const Channel& ch : g.channels) {
    // Every token an iteration moves through a channel must be countable.
    if (static_cast<Wide>(q[ch.source]) * ch.production + ch.initialTokens > kMax / 2) {
      out.error = "channel " + ch.name + " would carry more tokens in one iteration than 64 bits count";
      return out;
    }
  }
  std::vector<std::int64_t> tokens(g.channels.size()), remaining = q;
  for (std::size_t c = 0; c < g.channels.size(); ++c) tokens[c] = g.channels[c].initialTokens;
  out.maxTokens = tokens;
  if (std::optional<std::vector<ActorId>> order = flatSingleAppearanceOrder(g, q)) {
    for (ActorId a : *order) {
      if (q[a] == 0) continue;
      out.schedule.push_back({a, q[a]});
      for (std::size_t c : inputs[a]) {
        if (!g.channels[c].selfLoop()) tokens[c] -= q[a] * g.channels[c].consumption;
      }
      for (std::size_t c : outputs[a]) {
        if (g.channels[c].selfLoop()) continue;
        tokens[c] += q[a] * g.channels[c].production;
        out.maxTokens[c] = std::max(out.maxTokens[c], tokens[c]);
      }
    }
    out.deadlockFree = true;
    out.tokensAtEnd = std::move(tokens);
    return out;
  }
  // No flat single-appearance schedule: each pass fires every enabled actor as often as its tokens allow (as a run of firings); a pass
  // without any firing with firings left is a deadlock.
  for (bool progress = true; progress;) {
    progress = false;
    for (ActorId a = 0; a < n; ++a) {
      if (remaining[a] == 0) continue;
      std::int64_t times = remaining[a];
      for (std::size_t c : inputs[a]) {
        const Channel& ch = g.channels[c];
        if (ch.selfLoop()) times = std::min(times, tokens[c] >= ch.consumption ? times : 0);
        else times = std::min(times, tokens[c] / ch.consumption);
      }
      if (times == 0) continue;
      progress = true;
      remaining[a] -= times;
      if (!out.schedule.empty() && out.schedule.back().actor == a) out.schedule.back().times += times;
      else out.schedule.push_back({a, times});
      for (std::size_t c : inputs[a]) {
        if (!g.channels[c].selfLoop()) tokens[c] -= times * g.channels[c].consumption;
      }
      for (std::size_t c : outputs[a]) {
        if (g.channels[c].selfLoop()) continue;  // balanced: consumed and produced per firing
        tokens[c] += times * g.channels[c].production;
        out.maxTokens[c] = std::max(out.maxTokens[c], tokens[c]);
      }
    }
  }
  out.deadlockFree = std::all_of(remaining.begin(), remaining.end(), [](std::int64_t r) { return r == 0; });
  out.tokensAtEnd = std::move(tokens);
  return out;
}

std::string scheduleText(const Graph& g, const std::vector<FiringRun>& schedule) {
  std::string out;
  for (const FiringRun& run : schedule) {
    if (!out.empty()) out += ' ';
    if (run.times > 1) out += std::to_string(run.times);
    out += g.actors[run.actor].name;
  }
  return out;
}

}  // namespace semo::sdf
