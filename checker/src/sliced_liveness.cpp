// Liveness on slices, refined by counterexamples (sliced_liveness.hpp).
//
// The first slice keeps only the variables the property reads. Each slice is searched as any model
// is (the product with the property's Büchi automaton, fairness, symmetry). When it proves the
// property, the property holds on the model (slicing.hpp). When it finds a lasso, the lasso is
// rebuilt on the whole model step by step (slice_lasso_rebuild.hpp). Where the rebuilding fails,
// the rule at fault reads variables the slice left out: they are kept and the next slice searched.
// A lasso is reported only when checkLasso passes on the whole model. When no slice decides, a hunt
// on the property's exact cone looks for a violation the slices' lassos kept missing.
#include "sliced_liveness.hpp"
#include "symbolic_liveness.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <optional>

#include "semo/checker/fairness.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/slicing.hpp"
#include "lasso_walks.hpp"
#include "recurring_rules.hpp"
#include "slice_lasso_rebuild.hpp"
#include "symmetry_finder.hpp"

namespace semo::checker::detail {

namespace {

using rebuild::Concretizer;

constexpr std::uint32_t kMaxRefinements = 32;

// Of a property's symbolic time (LivenessOptions::symbolicSeconds), the hunt on its cone keeps
// the last ninth up to 180 s of it (20 s), and half of what is given beyond: the slices of a large
// model stop gaining long before its hunt has searched every settling world (scouting's light
// watch handed over: 160 s; specs/examples/README.md).
double huntSeconds(double symbolicSeconds) {
  return symbolicSeconds <= 180 ? symbolicSeconds / 9 : 20 + (symbolicSeconds - 180) / 2;
}

// With the exact cone to follow (--cone-seconds), the symbolic slices stop once one would hold this
// much of the cone's variables: its reachable states cost about what the cone's whole search does,
// and a proof there is rare. Scouting's mode_agreement: slices of 39, 41 and 42 of the cone's 61
// variables took 64 s and decided nothing, the cone then 46 s; with 0.6 those of 31, 32 and 33 took
// 17 s more and decided nothing either. The largest deciding slice known, leader_reelection
// [WatchLight]'s, holds 29 of its cone's 61 (48%): a property whose proof needs a slice past half
// its cone is proven on the cone instead, later (checker/README.md, "Sooner to the cone").
constexpr double kSliceShareOfCone = 0.5;

// A lasso that failed on one robot mostly has a twin on each robot that looks alike, which fails
// the same way one round later: scouting's light watch needed ev3_0's Watch, then ev3_1's; 7 of
// its 18 refinements were the twin of an earlier one. So a refinement also keeps each variable it
// names on the robots that look alike (lookalikeClasses, symmetry_finder.hpp):
// - on robots the property does not name, always: the light watch's re-election names the
//   burgers, and with the ev3s' twins it took 13 rounds and 10.8 s instead of 19 and 17.6 s, on
//   the same slice of 29 variables;
// - on robots it names the same way (their same variables are its own), only once the slices
//   are searched symbolically, where a round costs seconds, not milliseconds. In the first, cheap
//   rounds they changed which lassos were found, and the light watch then needed 40 variables
//   (24.9 s). From the symbolic rounds on, they take mode_agreement's slices to half its cone in
//   6 rounds and 8 s instead of 9 and 24 s, and the light watch is proven on 30 variables.
// The robots need not be interchangeable (scouting's are not: its elections tell them apart):
// which variables a slice keeps only decides how soon it decides, never what (slicing.hpp).
class Twins {
 public:
  Twins(const ir::Model& model, const std::vector<ir::VarId>& own)
      : classes_(lookalikeClasses(model)), place_(model.variables.size()) {
    std::vector<char> isOwn(model.variables.size(), 0);
    for (ir::VarId v : own) isOwn[v] = 1;
    named_.resize(classes_.size());
    for (std::uint32_t c = 0; c < classes_.size(); ++c) {
      const LookalikeClass& k = classes_[c];
      named_[c].resize(k.robots.size());
      for (std::uint32_t i = 0; i < k.robots.size(); ++i) {
        for (std::uint32_t j = 0; j < k.blocks[i].size(); ++j) {
          place_[k.blocks[i][j]] = Place{c, i, j};
          if (isOwn[k.blocks[i][j]] != 0) named_[c][i].push_back(j);
        }
      }
    }
  }

  // Keeps v's twins: on every robot of its class that the property does not name, when v's robot is
  // one of them; with `named`, when its robot is named, on every robot named the same way (the
  // same places of their blocks hold the property's own variables).
  void keep(ir::VarId v, bool named, std::vector<char>& keep) const {
    const Place& p = place_[v];
    if (p.cls == kNone) return;
    const std::vector<std::uint32_t>& how = named_[p.cls][p.robot];
    if (!how.empty() && !named) return;
    const LookalikeClass& k = classes_[p.cls];
    for (std::uint32_t i = 0; i < k.robots.size(); ++i) {
      if (named_[p.cls][i] == how) keep[k.blocks[i][p.at]] = 1;
    }
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  struct Place {
    std::uint32_t cls = kNone, robot = 0, at = 0;
  };
  std::vector<LookalikeClass> classes_;
  std::vector<Place> place_;
  // Per class and robot: the places of its block that hold the property's own variables.
  std::vector<std::vector<std::vector<std::uint32_t>>> named_;
};

SlicedOutcome refineSlices(const CompiledModel& full, const ControlFacts& facts, std::size_t property, const SearchLimits& limits,
                           std::uint64_t sliceStates, bool symbolic, double symbolicBudget, std::size_t coneVariables) {
  // Slices are cut from the model with the control facts applied (slicing.hpp): the same runs.
  const ir::Model& model = facts.model;
  const ir::Property& prop = model.properties.at(property);
  SlicedOutcome out;
  out.property = {prop.name, prop.origin, Verdict::Unknown, {}};
  std::vector<char> keep(model.variables.size(), 0);
  SearchLimits sub = limits;
  sub.threads = 1;
  sub.maxStates = std::min(limits.maxStates, sliceStates);
  sub.onPhase = nullptr;  // a slice's verdict is not the property's: the rounds are said below
  LivenessOptions plain;
  plain.slicing = false;
  plain.slice = true;
  double symbolicSeconds = 0;
  bool enumerate = true;
  std::optional<Twins> twins;  // found on the first slice: the property's own variables
  for (std::uint32_t round = 0; round < kMaxRefinements; ++round) {
    Slice slice = sliceModel(model, property, keep, facts.neverFires);
    out.keptVariables = slice.variables.size();
    out.refinements = round;
    if (!twins) twins.emplace(model, slice.variables);
    if (slice.tooCoarse) {
      for (ir::VarId v : slice.coarseReads) keep[v] = 1;
      for (ir::VarId v : slice.variables) keep[v] = 1;
      continue;
    }
    if (!enumerate && coneVariables > 0 && static_cast<double>(slice.variables.size()) >= kSliceShareOfCone * static_cast<double>(coneVariables)) {
      out.why = "the slice of " + std::to_string(slice.variables.size()) + " variables holds most of the property's cone of " +
                std::to_string(coneVariables) + ": the cone is searched instead";
      return out;
    }
    // Slices only grow: once one has been too large to enumerate, the next ones go straight to
    // the symbolic search.
    LivenessResult r;
    r.complete = false;
    r.limitReached = "--max-states " + std::to_string(sub.maxStates) + " reached by a smaller slice";
    if (limits.onPhase) {
      limits.onPhase("liveness: " + prop.name + ": slice of " + std::to_string(slice.variables.size()) + " of " +
                     std::to_string(model.variables.size()) + " variables (round " + std::to_string(round + 1) + ")" +
                     (enumerate ? "" : ", symbolically"));
    }
    if (enumerate) r = checkLiveness(slice.model, sub, plain);
    // A developer's trace of the refinement (checker/README.md), on stderr.
    if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) {
      std::string names;
      for (ir::VarId v : slice.variables) names += " " + model.variables[v].name;
      std::fprintf(stderr, "[slice] %s round %u: %zu vars, %zu rules, %llu states, %s; %s\n", prop.name.c_str(), round,
                   slice.variables.size(), slice.model.rules.size(), static_cast<unsigned long long>(r.states),
                   r.complete ? verdictName(r.properties[0].verdict) : r.limitReached.c_str(), names.c_str());
    }
    out.states += r.states;
    out.transitions += r.transitions;
    out.reduced = r.reducedProperties > 0;
    // The slice's lasso: from its explicit search, or, when its states are too many to enumerate,
    // from a symbolic search (symbolic_liveness.hpp), which also proves it when it has none.
    std::optional<Trace> sliceLasso;
    if (!r.complete) {
      std::string limit = r.limitReached;
      if (sliceStates < limits.maxStates && limit.rfind("--max-states", 0) == 0) limit = "--slice-states " + std::to_string(sliceStates) + " reached";
      SymbolicLimits symbolicLimits;
      symbolicLimits.maxMemoryBytes = limits.maxMemoryBytes;
      const double forSlices = symbolicBudget - huntSeconds(symbolicBudget);
      symbolicLimits.seconds = forSlices - symbolicSeconds;
      symbolicLimits.onProgress = limits.onProgress;
      const bool affordable = symbolic && symbolicLimits.seconds > 1;
      SymbolicOutcome result = affordable ? decideSymbolically(slice.model, 0, symbolicLimits) : SymbolicOutcome{};
      if (symbolic && !affordable) {
        result.why = "its time was spent";
      }
      symbolicSeconds += result.seconds;
      out.symbolicSeconds = symbolicSeconds;
      out.symbolicStates += result.reachable;
      if (result.kind == SymbolicOutcome::Kind::NoViolation) {
        out.property.verdict = Verdict::Proven;
        out.symbolic = true;
        return out;
      }
      if (result.kind != SymbolicOutcome::Kind::Violation || !result.lasso) {
        // A search cut by the budget says which budget: the user may give more (or less) of it.
        const bool outOfTime = !affordable || result.why.find("ran out") != std::string::npos;
        out.why = "the slice of " + std::to_string(slice.variables.size()) + " of " + std::to_string(model.variables.size()) +
                  " variables did not decide: " + limit +
                  (symbolic ? "; the symbolic search gave up: " + result.why +
                                  (outOfTime ? " (" + std::to_string(static_cast<int>(forSlices)) + " s of --symbolic-seconds " +
                                                   std::to_string(static_cast<int>(symbolicBudget)) + " for the slices)"
                                             : std::string())
                            : std::string());
        return out;
      }
      sliceLasso = std::move(result.lasso);
    } else {
      const PropertyResult& p = r.properties.at(0);
      if (p.verdict == Verdict::Proven) {
        out.property.verdict = Verdict::Proven;
        return out;
      }
      if (!p.counterexample) {
        out.why = "a violation on the slice of " + std::to_string(slice.variables.size()) + " variables came without a lasso";
        return out;
      }
      sliceLasso = p.counterexample;
    }
    // An explicit search that filled its budget found its lasso among the states it explored.
    const bool filled = r.complete && r.states >= sub.maxStates;
    enumerate = enumerate && r.complete && !filled;
    Concretizer concretizer(full, slice, *sliceLasso, prop.settled);
    Trace concrete;
    auto violated = [&] {
      out.states += concretizer.regionStates();
      out.property.verdict = Verdict::Violated;
      out.property.counterexample = std::move(concrete);
      return out;
    };
    if (concretizer.run(concrete, prop)) return violated();
    if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) std::fprintf(stderr, "[slice]   not rebuilt: %s\n", concretizer.why().c_str());
    std::vector<ir::VarId> added;
    for (std::size_t v = 0; v < keep.size(); ++v) {
      if (concretizer.refine()[v] && !keep[v]) keep[v] = 1, added.push_back(static_cast<ir::VarId>(v));
    }
    const bool grew = !added.empty();
    for (ir::VarId v : added) twins->keep(v, !enumerate, keep);
    // A slice too large to enumerate, or one that cannot grow, may be the last: the whole model
    // is searched where the slice's loop is first. A larger slice is then searched symbolically.
    const bool last = filled || !enumerate || !grew;
    if (last && concretizer.searchRegion(concrete, prop)) return violated();
    out.states += concretizer.regionStates();
    if (!grew) {
      out.why = "the lasso of the slice of " + std::to_string(slice.variables.size()) + " variables could not be rebuilt: " + concretizer.why();
      return out;
    }
    for (ir::VarId v : slice.variables) keep[v] = 1;
  }
  out.why = "no slice decided within " + std::to_string(kMaxRefinements) + " refinements";
  return out;
}

}  // namespace

// The walks' time per property: a lasso the walks can find turns up within seconds (scouting's
// mode_agreement in under one), and a model without one costs no more than this.
constexpr double kWalkSeconds = 10;

void walkForLasso(const CompiledModel& full, std::size_t property, const SearchLimits& limits, std::uint64_t seed, SlicedOutcome& out) {
  const ir::Property& prop = full.model().properties.at(property);
  if (limits.onPhase) limits.onPhase("liveness: " + prop.name + ": no slice decided; random walks hunting a fair loop");
  LassoWalkLimits walks;
  walks.seconds = kWalkSeconds;
  walks.seed = seed;
  const LassoWalkOutcome r = findLassoByWalks(full.model(), property, walks);
  out.walkSeconds = r.seconds;
  if (r.lasso) {
    out.property.verdict = Verdict::Violated;
    out.property.counterexample = *r.lasso;
    out.walked = true;
    out.walks = r.lassoWalk;
    return;
  }
  out.why += "; " + r.why;
}

namespace {

// A lasso of the cone (exact in its variables, not in every group's fairness), rebuilt on the
// whole model as a slice's: then `out`'s verdict, with the cone's size and counts; else `why` says
// why not.
bool rebuiltOnModel(const CompiledModel& full, const Slice& cone, const SymbolicOutcome& r, const ir::Property& prop,
                    SlicedOutcome& out, std::string& why) {
  Concretizer concretizer(full, cone, *r.lasso, prop.settled);
  Trace concrete;
  if (!concretizer.run(concrete, prop)) {
    why = "its lasso could not be rebuilt (" + concretizer.why() + ")";
    return false;
  }
  out.property.verdict = Verdict::Violated;
  out.property.counterexample = std::move(concrete);
  out.keptVariables = cone.variables.size();
  out.symbolicStates += r.reachable;
  return true;
}

}  // namespace

// Slices over-approximate, so their lassos may keep failing on the model while a real violation
// hides among them. The hunt looks at the property's whole cone instead (exact), without the
// crashes and environment steps no fairness asks for: first for a loop that senses nothing (settled
// on any world, and cheap), then on each settling world: every fair lasso found there is one of
// the model's, rebuilt on it as a slice's.
void huntOnCone(const CompiledModel& full, std::size_t property, const SearchLimits& limits, SlicedOutcome& out,
                const ControlFacts* facts, double symbolicSeconds) {
  const ControlFacts none{{}, {}, 0, 0};
  const ir::Model& model = facts != nullptr ? facts->model : full.model();
  const std::vector<char>& neverFires = facts != nullptr ? facts->neverFires : none.neverFires;
  const ir::Property& prop = model.properties.at(property);
  Slice cone = sliceModel(model, property, coneOfInfluence(model, property, neverFires), neverFires);
  if (cone.tooCoarse) return;
  if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) {
    std::vector<char> in(model.variables.size(), 0);
    for (ir::VarId v : cone.variables) in[v] = 1;
    for (ir::VarId v = 0; v < in.size(); ++v) {
      if (in[v] == 0) std::fprintf(stderr, "[slice] outside the cone: %s\n", model.variables[v].name.c_str());
    }
  }
  withoutUnfairEnvironment(cone);
  SymbolicLimits hunt;
  hunt.maxMemoryBytes = limits.maxMemoryBytes;
  hunt.seconds = symbolicSeconds - out.symbolicSeconds;
  hunt.onProgress = limits.onProgress;
  hunt.quietLoop = true;
  hunt.thenSettled = true;
  const SymbolicOutcome r = decideSymbolically(cone.model, 0, hunt);
  out.symbolicSeconds += r.seconds;
  std::string found;
  if (r.kind == SymbolicOutcome::Kind::Violation && r.lasso) {
    if (rebuiltOnModel(full, cone, r, prop, out, found)) {
      out.hunted = true;
      return;
    }
  } else {
    found = r.kind == SymbolicOutcome::Kind::NoViolation ? "no fair loop on any settling world" : "gave up (" + r.why + ")";
  }
  out.why += "; a hunt on the property's cone of " + std::to_string(cone.variables.size()) + " variables without crashes: " + found;
}

// The exact cone keeps every rule that can influence the property, crashes and discoveries
// included: a proof there is a proof on the model, a lasso there is one of the model (rebuilt on
// it as a slice's). What makes it affordable is the narrowing of each world's loops to the rules
// that can recur (recurring_rules.hpp): on scouting's mode_agreement most strongly fair
// deliveries cannot, and the fixpoint of each world ends in seconds to minutes where it did not
// end in 15 minutes. The reachable states were the dear part (18 minutes there): the worlds are
// now searched first within a superset of them bounded by the proven invariants
// (projected_reach.hpp), which proves scouting's mode_agreement in under three minutes.
void proveOnCone(const CompiledModel& full, const ControlFacts& facts, std::size_t property, const SearchLimits& limits,
                 SlicedOutcome& out, double seconds, const std::vector<std::size_t>& provenInvariants) {
  const ir::Model& model = facts.model;
  const ir::Property& prop = model.properties.at(property);
  Slice cone = sliceModel(model, property, coneOfInfluence(model, property, facts.neverFires), facts.neverFires);
  // Each proven invariant as the cone sees it (what it says of the cone's variables whatever the
  // others hold: implied by it, so true in every reachable state of the cone too); one that reads
  // none of the cone's variables says nothing there.
  std::vector<std::string> assumed;
  std::vector<char> inCone(model.variables.size(), 0);
  for (ir::VarId v : cone.variables) inCone[v] = 1;
  for (std::size_t i : provenInvariants) {
    const ir::Invariant& inv = model.invariants.at(i);
    std::vector<char> reads(model.variables.size(), 0);
    markVariablesRead(inv.holds, reads);
    bool seen = false;
    for (ir::VarId v = 0; v < reads.size() && !seen; ++v) seen = reads[v] != 0 && inCone[v] != 0;
    if (!seen) continue;
    cone.model.invariants.push_back({inv.name, inv.origin, seenThrough(inv.holds, cone, model.variables.size())});
    assumed.push_back(inv.name);
  }
  if (cone.tooCoarse) {
    out.why += "; the exact cone: an update has too many values to enumerate";
    return;
  }
  const RecurringRules recurring(model, facts.neverFires);
  const LoopNarrowing narrowing(recurring, model, cone.rules);
  SymbolicLimits exact;
  exact.maxMemoryBytes = limits.maxMemoryBytes;
  exact.seconds = seconds;
  exact.onProgress = limits.onProgress;
  exact.narrowing = &narrowing;
  exact.everyWorld = true;
  exact.worldsHelper = limits.threads >= 2;
  exact.overApproximate = true;
  const SymbolicOutcome r = decideSymbolically(cone.model, 0, exact);
  out.symbolicSeconds += r.seconds;
  const std::string where = "the exact cone of " + std::to_string(cone.variables.size()) + " variables";
  if (r.kind == SymbolicOutcome::Kind::NoViolation) {
    out.property.verdict = Verdict::Proven;
    out.symbolic = true;
    out.onCone = true;
    out.keptVariables = cone.variables.size();
    out.symbolicStates = r.reachable;
    if (r.overApproximated) out.assumedInvariants = std::move(assumed);
    return;
  }
  if (r.kind == SymbolicOutcome::Kind::Violation && r.lasso) {
    std::string why;
    if (rebuiltOnModel(full, cone, r, prop, out, why)) {
      out.onCone = true;
      return;
    }
    out.why += "; " + where + ": " + why;
    return;
  }
  out.why += "; " + where + " (--cone-seconds " + std::to_string(static_cast<int>(seconds)) + "): gave up (" + r.why + ")";
}

SlicedOutcome checkSliced(const CompiledModel& full, const ControlFacts& facts, std::size_t property, const SearchLimits& limits,
                          const LivenessOptions& options) {
  const bool symbolic = options.symbolic;
  const double symbolicSeconds = options.symbolicSeconds;
  std::size_t coneVariables = 0;
  if (symbolic && options.coneSeconds > 0) {
    const std::vector<char> cone = coneOfInfluence(facts.model, property, facts.neverFires);
    coneVariables = static_cast<std::size_t>(std::count(cone.begin(), cone.end(), 1));
  }
  SlicedOutcome out = refineSlices(full, facts, property, limits, options.sliceStates, symbolic, symbolicSeconds, coneVariables);
  const std::string& name = full.model().properties[property].name;
  // The random walks first: a lasso they can find turns up within a second or two, where the exact
  // cone may spend its whole time before it finds the same one, and they cost at most kWalkSeconds
  // on a property that holds. The exact cone, asked for, comes next: it decides either
  // way (a proof, or a lasso of the model), where the hunt can only find a lasso and costs its whole
  // time on a property that holds. The hunt remains for a cone that gave up (out of time or memory)
  // or whose lasso could not be rebuilt.
  if (options.walks && out.property.verdict == Verdict::Unknown) walkForLasso(full, property, limits, options.walkSeed, out);
  double coneSpent = 0;
  if (coneVariables > 0 && out.property.verdict == Verdict::Unknown) {
    std::vector<std::size_t> invariants = options.provenInvariants;
    bool waited = true;
    if (options.provenInvariantsLater.valid()) {
      const bool ready = options.provenInvariantsLater.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
      if (!ready && limits.onPhase) limits.onPhase("liveness: " + name + ": waiting for the safety proofs, whose invariants bound its exact cone");
      try {
        invariants = options.provenInvariantsLater.get();
      } catch (const std::future_error&) {
        waited = false;
        out.why += "; the exact cone: not searched, the safety proofs ended without a result";
      }
    }
    if (waited) {
      if (limits.onPhase) limits.onPhase("liveness: " + name + ": searching its exact cone, crashes included, on every settling world (symbolically)");
      const double before = out.symbolicSeconds;
      proveOnCone(full, facts, property, limits, out, options.coneSeconds, invariants);
      coneSpent = out.symbolicSeconds - before;
    }
  }
  if (symbolic && out.property.verdict == Verdict::Unknown) {
    if (limits.onPhase) limits.onPhase("liveness: " + name + ": no slice decided; hunting the property's cone for a fair loop (symbolically)");
    // After the exact cone, the hunt keeps to its own share of the time: slices that stopped early
    // for the cone leave much of theirs. The cone's own time is not the slices'.
    const double forHunt = coneVariables > 0 ? std::min(symbolicSeconds, out.symbolicSeconds - coneSpent + huntSeconds(symbolicSeconds)) : symbolicSeconds;
    huntOnCone(full, property, limits, out, &facts, forHunt + coneSpent);
  }
  return out;
}

}  // namespace semo::checker::detail
