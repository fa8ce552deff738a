#include "semo/sdf/buffers.hpp"

#include <algorithm>
#include <numeric>
#include <set>

#include "buffers_cover.hpp"
#include "semo/sdf/automorphisms.hpp"
#include "semo/sdf/cycle_ratio.hpp"

// The front, exactly, by learning from cycles (why nothing better is missed).
//
// Write P(d) for the period with the distribution d: the maximum cycle ratio of the HSDF expansion
// with space edges (cycle_ratio.hpp). Take a cycle of that expansion under d, of ratio r, whose
// space edges belong to the channels S. Under any distribution d' that leaves each channel of S
// below the capacity that moves its edge on the cycle (whatever d' does elsewhere), that producer
// firing waits for the same consumer firing or a later one, which ends no earlier (firings of an
// actor end in order): the cycle's inequalities still hold in the self-timed execution, so
// P(d') >= r. Hence every distribution with a period below r raises some channel of S to the
// capacity that moves its edge: a clause. A cycle without delay (a deadlock) gives a clause that
// every distribution with a throughput meets.
//
// One query: the smallest total whose period is below p (or without deadlock). The cheapest
// distribution meeting every clause learnt from cycles of ratio >= p (buffers_cover.hpp, exact)
// costs no more than the answer, since the answer meets them all; if its period is below p it is
// the answer, else its critical cycle (ratio >= p) gives a clause it breaks, and the query goes on
// (it ends: each round excludes the distribution just evaluated). Clauses are kept: those of ratio
// >= p hold for every later, smaller p.
//
// The front: after the smallest total without deadlock, each query asks for a period below the best
// so far. An answer of the same total replaces the point (a better period for that total); a larger
// total T' means no total below T' does better, so the previous point stands. It ends at the period
// with unbounded channels.
//
// Symmetry: for an automorphism s of the graph (automorphisms.hpp, each checked exactly), the
// distribution d and its image s(d) (s(d)[s(c)] = d[c]) have the same expansion up to renaming, so
// the same period. A distribution d' that leaves every s(c), c in S, below the clause's capacities
// is the image of s^-1(d'), which leaves every c in S below them: P(d') = P(s^-1(d')) >= r. So the
// clause's images are clauses too; learning them (or part of them) only learns more true clauses.
//
// Capacities: only each channel's grid, its smallest capacity plus multiples of g = gcd(p, c), is
// tried. Tokens and claimed space on a channel always add up to d plus a multiple of g and every
// claim is a multiple of g, so a capacity off the grid lets a producer claim exactly what the grid
// value below it lets it claim, for a larger total; and below the smallest capacity the channel
// alone deadlocks.

namespace semo::sdf {

namespace {

__extension__ typedef __int128 Wide;  // GCC and Clang: exact cross products of two 64-bit values

// a is a longer period (a lower throughput) than b.
bool slower(const Period& a, const Period& b) { return static_cast<Wide>(a.num) * b.den > static_cast<Wide>(b.num) * a.den; }

// Where a clause comes from: the ratio of its cycle, or a deadlock.
struct LearntFrom {
  bool deadlock = false;  // from a cycle without delay: holds for every target
  Period ratio;
};

class FrontSearch {
 public:
  FrontSearch(const Graph& g, const std::vector<std::int64_t>& q, std::uint64_t maxDistributions, ParetoFront& out)
      : g_(g), expansion_(g, q), maxDistributions_(maxDistributions), out_(out) {
    const std::size_t m = g.channels.size();
    lowest_.resize(m);
    step_.resize(m);
    counted_.resize(m);
    for (std::size_t c = 0; c < m; ++c) {
      lowest_[c] = smallestCapacity(g.channels[c]);
      step_[c] = std::gcd(g.channels[c].production, g.channels[c].consumption);
      counted_[c] = g.channels[c].selfLoop() ? 0 : 1;
    }
    automorphisms_ = findAutomorphisms(g);
  }

  void run() {
    if (!expansion_.error().empty()) {
      out_.error = expansion_.error();
      return;
    }
    const CycleRatioResult unbounded = expansion_.evaluate({});
    if (!unbounded.error.empty() || unbounded.deadlock || unbounded.cycles.empty()) {
      out_.error = !unbounded.error.empty() ? unbounded.error
                   : unbounded.deadlock     ? "the graph deadlocks even with unbounded channels"
                                            : "with unbounded channels no cycle limits the throughput";
      return;
    }
    out_.best = unbounded.period;
    std::vector<std::int64_t> capacities = lowest_;
    CycleRatioResult r;
    if (!evaluate(capacities, r)) return;
    if (r.deadlock) {
      out_.points.push_back({total(lowest_), lowest_, true, {}});
      learn(r, std::nullopt);
      if (!query(std::nullopt, total(lowest_), capacities, r)) return;
    }
    BufferPoint current{total(capacities), capacities, false, r.period};
    while (slower(current.period, out_.best)) {
      if (!query(current.period, current.total, capacities, r)) {
        out_.points.push_back(current);  // reached, but perhaps not the best of its total: the error says so
        return;
      }
      if (total(capacities) != current.total) out_.points.push_back(current);
      current = {total(capacities), capacities, false, r.period};
    }
    out_.points.push_back(current);
  }

 private:
  std::int64_t total(const std::vector<std::int64_t>& capacities) const {
    std::int64_t sum = 0;
    for (std::size_t c = 0; c < capacities.size(); ++c) sum += counted_[c] ? capacities[c] : 0;
    return sum;
  }

  bool evaluate(const std::vector<std::int64_t>& capacities, CycleRatioResult& r) {
    if (++out_.distributions > maxDistributions_) {
      out_.error = "more than " + std::to_string(maxDistributions_) + " distributions explored";
      return false;
    }
    std::vector<std::optional<std::int64_t>> bounds(capacities.size());
    for (std::size_t c = 0; c < capacities.size(); ++c) {
      if (counted_[c]) bounds[c] = capacities[c];
    }
    r = expansion_.evaluate(bounds);
    if (!r.error.empty()) out_.error = r.error;
    return r.error.empty();
  }

  // The capacity on channel c's grid at or above `capacity`.
  std::int64_t onGrid(std::size_t c, std::int64_t capacity) const {
    if (capacity <= lowest_[c]) return lowest_[c];
    return lowest_[c] + (capacity - lowest_[c] + step_[c] - 1) / step_[c] * step_[c];
  }

  // Keeps a clause for each cycle of `r` that holds the target back, with its images under the
  // graph's automorphisms. Returns whether a cycle did.
  bool learn(const CycleRatioResult& r, const std::optional<Period>& target) {
    bool any = false;
    for (const RatioCycle& cycle : r.cycles) {
      if (!cycle.deadlock && target && slower(*target, cycle.ratio)) continue;  // below the target: no obstacle
      if (!cycle.deadlock && !target) continue;
      CoverClause clause;
      for (const SpaceOnCycle& s : cycle.space) clause.push_back({static_cast<std::uint32_t>(s.channel), onGrid(s.channel, s.capacityThatMovesIt)});
      any = true;
      // The orbit of the clause (breadth first over the generators; bounded, any part of it is sound).
      std::vector<CoverClause> orbit{clause};
      keep(cycle, clause);
      for (std::size_t i = 0; i < orbit.size() && orbit.size() < kMaxOrbit; ++i) {
        for (const Automorphism& sigma : automorphisms_) {
          CoverClause image = orbit[i];
          for (CoverLiteral& l : image) l.channel = static_cast<std::uint32_t>(sigma.channel[l.channel]);
          if (keep(cycle, image)) orbit.push_back(std::move(image));
        }
      }
    }
    return any;
  }

  // Adds the clause unless it is known (with the same origin). Returns whether it was new.
  bool keep(const RatioCycle& cycle, CoverClause clause) {
    std::sort(clause.begin(), clause.end(), [](const CoverLiteral& a, const CoverLiteral& b) { return a.channel < b.channel; });
    std::vector<std::int64_t> key{cycle.deadlock ? 1 : 0, cycle.ratio.num, cycle.ratio.den};
    for (const CoverLiteral& l : clause) key.insert(key.end(), {static_cast<std::int64_t>(l.channel), l.atLeast});
    if (!known_.insert(std::move(key)).second) return false;
    learnt_.push_back({cycle.deadlock, cycle.ratio});
    clauses_.push_back(std::move(clause));
    return true;
  }

  // The smallest total (at least `needed`) whose distribution has no deadlock and, with a target, a
  // period below it.
  bool query(const std::optional<Period>& target, std::int64_t needed, std::vector<std::int64_t>& capacities, CycleRatioResult& r) {
    for (;;) {
      std::vector<std::size_t> active;
      for (std::size_t i = 0; i < learnt_.size(); ++i) {
        if (learnt_[i].deadlock || (target && !slower(*target, learnt_[i].ratio))) active.push_back(i);
      }
      if (std::any_of(active.begin(), active.end(), [&](std::size_t i) { return clauses_[i].empty(); })) {
        out_.error = "no distribution reaches the period";  // cannot happen above the unbounded period
        return false;
      }
      CoverResult cover = cheapestCover(lowest_, counted_, clauses_, active, needed, parts_);
      coverNodes_ += cover.nodes;
      if (!cover.capacities) {
        out_.error = "no distribution reaches the period";
        return false;
      }
      capacities = *cover.capacities;
      if (!evaluate(capacities, r)) return false;
      if (!r.deadlock && (!target || slower(*target, r.period))) return true;
      if (!learn(r, target)) {
        out_.error = "a cycle holds the throughput back but was not learnt";  // cannot happen: the critical cycle is one
        return false;
      }
      needed = total(capacities);
    }
  }

  const Graph& g_;
  HsdfExpansion expansion_;
  std::uint64_t maxDistributions_;
  ParetoFront& out_;
  std::vector<std::int64_t> lowest_, step_;
  std::vector<char> counted_;
  static constexpr std::size_t kMaxOrbit = 10'000;
  std::vector<Automorphism> automorphisms_;
  std::set<std::vector<std::int64_t>> known_;  // the clauses kept, with their origins
  std::vector<LearntFrom> learnt_;  // per clause
  std::vector<CoverClause> clauses_;
  CoverParts parts_;
  std::uint64_t coverNodes_ = 0;
};

}  // namespace

std::int64_t smallestCapacity(const Channel& c) {
  if (c.selfLoop()) return 0;
  const std::int64_t g = std::gcd(c.production, c.consumption);
  return std::max(c.initialTokens, c.production + c.consumption - g + c.initialTokens % g);
}

ParetoFront bufferParetoFront(const Graph& g, const std::vector<std::int64_t>& q, std::uint64_t maxDistributions) {
  ParetoFront out;
  FrontSearch(g, q, maxDistributions, out).run();
  return out;
}

}  // namespace semo::sdf
