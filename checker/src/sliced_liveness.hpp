#pragma once
// A liveness property decided on slices of the model (slicing.hpp), refined until a slice proves
// it, or a lasso found on a slice is rebuilt on the whole model (counterexample-guided abstraction
// refinement): see sliced_liveness.cpp.
#include <cstdint>
#include <optional>
#include <string>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/slicing.hpp"

namespace semo::checker::detail {

struct SlicedOutcome {
  PropertyResult property;        // proven, violated with a lasso of the whole model, or unknown
  std::uint64_t states = 0, transitions = 0;  // the slices' products, summed over the refinements
  std::size_t keptVariables = 0;  // of the slice that decided
  std::uint32_t refinements = 0;  // slices tried before it
  bool reduced = false;           // the deciding slice was searched up to symmetry
  std::string why;                // when unknown: why no slice decided
  // A slice too large to enumerate is searched symbolically (symbolic_liveness.hpp): when that
  // proves it, these say so.
  bool symbolic = false;
  double symbolicStates = 0;      // the slice's product states searched, counted
  // The violation was found by the hunt on the property's cone (sliced_liveness.cpp), after no
  // slice decided; keptVariables is then the cone's.
  bool hunted = false;
  // Decided on the property's exact cone, crashes and discoveries included, every settling world
  // searched with its loops narrowed (sliced_liveness.cpp, proveOnCone); keptVariables is the cone's.
  bool onCone = false;
  // onCone and proven: the proven invariants (their names) the search assumed, its reachable states
  // over-approximated within them (projected_reach.hpp); empty when it computed them exactly.
  std::vector<std::string> assumedInvariants;
  double symbolicSeconds = 0;     // spent in symbolic searches (slices and hunt)
  // The violation was found by random walks on the whole model (lasso_walks.hpp), after no slice
  // decided, in the `walks`-th walk.
  bool walked = false;
  std::uint32_t walks = 0;
  double walkSeconds = 0;
};

// Each slice's product is searched within `sliceStates` states (and limits.maxStates): a slice
// that grows past it leaves the property to the whole product, if the caller searches it.
// With `symbolic`, a slice too large to enumerate is searched symbolically (symbolic_liveness.hpp).
// The hunt on the property's cone, as checkSliced runs it when no slice decided: a violation found
// there and rebuilt on the whole model becomes `out`'s verdict (hunted); otherwise out.why says how
// the hunt ended. Never a proof.
void huntOnCone(const CompiledModel& full, std::size_t property, const SearchLimits& limits, SlicedOutcome& out,
                const ControlFacts* facts = nullptr, double symbolicSeconds = LivenessOptions{}.symbolicSeconds);

// The search of the property's exact cone of influence, crashes and discoveries included, on every
// settling world, each world's loops narrowed to the rules that can recur (recurring_rules.hpp),
// within `seconds` of processor time: a proof or a lasso rebuilt on the whole model becomes
// `out`'s verdict (onCone); otherwise out.why says how it ended. `provenInvariants` (indices into
// the model's invariants, proven by the check) bound the superset of the reachable states the
// search starts from (projected_reach.hpp).
void proveOnCone(const CompiledModel& full, const ControlFacts& facts, std::size_t property, const SearchLimits& limits,
                 SlicedOutcome& out, double seconds, const std::vector<std::size_t>& provenInvariants = {});

// Random walks on the whole model for a fair violation (lasso_walks.hpp): a lasso found becomes
// `out`'s verdict (walked); otherwise out.why says how many walks found none. Never a proof.
void walkForLasso(const CompiledModel& full, std::size_t property, const SearchLimits& limits, std::uint64_t seed, SlicedOutcome& out);

// `facts` are the model's control facts (slicing.hpp), computed once for all its properties. The
// slices first, each enumerated within `options.sliceStates` product states, or, with
// `options.symbolic`, searched symbolically once too large. When no slice decides: with
// `options.coneSeconds` > 0 the search of the exact cone, which can prove; then, if still
// undecided, random walks (`options.walks`) and the hunt on the cone, which can only find a lasso.
// The symbolic searches but the exact cone share `options.symbolicSeconds` of processor time.
SlicedOutcome checkSliced(const CompiledModel& full, const ControlFacts& facts, std::size_t property, const SearchLimits& limits,
                          const LivenessOptions& options);

}  // namespace semo::checker::detail
