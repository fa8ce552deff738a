#pragma once
// The smallest total capacity that meets a set of "raise one of these" constraints (the conflicts the
// buffer exploration learns from cycles, buffers.cpp): each clause is satisfied when at least one of
// its channels has at least the capacity it names. Exact, by branch and bound: a clause with a
// single way out left is taken; otherwise it branches on the raise that meets the most open clauses
// per unit of total, either made or forbidden (the channel stays below it), so the two branches
// share no distribution and together hold them all. A branch is pruned when its total plus a lower
// bound on what its open clauses still need (over clauses with pairwise disjoint channels, each at
// least its cheapest raise) passes the current bound; the bound starts at a total every cover needs
// and rises to the smallest pruned total each round (iterative deepening), so the first cover found
// is a cheapest one.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace semo::sdf {

struct CoverLiteral {
  std::uint32_t channel = 0;
  std::int64_t atLeast = 0;  // a capacity on the channel's grid
};
using CoverClause = std::vector<CoverLiteral>;

struct CoverResult {
  std::optional<std::vector<std::int64_t>> capacities;  // none: the clauses cannot all hold
  std::uint64_t nodes = 0;                              // branch and bound nodes visited
};

// Clauses that share no channel with the others form independent parts, each solved on its own
// (the cheapest cover is the lowest capacities raised by each part's cheapest raise); a part's
// answer is kept, by its clauses and its channels' lowest capacities, for the next call.
using CoverParts = std::map<std::vector<std::int64_t>, std::vector<CoverLiteral>>;

// `lowest`: per channel, the smallest capacity; `counted`: whether the channel counts in the total
// (self-loops do not, and appear in no clause). `active`: the indices of the clauses to meet in
// `clauses`. `neededTotal`: a total every cover is known to need (a start for the search).
CoverResult cheapestCover(const std::vector<std::int64_t>& lowest, const std::vector<char>& counted, const std::vector<CoverClause>& clauses,
                          const std::vector<std::size_t>& active, std::int64_t neededTotal, CoverParts& known);

}  // namespace semo::sdf
