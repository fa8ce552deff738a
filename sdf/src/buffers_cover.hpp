#pragma once
// The smallest total capacity that meets a set of "raise one of these" constraints (the conflicts the
// buffer exploration learns from cycles, buffers.cpp): each clause is satisfied when at least one of
// its channels has at least the capacity it names. An exact branch and bound: it branches on an
// unsatisfied clause with the fewest ways out, one branch per literal, and in the i-th branch forbids
// the literals of the branches before it (their channels stay below those capacities), so no
// distribution is reached twice; it prunes a branch whose cost plus a lower bound on what its
// unsatisfied clauses still need (over clauses with pairwise disjoint channels, each at least its
// cheapest raise) cannot beat the best found.
#include <cstdint>
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

// `lowest`: per channel, the smallest capacity; `counted`: whether the channel counts in the total
// (self-loops do not, and appear in no clause). The search stops at the first cover whose total is
// `enough` (a total known to be needed anyway).
CoverResult cheapestCover(const std::vector<std::int64_t>& lowest, const std::vector<char>& counted, const std::vector<const CoverClause*>& clauses,
                          std::int64_t enough);

}  // namespace semo::sdf
