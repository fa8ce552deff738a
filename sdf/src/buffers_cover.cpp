#include "buffers_cover.hpp"

#include <algorithm>
#include <cstddef>

namespace semo::sdf {

namespace {

class Cover {
 public:
  Cover(const std::vector<std::int64_t>& lowest, const std::vector<char>& counted, const std::vector<const CoverClause*>& clauses, std::int64_t neededTotal)
      : current_(lowest), highest_(lowest.size(), INT64_MAX), used_(lowest.size(), 0), clauses_(clauses), neededTotal_(neededTotal) {
    for (std::size_t c = 0; c < lowest.size(); ++c) {
      if (counted[c]) cost_ += lowest[c];
    }
  }

  // Iterative deepening on the total: a search that admits totals up to a bound, pruning where the
  // total so far plus what the open clauses still need passes it; the first bound is a lower bound
  // on every cover, each next one the smallest total a pruned branch could still reach, so the first
  // cover found is a cheapest one.
  CoverResult run() {
    CoverResult out;
    bound_ = neededTotal_;
    for (;;) {
      nextBound_ = INT64_MAX;
      search();
      if (found_ || nextBound_ == INT64_MAX) break;
      bound_ = nextBound_;
    }
    out.nodes = nodes_;
    if (found_) out.capacities = best_;
    return out;
  }

 private:
  bool holds(const CoverLiteral& l) const { return current_[l.channel] >= l.atLeast; }
  bool possible(const CoverLiteral& l) const { return l.atLeast <= highest_[l.channel]; }
  std::int64_t raise(const CoverLiteral& l) const { return l.atLeast - current_[l.channel]; }

  void search() {
    ++nodes_;
    std::vector<std::pair<std::int64_t, const CoverClause*>> open;  // (cheapest raise, clause)
    const CoverClause* branchOn = nullptr;
    std::size_t fewestWays = SIZE_MAX;
    for (const CoverClause* clause : clauses_) {
      if (std::any_of(clause->begin(), clause->end(), [&](const CoverLiteral& l) { return holds(l); })) continue;
      std::size_t ways = 0;
      std::int64_t cheapest = INT64_MAX;
      for (const CoverLiteral& l : *clause) {
        if (!possible(l)) continue;
        ++ways;
        cheapest = std::min(cheapest, raise(l));
      }
      if (ways == 0) return;
      open.push_back({cheapest, clause});
      if (ways < fewestWays) {
        fewestWays = ways;
        branchOn = clause;
      }
    }
    const std::int64_t reachable = open.empty() ? cost_ : cost_ + neededAtLeast(open);
    if (reachable > bound_) {
      nextBound_ = std::min(nextBound_, reachable);
      return;
    }
    if (open.empty()) {
      found_ = true;
      best_ = current_;
      return;
    }
    // A clause with one way out: take it. Else branch on the raise that meets the most open clauses
    // per unit of total (either it is made, or the channel stays below it): the first dive is the
    // greedy cover, and shared raises come first.
    CoverLiteral chosen{};
    if (fewestWays == 1) {
      for (const CoverLiteral& l : *branchOn) {
        if (possible(l)) chosen = l;
      }
    } else {
      double bestScore = -1;
      for (const auto& [cheapest, clause] : open) {
        for (const CoverLiteral& l : *clause) {
          if (!possible(l)) continue;
          std::size_t meets = 0;
          for (const auto& [other, otherClause] : open) {
            if (std::any_of(otherClause->begin(), otherClause->end(),
                            [&](const CoverLiteral& o) { return o.channel == l.channel && o.atLeast <= l.atLeast; })) {
              ++meets;
            }
          }
          const double score = static_cast<double>(meets) / static_cast<double>(raise(l));
          if (score > bestScore) {
            bestScore = score;
            chosen = l;
          }
        }
      }
    }
    const std::int64_t before = current_[chosen.channel];
    current_[chosen.channel] = chosen.atLeast;
    cost_ += chosen.atLeast - before;
    search();
    cost_ -= chosen.atLeast - before;
    current_[chosen.channel] = before;
    if (found_ || fewestWays == 1) return;
    const std::int64_t savedHighest = highest_[chosen.channel];
    highest_[chosen.channel] = chosen.atLeast - 1;
    search();
    highest_[chosen.channel] = savedHighest;
  }

  // What the open clauses still need: over clauses whose possible channels are pairwise disjoint
  // (one raise helps at most one of them), each at least its cheapest raise.
  std::int64_t neededAtLeast(std::vector<std::pair<std::int64_t, const CoverClause*>>& open) {
    std::sort(open.begin(), open.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::int64_t sum = 0;
    std::vector<std::uint32_t> marked;
    for (const auto& [cheapest, clause] : open) {
      if (std::any_of(clause->begin(), clause->end(), [&](const CoverLiteral& l) { return possible(l) && used_[l.channel]; })) continue;
      sum += cheapest;
      for (const CoverLiteral& l : *clause) {
        if (possible(l) && !used_[l.channel]) {
          used_[l.channel] = 1;
          marked.push_back(l.channel);
        }
      }
    }
    for (std::uint32_t c : marked) used_[c] = 0;
    return sum;
  }

  std::vector<std::int64_t> current_, highest_;
  std::vector<char> used_;
  const std::vector<const CoverClause*>& clauses_;
  std::int64_t neededTotal_;
  std::int64_t cost_ = 0, bound_ = 0, nextBound_ = 0;
  bool found_ = false;
  std::vector<std::int64_t> best_;
  std::uint64_t nodes_ = 0;
};

}  // namespace

CoverResult cheapestCover(const std::vector<std::int64_t>& lowest, const std::vector<char>& counted, const std::vector<CoverClause>& clauses,
                          const std::vector<std::size_t>& active, std::int64_t neededTotal, CoverParts& known) {
  // Channels joined by a clause, in one part (union-find).
  std::vector<std::size_t> parent(lowest.size());
  for (std::size_t c = 0; c < parent.size(); ++c) parent[c] = c;
  auto root = [&](std::size_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  // A clause of one raise is a lower bound: raise first (every cover does), then drop what holds.
  std::vector<std::int64_t> raised = lowest;
  for (std::size_t i : active) {
    if (clauses[i].size() == 1) raised[clauses[i][0].channel] = std::max(raised[clauses[i][0].channel], clauses[i][0].atLeast);
  }
  std::vector<std::size_t> open;  // clauses the raised capacities do not meet
  for (std::size_t i : active) {
    const CoverClause& clause = clauses[i];
    if (std::any_of(clause.begin(), clause.end(), [&](const CoverLiteral& l) { return raised[l.channel] >= l.atLeast; })) continue;
    open.push_back(i);
    for (const CoverLiteral& l : clause) parent[root(l.channel)] = root(clause.front().channel);
  }
  std::map<std::size_t, std::vector<std::size_t>> parts;
  for (std::size_t i : open) parts[clauses[i].empty() ? SIZE_MAX : root(clauses[i].front().channel)].push_back(i);
  CoverResult out;
  if (parts.size() <= 1) {
    std::vector<const CoverClause*> mine;
    for (std::size_t i : open) mine.push_back(&clauses[i]);
    return Cover(raised, counted, mine, neededTotal).run();
  }
  std::vector<std::int64_t> capacities = raised;
  for (const auto& [channel, part] : parts) {
    // The part's answer depends on its clauses and on the raised capacities of its channels.
    std::vector<std::int64_t> key(part.begin(), part.end());
    for (std::size_t c = 0; c < raised.size(); ++c) {
      if (root(c) == channel) key.push_back(raised[c]);
    }
    auto it = known.find(key);
    if (it == known.end()) {
      std::vector<const CoverClause*> mine;
      for (std::size_t i : part) mine.push_back(&clauses[i]);
      CoverResult r = Cover(raised, counted, mine, INT64_MIN).run();
      out.nodes += r.nodes;
      if (!r.capacities) return out;
      std::vector<CoverLiteral> more;
      for (std::size_t c = 0; c < raised.size(); ++c) {
        if ((*r.capacities)[c] != raised[c]) more.push_back({static_cast<std::uint32_t>(c), (*r.capacities)[c]});
      }
      it = known.emplace(std::move(key), std::move(more)).first;
    }
    for (const CoverLiteral& l : it->second) capacities[l.channel] = l.atLeast;
  }
  out.capacities = std::move(capacities);
  return out;
}

}  // namespace semo::sdf
