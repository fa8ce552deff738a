#include "buffers_cover.hpp"

#include <algorithm>
#include <cstddef>

namespace semo::sdf {

namespace {

class Cover {
 public:
  Cover(const std::vector<std::int64_t>& lowest, const std::vector<char>& counted, const std::vector<const CoverClause*>& clauses, std::int64_t enough)
      : current_(lowest), highest_(lowest.size(), INT64_MAX), used_(lowest.size(), 0), clauses_(clauses), enough_(enough) {
    for (std::size_t c = 0; c < lowest.size(); ++c) {
      if (counted[c]) cost_ += lowest[c];
    }
  }

  CoverResult run() {
    search();
    CoverResult out;
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
    if (open.empty()) {
      if (!found_ || cost_ < bestCost_) {
        found_ = true;
        bestCost_ = cost_;
        best_ = current_;
      }
      return;
    }
    if (found_ && cost_ + neededAtLeast(open) >= bestCost_) return;
    std::vector<CoverLiteral> ways;
    for (const CoverLiteral& l : *branchOn) {
      if (possible(l)) ways.push_back(l);
    }
    std::sort(ways.begin(), ways.end(), [&](const CoverLiteral& a, const CoverLiteral& b) { return raise(a) < raise(b); });
    std::vector<std::int64_t> savedHighest;
    for (const CoverLiteral& l : ways) savedHighest.push_back(highest_[l.channel]);
    for (const CoverLiteral& l : ways) {
      const std::int64_t before = current_[l.channel];
      current_[l.channel] = l.atLeast;
      cost_ += l.atLeast - before;
      search();
      cost_ -= l.atLeast - before;
      current_[l.channel] = before;
      if (found_ && bestCost_ <= enough_) break;
      // The later branches leave this channel below the capacity: covers with it are all in this one.
      highest_[l.channel] = l.atLeast - 1;
    }
    for (std::size_t i = 0; i < ways.size(); ++i) highest_[ways[i].channel] = savedHighest[i];
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
  std::int64_t enough_;
  std::int64_t cost_ = 0, bestCost_ = 0;
  bool found_ = false;
  std::vector<std::int64_t> best_;
  std::uint64_t nodes_ = 0;
};

}  // namespace

CoverResult cheapestCover(const std::vector<std::int64_t>& lowest, const std::vector<char>& counted, const std::vector<const CoverClause*>& clauses,
                          std::int64_t enough) {
  return Cover(lowest, counted, clauses, enough).run();
}

}  // namespace semo::sdf
