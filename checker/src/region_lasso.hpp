#pragma once
// A lasso of the whole model looked for inside a region of its states: the region a slice's loop
// sees (sliced_liveness.cpp), when the slice's own loop cannot be followed step by step but the
// model may loop there in another order. An under-approximation: only a violation is ever
// concluded from it, and only once checkLasso accepts the lasso on the whole model.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/trace.hpp"

namespace semo::checker::detail {

struct RegionSearch {
  std::optional<Trace> lasso;  // from `start`: a fair accepting cycle of the product, and the way to it
  std::uint64_t states = 0;    // product states explored
  std::string why;             // when no lasso: why
};

// The product of the model with the property's negation, explored breadth-first from `start`
// within `maxStates`; only the states `inRegion` accepts are expanded (the others get no edges, so
// that a fair cycle of the part explored is one of the whole product: liveness_product.hpp).
RegionSearch lassoInRegion(const CompiledModel& cm, const ir::Property& property, const std::vector<Value>& start,
                           const std::function<bool(const Value*)>& inRegion, std::uint64_t maxStates);

// The product explored from the initial state under a round-robin scheduler over the fairness
// groups (Product::roundRobin) within `maxStates`: most interleavings of the robots' steps are left
// out, so that a fair accepting cycle deep in a model too large to search whole may be in reach.
// A lasso is returned only when checkLasso accepts it on the whole model.
RegionSearch lassoUnderRoundRobin(const CompiledModel& cm, const ir::Property& property, std::uint64_t maxStates);

}  // namespace semo::checker::detail
