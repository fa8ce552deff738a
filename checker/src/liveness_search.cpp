#include "semo/checker/liveness_search.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

#include "fair_cycle_search.hpp"
#include "liveness_product.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/checker/slicing.hpp"
#include "region_lasso.hpp"
#include "sliced_liveness.hpp"

namespace semo::checker {

namespace {

using detail::Clock;
using detail::Edge;
using detail::compose;
using detail::inverse;
using detail::keyOf;
using detail::kStutter;
using detail::Permutation;
using detail::PermutationTable;
using detail::Product;
using detail::ruleOf;
using detail::FairCycleSearch;
using detail::fairLoop;
using detail::lasso;

struct Outcome {
  PropertyResult property;
  std::uint64_t states = 0, transitions = 0;
  bool whole = true;
  std::string why;
  bool reduced = false;  // searched up to symmetry
  std::string note;
  LivenessMethod method;
};

// With `symmetry` (non-null only when every atom of the property is invariant), the product of
// the quotient is searched; it decides the property exactly (see FairCycleSearch::liftComponent).
// A violation found there is searched again without symmetry for a concrete lasso.
Outcome checkProperty(const CompiledModel& cm, const ir::Property& prop, const SearchLimits& limits, Clock::time_point start,
                      const Symmetry* symmetry, bool slice = false) {
  Outcome out{{prop.name, prop.origin, Verdict::Unknown, {}}, 0, 0, true, {}, false, {}, {}};
  Buchi ba;
  try {
    ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, prop.formula));
  } catch (const std::length_error& e) {
    out.whole = false;
    out.why = prop.name + ": " + e.what();
    return out;
  }
  if (symmetry != nullptr &&
      !std::all_of(ba.atoms.begin(), ba.atoms.end(), [&](const ir::Expr& a) { return symmetry->invariant(a); })) {
    symmetry = nullptr;
  }
  out.reduced = symmetry != nullptr;
  Product product(cm, ba, symmetry);
  // As the safety search: the rules of a robot equal to its neighbour are not expanded (the same
  // developer's knob turns that off, to measure).
  product.pruneEqualRobots(symmetry != nullptr && std::getenv("SEMO_NO_EQUAL_ROBOT_PRUNING") == nullptr);
  product.outOfRangeIsNoStep(slice);
  out.whole = product.explore(limits, start, 0, out.why);
  out.states = product.size();
  out.transitions = product.edgeCount();
  if (!out.whole) {
    // Stopped by --max-states: a fair cycle among the states expanded so far is still a real
    // violation (closeFrontier). Not on a quotient, whose cycles need the whole orbit structure to
    // be lifted, nor after an error or --max-memory.
    if (symmetry != nullptr || out.why.rfind("--max-states", 0) != 0) return out;
    product.closeFrontier();
    FairCycleSearch partial(cm, ba, product, prop.settled);
    std::vector<std::uint32_t> cycle = partial.find();
    if (cycle.empty()) return out;
    std::uint32_t entry = *std::min_element(cycle.begin(), cycle.end());
    Trace t = lasso(cm, product, entry, fairLoop(ba, product, partial, cycle, entry));
    t.property = prop.name;
    t.kind = "lasso";
    out.property.verdict = Verdict::Violated;
    out.property.counterexample = std::move(t);
    out.whole = true;  // decided: the rest of the product cannot undo a violation
    out.why.clear();
    return out;
  }
  // A settling world constrains each robot's sensed conditions on its own, which a quotient does not
  // keep apart (robots of one orbit may settle differently): the quotient is searched without that
  // constraint, which only adds runs, so that no cycle there proves the property; a cycle there is
  // looked for again on the whole product, where the constraint applies.
  FairCycleSearch search(cm, ba, product, prop.settled && symmetry == nullptr);
  std::vector<std::uint32_t> cycle = search.find();
  if (cycle.empty()) {
    out.property.verdict = Verdict::Proven;
    return out;
  }
  if (symmetry != nullptr && prop.settled) {
    Outcome concrete = checkProperty(cm, prop, limits, start, nullptr, slice);
    concrete.states += out.states;
    concrete.transitions += out.transitions;
    concrete.reduced = true;
    return concrete;
  }
  if (symmetry != nullptr) {
    Outcome concrete = checkProperty(cm, prop, limits, start, nullptr, slice);
    concrete.states += out.states;
    concrete.transitions += out.transitions;
    concrete.reduced = true;
    if (concrete.property.verdict == Verdict::Violated) return concrete;
    // The quotient's verdict is exact; only the lasso is missing.
    out.property.verdict = Verdict::Violated;
    out.note = "violated up to symmetry; no concrete lasso: ";
    out.note += concrete.whole ? "none found" : concrete.why;
    out.states = concrete.states;
    out.transitions = concrete.transitions;
    return out;
  }
  std::uint32_t entry = *std::min_element(cycle.begin(), cycle.end());  // breadth-first: the shortest way in
  Trace t = lasso(cm, product, entry, fairLoop(ba, product, search, cycle, entry));
  t.property = prop.name;
  t.kind = "lasso";
  out.property.verdict = Verdict::Violated;
  out.property.counterexample = std::move(t);
  return out;
}

// A violation found on a slice is searched again on the whole product when that stays within
// this many states: its lasso then has the shortest way into the loop, as without slicing.
constexpr std::uint64_t kWholeLassoBudget = 2'000'000;
// Product states the round-robin hunt for a violation may take when no slice decided.
constexpr std::uint64_t kRoundRobinBudget = 2'000'000;

// One property: on slices first (when asked, and the formula is stutter-insensitive), else, or when
// no slice decides, on the whole product.
Outcome decide(const CompiledModel& cm, const ControlFacts& facts, std::size_t k, const SearchLimits& limits,
               const LivenessOptions& options, Clock::time_point start, const Symmetry* symmetry) {
  const ir::Property& prop = cm.model().properties[k];
  if (!options.slicing || usesNext(prop.formula)) {
    Outcome o = checkProperty(cm, prop, limits, start, symmetry, options.slice);
    o.method.states = o.states;
    return o;
  }
  std::uint64_t spent = 0;  // product states of a whole search that did not fit
  if (options.wholeFirstStates > 0) {
    SearchLimits small = limits;
    small.maxStates = std::min(limits.maxStates, options.wholeFirstStates);
    Outcome whole = checkProperty(cm, prop, small, start, symmetry);
    if (whole.whole) {
      whole.method.states = whole.states;
      return whole;
    }
    spent = whole.states;
  }
  detail::SlicedOutcome sliced = detail::checkSliced(cm, facts, k, limits, options);
  LivenessMethod method;
  method.sliced = true;
  method.keptVariables = sliced.keptVariables;
  method.refinements = sliced.refinements;
  method.states = sliced.states;
  method.symbolic = sliced.symbolic;
  method.symbolicStates = sliced.symbolicStates;
  method.hunted = sliced.hunted;
  method.onCone = sliced.onCone;
  method.assumedInvariants = sliced.assumedInvariants;
  method.walked = sliced.walked;
  method.walks = sliced.walks;
  method.states += spent;
  Outcome out{sliced.property, sliced.states + spent, sliced.transitions, true, {}, sliced.reduced, {}, method};
  if (sliced.property.verdict == Verdict::Proven) return out;
  if (sliced.property.verdict == Verdict::Violated) {
    if (!options.wholeProduct) return out;
    SearchLimits small = limits;
    small.maxStates = std::min(limits.maxStates, kWholeLassoBudget);
    Outcome whole = checkProperty(cm, prop, small, start, symmetry);
    out.states += whole.states;
    out.transitions += whole.transitions;
    out.method.states = out.states;
    if (whole.whole && whole.property.verdict == Verdict::Violated && whole.property.counterexample) {
      out.property.counterexample = std::move(whole.property.counterexample);
      out.reduced = out.reduced || whole.reduced;
    } else if (whole.whole && whole.property.verdict == Verdict::Proven) {
      out.note = "engines disagree: the whole product has no fair violation, a slice's lasso replays as one";
    }
    return out;
  }
  out.method.slicingGaveUp = sliced.why;
  // No slice decided: a violation may still be in reach of a round-robin scheduler (region_lasso.hpp).
  // Each phase says so: the progress line would otherwise go on naming the symbolic hunt.
  if (limits.onPhase) limits.onPhase("liveness: " + prop.name + ": no slice decided; hunting a fair loop under a round-robin scheduler");
  detail::RegionSearch hunt = detail::lassoUnderRoundRobin(cm, prop, std::min(limits.maxStates, kRoundRobinBudget));
  out.states += hunt.states;
  out.method.states = out.states;
  if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) {
    std::fprintf(stderr, "[hunt] %s: %llu states, %s\n", prop.name.c_str(), static_cast<unsigned long long>(hunt.states),
                 hunt.lasso ? "lasso" : hunt.why.c_str());
  }
  if (hunt.lasso) {
    out.property.verdict = Verdict::Violated;
    out.property.counterexample = std::move(hunt.lasso);
    out.method.roundRobin = true;
    return out;
  }
  if (!options.wholeProduct) {
    out.whole = false;
    out.why = prop.name + ": " + sliced.why;
    return out;
  }
  if (limits.onPhase) {
    limits.onPhase("liveness: " + prop.name + ": no slice decided; searching the whole product (--max-states " + std::to_string(limits.maxStates) + ")");
  }
  Outcome whole = checkProperty(cm, prop, limits, start, symmetry);
  whole.states += sliced.states;
  whole.transitions += sliced.transitions;
  whole.method = LivenessMethod{};
  whole.method.states = whole.states;
  whole.method.slicingGaveUp = sliced.why;
  return whole;
}

}  // namespace

LivenessResult checkLiveness(const ir::Model& model, const SearchLimits& limits, const LivenessOptions& options) {
  auto start = Clock::now();
  CompiledModel cm(model);
  const std::size_t n = model.properties.size();
  // Each property's product is reduced by the robots interchangeable for it: the rules, their
  // fairness and that property, not the model's other properties, invariants or valid end (they
  // play no part in its runs). The swarm's all_turn_back names legged_0, which sets that robot
  // apart for the whole model; for knowledge_convergence all fifty robots of a team of fifty stay
  // interchangeable (77,378 product states against 332,428 with the model's symmetry).
  std::vector<Symmetry> symmetries(n);
  auto findSymmetry = [&](std::size_t k) -> const Symmetry* {
    if (!limits.symmetry) return nullptr;
    symmetries[k] = Symmetry::find(model, SymmetryScope::liveness(k));
    return symmetries[k].empty() ? nullptr : &symmetries[k];
  };
  LivenessResult result;
  // What the robots' control variables reach (slicing.hpp), for every property's slices: once.
  const ControlFacts facts = options.slicing ? controlFacts(model) : ControlFacts{};
  if (std::getenv("SEMO_DEBUG_SLICING") != nullptr) {
    std::size_t dead = 0;
    for (std::size_t r = 0; r < facts.neverFires.size(); ++r) {
      if (facts.neverFires[r] != 0) ++dead, std::fprintf(stderr, "[slice] never fires: %s\n", model.rules[r].name.c_str());
    }
    std::fprintf(stderr, "[slice] control facts: %zu rules never fire, %zu conjuncts implied, %zu robots skipped\n", dead,
                 facts.droppedConjuncts, facts.robotsSkipped);
  }
  // The properties' products are independent: up to `threads` are searched at once, each within
  // --max-states and its share of --max-memory; only the first worker reports progress.
  const std::size_t workers = std::min<std::size_t>(n, std::max(1u, limits.threads));
  std::vector<Outcome> outcomes(n);
  std::atomic<std::size_t> next{0};
  // The phases of all workers are said as they come, but the counts are the first worker's: before
  // its counts, its own phase is said again if another worker's came since (a count of the swarm's
  // knowledge_convergence shown after "mode_agreement: proven" misled).
  // Progress comes from the lowest-numbered worker still searching: one line to follow, and, once
  // the others are done, the one left (scouting's mode_agreement searches its exact cone for half
  // an hour after the rest have ended; its progress used to go unshown, worker 0 being done).
  std::mutex phaseLock;
  std::string lastPhase;
  std::vector<std::string> phaseOf(workers);
  std::vector<char> busy(workers, 1);
  auto work = [&](std::size_t worker) {
    SearchLimits mine = limits;
    mine.maxMemoryBytes = limits.maxMemoryBytes / std::max<std::size_t>(1, workers);
    if (limits.onPhase) {
      mine.onPhase = [&, worker](const std::string& what) {
        const std::lock_guard<std::mutex> hold(phaseLock);
        lastPhase = what;
        phaseOf[worker] = what;
        limits.onPhase(what);
      };
    }
    mine.onProgress = nullptr;
    if (limits.onProgress && limits.onPhase) {
      mine.onProgress = [&, worker](const Progress& p) {
        {
          const std::lock_guard<std::mutex> hold(phaseLock);
          for (std::size_t w = 0; w < worker; ++w) {
            if (busy[w] != 0) return;
          }
          if (lastPhase != phaseOf[worker]) {
            lastPhase = phaseOf[worker];
            limits.onPhase(phaseOf[worker]);
          }
        }
        limits.onProgress(p);
      };
    }
    for (std::size_t k = next++; k < n; k = next++) {
      const auto begin = Clock::now();
      if (mine.onPhase) mine.onPhase("liveness: " + model.properties[k].name + " (" + std::to_string(k + 1) + " of " + std::to_string(n) + "): searching");
      outcomes[k] = decide(cm, facts, k, mine, options, start, findSymmetry(k));
      outcomes[k].method.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
      if (mine.onPhase) {
        mine.onPhase("liveness: " + model.properties[k].name + ": " + verdictName(outcomes[k].property.verdict) + " after " +
                     std::to_string(static_cast<long long>(outcomes[k].method.seconds)) + " s, " + std::to_string(outcomes[k].states) +
                     " product states");
      }
    }
    const std::lock_guard<std::mutex> hold(phaseLock);
    busy[worker] = 0;
  };
  std::vector<std::thread> helpers;
  for (std::size_t w = 1; w < workers; ++w) helpers.emplace_back(work, w);
  work(0);
  for (std::thread& h : helpers) h.join();
  // A product that outgrew its share of the memory gets the whole budget, alone.
  if (workers > 1) {
    for (std::size_t k = 0; k < n; ++k) {
      if (!outcomes[k].whole && outcomes[k].why.rfind("--max-memory", 0) == 0) {
        const auto begin = Clock::now();
        outcomes[k] = decide(cm, facts, k, limits, options, start, symmetries[k].empty() ? nullptr : &symmetries[k]);
        outcomes[k].method.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
      }
    }
  }
  for (Outcome& o : outcomes) {
    result.states += o.states;
    result.transitions += o.transitions;
    result.reducedProperties += o.reduced ? 1 : 0;
    if (!o.whole) {
      result.complete = false;
      if (result.limitReached.empty()) result.limitReached = o.why;
    }
    result.properties.push_back(std::move(o.property));
    result.notes.push_back(std::move(o.note));
    result.methods.push_back(std::move(o.method));
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace semo::checker
