#pragma once
// LTL model checking of the IR's properties under fairness: for each property, the product of the
// model with a Büchi automaton of the property's negation is explored, its strongly connected
// components are searched for a fair accepting cycle, and one found is printed as a lasso (a path,
// then a loop that repeats for ever). Fairness: a weakly fair rule enabled for ever is taken
// eventually; a strongly fair rule enabled again and again is taken again and again (specs/ir.md).
// "Proven" needs the whole product explored; a limit leaves the property "unknown".
//
// Symmetry: a property whose atoms every permutation of the interchangeable robots leaves unchanged
// is decided on the product of the quotient (one state per orbit). Fairness is per rule, and a
// rule of one robot is another robot's rule in a permuted state, so each component of the quotient
// is lifted back: the permutations along its cycles generate a group, and a rule counts as enabled
// everywhere (or taken) in the concrete component when its orbit under that group does (in the spirit
// of Emerson and Sistla's annotated quotient structures, kept to what the fairness check needs). The verdict is exact;
// a lasso comes from the concrete product.
#include <cstdint>
#include <future>
#include <string>
#include <vector>

#include "semo/checker/explicit_search.hpp"

namespace semo::checker {

// How a property's verdict was reached.
struct LivenessMethod {
  bool sliced = false;            // on a slice of the model (slicing.hpp), else on the whole product
  std::size_t keptVariables = 0;  // sliced: the variables of the deciding slice
  std::uint32_t refinements = 0;  // sliced: slices tried before it
  std::uint64_t states = 0;       // product states searched for this property (all slices, any fallback)
  std::string slicingGaveUp;      // why no slice decided, when the whole product was searched after them
  bool roundRobin = false;        // the violation was found under a round-robin scheduler (region_lasso.hpp)
  // Sliced: the deciding slice was too large to enumerate and was searched as decision diagrams
  // (symbolic_liveness.hpp); symbolicStates counts the product states of the slices so searched
  // (SymbolicOutcome::reachable).
  bool symbolic = false;
  double symbolicStates = 0;
  // Violated: the lasso was found by the hunt on the property's cone, without crashes
  // (symbolically), after no slice decided; keptVariables is the cone's.
  bool hunted = false;
  // Decided on the property's exact cone of influence, crashes and discoveries included, every
  // settling world searched symbolically (LivenessOptions::coneSeconds); keptVariables is the cone's.
  bool onCone = false;
  // onCone and proven within a superset of the reachable states bounded by these proven
  // invariants (LivenessOptions::provenInvariants); empty: on the exact reachable states.
  std::vector<std::string> assumedInvariants;
  // Violated: the lasso was found by random walks on the whole model (the walks-th), after no
  // slice decided.
  bool walked = false;
  std::uint32_t walks = 0;
  double seconds = 0;             // spent on this property
};

struct LivenessResult {
  std::vector<PropertyResult> properties;  // Model::properties in order
  std::vector<std::string> notes;          // per property: what its verdict needs said, or empty
  std::vector<LivenessMethod> methods;     // per property
  std::uint64_t states = 0;       // product states, summed over the properties
  std::uint64_t transitions = 0;  // product transitions, summed
  std::uint32_t reducedProperties = 0;  // searched up to symmetry (SearchLimits::symmetry)
  bool complete = true;           // every product explored whole
  std::string limitReached;
  double seconds = 0;
};

struct LivenessOptions {
  // The model is a slice (slicing.hpp): a step that would leave a variable's declared range is no
  // step (it is the image of no step of the model, whose updates stay in range: a step leaving one
  // is a modelling error the safety search reports), where on a model it stops the search.
  bool slice = false;
  // Decide each property without `next` on slices of the model first, refined by counterexamples
  // (sliced_liveness.cpp); a lasso is always one of the whole model.
  bool slicing = true;
  // When no slice decides, search the product of the whole model (within the limits).
  bool wholeProduct = true;
  // A slice whose product grows past this many states is not enumerated: it, and every larger
  // slice after it, is searched symbolically (or, without `symbolic`, given up, and the whole
  // product searched instead, if it may be). 50,000: enumerating a slice's product runs at 25,000
  // to 40,000 states a second, where the symbolic search decides a slice of a million states in a
  // fraction of a second (scouting's light watch: 904,064 states enumerated in 23 s, the next slice
  // counted in 0.2 s). With 500,000 scouting's check without mode_agreement took 78 s, with 50,000
  // 64 s, patrol's auto check 29.7 s and 13.0 s, the same verdicts (2026-12-03; 5,000,000 before
  // 2026-11-28: scouting 3 min, patrol 103 s).
  std::uint64_t sliceStates = 50'000;
  // A slice too large to enumerate is searched as decision diagrams (symbolic_liveness.hpp).
  bool symbolic = true;
  // The processor time all the symbolic searches of one property may take: its slices, then the
  // hunt on its cone (the last ninth, at most 20 s). 90 s: scouting's
  // leader_reelection[WatchLight] is proven on its 25th slice after about 44 s of them (since the
  // preimages through clusters, 2026-11-28; it was 80 to 130 s, hence three minutes before), and an
  // undecided property ends twice as soon.
  double symbolicSeconds = 90;
  // When the slices leave a property undecided (before the walks and the hunt, which can only find
  // a lasso, and then run only if this search gives up): the processor time for
  // searching its exact cone of influence, crashes and discoveries included, on every settling
  // world, each world's loops narrowed to the rules that can recur (sliced_liveness.cpp,
  // proveOnCone). 0 (the default): not tried. It can prove what the slices cannot, at a price:
  // scouting's mode_agreement took 1,724 s of it with its exact reachable states, about 70 s
  // within the superset its proven invariants bound (checker/README.md).
  double coneSeconds = 0;
  // The model's invariants (indices into ir::Model::invariants) the check has proven. The search
  // of an exact cone starts within a superset of the reachable states bounded by them, far cheaper
  // than the reachable states themselves (scouting's mode_agreement: checker/README.md, "The exact
  // cone"); a proof that used them names them.
  std::vector<std::size_t> provenInvariants;
  // Instead, when the search starts beside the safety proofs (verify.cpp): those invariants once
  // the proofs end. Only an exact cone waits for them, when it starts; a promise broken (the proofs
  // ended in an error) leaves the cone out.
  std::shared_future<std::vector<std::size_t>> provenInvariantsLater;
  // When no slice decides (nor the exact cone, when asked), random walks on the whole model hunt a
  // fair violation (lasso_walks.hpp; at most 10 s), before the symbolic hunt and the round-robin one.
  bool walks = true;
  std::uint64_t walkSeed = 1;  // the same seed gives the same walks
  // Search the whole product first, within this many product states, and go to the slices only
  // when it does not fit (0: slices first). The caller sets it when the model's whole state space
  // is known to be small (verify.cpp: a complete safety search of at most 500,000 states): an
  // exact search of a small product takes a fraction of a second where refining slices took
  // seconds to minutes (the swarm of 20 robots: 21,166 states, mode_agreement 148 s on 21 slices).
  std::uint64_t wholeFirstStates = 0;
  // Never set wholeFirstStates: slices first whatever the model's size (`check --slices-first`).
  bool slicesFirst = false;
};

// Each property has its own product; up to limits.threads of them are searched at once, each
// within limits.maxStates and an equal share of limits.maxMemoryBytes (one that outgrows its share
// is searched again afterwards, alone, with the whole budget).
LivenessResult checkLiveness(const ir::Model& model, const SearchLimits& limits, const LivenessOptions& options = {});

}  // namespace semo::checker
