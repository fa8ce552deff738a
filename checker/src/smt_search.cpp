#include "semo/checker/smt_search.hpp"

#include <algorithm>
#include <chrono>
#include <optional>

#include "smt_encoding.hpp"
#include "smt_ic3.hpp"

namespace semo::checker {

namespace {

using detail::SmtEncoding;
using detail::Ic3Outcome;
using Clock = std::chrono::steady_clock;

// The safety properties in the explicit engine's order: the invariants, then deadlock freedom.
struct Target {
  std::string name, origin;
  const ir::Expr* invariant = nullptr;  // null: deadlock freedom
};

std::vector<Target> targets(const ir::Model& m) {
  std::vector<Target> out;
  for (const ir::Invariant& inv : m.invariants) out.push_back({inv.name, inv.origin, &inv.holds});
  if (m.validEnd) out.push_back({"deadlock_freedom", "", nullptr});
  return out;
}

// The property as a state predicate at step k.
z3::expr good(SmtEncoding& enc, const ir::Model& m, const Target& t, std::size_t k) {
  if (t.invariant != nullptr) return enc.holds(*t.invariant, k);
  return enc.enabled(k) || enc.holds(*m.validEnd, k);
}

std::int32_t intValue(const z3::model& model, const z3::expr& e) {
  return static_cast<std::int32_t>(model.eval(e, true).get_numeral_int64());
}

// The path s_0 .. s_depth of a satisfying assignment, as the explicit engine prints it.
Trace traceOf(const z3::model& model, SmtEncoding& enc, const ir::Model& m, std::size_t depth) {
  Trace t;
  const std::size_t n = m.variables.size();
  for (std::size_t v = 0; v < n; ++v) t.initial.push_back(intValue(model, enc.state(0)[static_cast<int>(v)]));
  for (std::size_t k = 0; k < depth; ++k) {
    auto a = static_cast<std::size_t>(intValue(model, enc.action(k)));
    Step step{enc.actions()[a].rule, enc.actions()[a].branch, {}};
    for (std::size_t v = 0; v < n; ++v) {
      std::int32_t before = intValue(model, enc.state(k)[static_cast<int>(v)]);
      std::int32_t after = intValue(model, enc.state(k + 1)[static_cast<int>(v)]);
      if (before != after) step.changes.push_back({static_cast<ir::VarId>(v), before, after});
    }
    t.steps.push_back(std::move(step));
  }
  return t;
}

z3::check_result checkWith(z3::solver& s, const z3::expr& extra) {
  s.push();
  s.add(extra);
  z3::check_result r = s.check();
  if (r != z3::sat) s.pop();  // on sat the caller reads the model first, then pops
  return r;
}

// A path of exactly `depth` steps, within the ranges, that ends where `error` holds (error(enc, k)
// is a condition on step k, or on steps k-1 and k for a range error); nullopt if there is none or
// the solver gave up. IC3 tells how deep its counterexample is but not the path itself.
template <class Error>
std::optional<Trace> pathOfDepth(const ir::Model& m, std::uint32_t depth, Error error, unsigned timeoutMs) {
  z3::context ctx;
  SmtEncoding enc(ctx, m);
  z3::solver s(ctx);
  if (timeoutMs != 0) {
    z3::params p(ctx);
    p.set("timeout", timeoutMs);
    s.set(p);
  }
  s.add(enc.initial(0));
  for (std::uint32_t k = 0; k < depth; ++k) {
    s.add(enc.transition(k));
    if (k + 1 < depth) s.add(enc.inRange(k + 1));
  }
  s.add(error(enc, depth));
  if (s.check() != z3::sat) return std::nullopt;
  return traceOf(s.get_model(), enc, m, depth);
}

// Whether every step from a state where `now` holds leads to one where `next` holds (its copy at
// step 1), checked one rule outcome at a time, each in a solver of its own: a step moves one robot,
// and a fresh solver simplifies the query away before searching. On the swarm of 10's team counts
// (81 outcomes): the whole step relation at once 17 s, one incremental solver 5.6 s, this 0.14 s
// (measured 2026-11-28).
bool keptByEveryStep(z3::context& ctx, SmtEncoding& enc, const z3::params& p, const z3::expr& now, const z3::expr& next) {
  const z3::expr broken = now && !next;
  for (std::size_t a = 0; a < enc.actions().size(); ++a) {
    z3::solver consecution(ctx);
    consecution.set(p);
    consecution.add(broken && enc.stepBy(a, 0));
    if (consecution.check() != z3::unsat) return false;
  }
  return true;
}

// keptByEveryStep for the ranges, asking of each rule outcome only whether one of its assignments
// leaves its range (the variables it keeps stay in theirs), in one incremental solver: these
// queries are small, and a fresh solver's setup was most of their cost. Scouting's 261 outcomes
// took 5.5 s as whole steps into a second state, each in a solver of its own; so, its whole check
// with BMC to depth 2 takes 0.2 s (measured 2026-12-03).
bool rangesKeptByEveryStep(z3::context& ctx, SmtEncoding& enc, const z3::params& p) {
  z3::solver consecution(ctx);
  consecution.set(p);
  consecution.add(enc.inRange(0));
  for (std::size_t a = 0; a < enc.actions().size(); ++a) {
    consecution.push();
    consecution.add(enc.stepLeavesRange(a, 0));
    if (consecution.check() != z3::unsat) return false;
    consecution.pop();
  }
  return true;
}

// The lemmas (SmtOptions::lemmas), if each holds initially and together they are kept by every
// step: then they hold in every reachable state. Whole or nothing: a definition that fails means
// the counts are not what they claim, and the others are not trusted either.
bool lemmasInductive(const ir::Model& m, const SmtOptions& options) {
  if (options.lemmas.empty()) return false;
  if (options.onPhase) options.onPhase("smt: the definitions of the team counts (" + std::to_string(options.lemmas.size()) + ")");
  z3::context ctx;
  SmtEncoding enc(ctx, m);
  z3::params p(ctx);
  if (options.timeoutMs != 0) p.set("timeout", options.timeoutMs);
  z3::expr_vector now(ctx), next(ctx);
  for (const ir::Expr& l : options.lemmas) {
    now.push_back(enc.holds(l, 0));
    next.push_back(enc.holds(l, 1));
  }
  z3::solver initiation(ctx);
  initiation.set(p);
  initiation.add(enc.initial(0) && !z3::mk_and(now));
  if (initiation.check() != z3::unsat) return false;
  return keptByEveryStep(ctx, enc, p, z3::mk_and(now), z3::mk_and(next));
}

// IC3 on every property still unknown after k-induction. The step relation keeps to the ranges, so
// the ranges come first: unless k-induction already proved them, IC3 must (an update that leaves a
// range is a modelling error, reported with its path as BMC would). Each invariant IC3 proves (and
// semo checks) is assumed by the proofs after it: it holds in every reachable state, and Spacer,
// stepping only from its states, need not learn it again (the dining philosophers' check: 40 s,
// 35 of them deadlock freedom after the other six properties; 4 s so; measured 2026-11-28).
void runIc3(const ir::Model& m, const std::vector<Target>& props, const SmtOptions& options, bool rangesProven, bool lemmas,
            SmtResult& out) {
  SearchResult& result = out.search;
  std::vector<std::size_t> open;
  for (std::size_t j = 0; j < props.size(); ++j) {
    if (result.properties[j].verdict == Verdict::Unknown) open.push_back(j);
  }
  z3::context ctx;
  SmtEncoding enc(ctx, m);
  z3::expr_vector proven(ctx);
  if (lemmas) {
    for (const ir::Expr& l : options.lemmas) proven.push_back(enc.holds(l, 0));
  }
  z3::expr assumed = z3::mk_and(proven);
  if (!rangesProven) {
    if (options.onPhase) options.onPhase("smt: IC3 on the variables' ranges");
    Ic3Outcome ranges = detail::proveWithIc3(ctx, enc, enc.transitionByCases(0) && !enc.inRange(1), options.timeoutMs, assumed);
    if (ranges.kind == Ic3Outcome::Kind::Violated) {
      auto leaves = [](SmtEncoding& e, std::uint32_t d) { return !e.inRange(d); };
      // The error clause takes the step that leaves the range itself: one more than IC3's count.
      if (std::optional<Trace> t = pathOfDepth(m, ranges.depth + 1, leaves, options.timeoutMs)) {
        t->kind = "range";
        t->property = "variable ranges";
        result.rangeError = std::move(*t);
        result.limitReached = "an update left a variable's declared range";
        for (std::size_t j = 0; j < props.size(); ++j) {  // a model with an error proves nothing
          if (result.properties[j].verdict == Verdict::Violated) continue;
          result.properties[j].verdict = Verdict::Unknown;
          out.proof[j] = SmtProof::None;
          out.inductionDepth[j] = 0;
        }
      } else {
        out.note = "IC3 found an update leaving a declared range after " + std::to_string(ranges.depth + 1) +
                   " steps, but no path of that length was rebuilt";
      }
      return;
    }
    if (ranges.kind == Ic3Outcome::Kind::Unknown) {
      out.note = "IC3 could not show that every variable stays in its range (" + ranges.note + "), so proved nothing unbounded";
      return;
    }
    proven.push_back(*ranges.invariant);
    assumed = z3::mk_and(proven);
    if (options.onRangesHold) options.onRangesHold();
  }
  for (std::size_t n = 0; n < open.size(); ++n) {
    const std::size_t j = open[n];
    if (options.onPhase) options.onPhase("smt: IC3 on " + props[j].name + " (" + std::to_string(n + 1) + " of " + std::to_string(open.size()) + ")");
    Ic3Outcome o = detail::proveWithIc3(ctx, enc, !good(enc, m, props[j], 0), options.timeoutMs, assumed);
    if (o.kind == Ic3Outcome::Kind::Proven) {
      result.properties[j].verdict = Verdict::Proven;
      out.proof[j] = SmtProof::Ic3;
      out.invariantConjuncts[j] = o.conjuncts;
      // Its checked invariant holds in every reachable state: the next proofs step only from its
      // states, Spacer starting from what this one learnt.
      proven.push_back(*o.invariant);
      assumed = z3::mk_and(proven);
    } else if (o.kind == Ic3Outcome::Kind::Violated) {
      const Target& t = props[j];
      auto fails = [&m, &t](SmtEncoding& e, std::uint32_t d) { return !good(e, m, t, d) && e.inRange(d); };
      if (std::optional<Trace> trace = pathOfDepth(m, o.depth, fails, options.timeoutMs)) {
        trace->property = t.name;
        trace->kind = t.invariant != nullptr ? "invariant" : "deadlock";
        result.properties[j].verdict = Verdict::Violated;
        result.properties[j].counterexample = std::move(*trace);
        out.deepCounterexample[j] = 1;
      } else {
        out.note = "IC3 found " + t.name + " violated after " + std::to_string(o.depth) + " steps, but no path of that length was rebuilt";
      }
    } else if (out.note.empty()) {
      out.note = o.note;
    }
  }
}

}  // namespace

SmtResult checkSafetySmt(const ir::Model& model, const SmtOptions& options) {
  auto start = Clock::now();
  SmtResult out;
  SearchResult& result = out.search;
  const std::vector<Target> props = targets(model);
  for (const Target& t : props) result.properties.push_back({t.name, t.origin, Verdict::Unknown, {}});
  out.inductionDepth.assign(props.size(), 0);
  out.invariantConjuncts.assign(props.size(), 0);
  out.deepCounterexample.assign(props.size(), 0);
  out.proof.assign(props.size(), SmtProof::None);

  z3::context ctx;
  z3::params params(ctx);
  if (options.timeoutMs != 0) params.set("timeout", options.timeoutMs);
  SmtEncoding enc(ctx, model);
  // Whether no step from within the ranges can leave them: then no range error exists at any
  // depth, and BMC need not look for one at each (the largest of its queries: 6.4 of scouting's 10 s
  // of BMC to depth 5; measured 2026-11-28); and, as they hold initially, they need no proof of
  // their own (below).
  const bool rangesKept = rangesKeptByEveryStep(ctx, enc, params);
  // Kept by every step and holding initially: an invariant already (1-inductive), which neither
  // induction nor IC3 need prove again. Scouting's ranges are so; its checks of LTL properties
  // alone, with no safety property for induction to carry them, spent 15 s of IC3 on them.
  bool rangesHold = false;
  if (rangesKept) {
    z3::solver initially(ctx);
    initially.set(params);
    initially.add(enc.initial(0) && !enc.inRange(0));
    rangesHold = initially.check() == z3::unsat;
  }
  if (rangesHold && options.onRangesHold) options.onRangesHold();
  z3::solver bmc(ctx);
  bmc.set(params);
  bmc.add(enc.initial(0));
  std::vector<std::size_t> open;
  for (std::size_t j = 0; j < props.size(); ++j) open.push_back(j);
  bool complete = false, limited = false;
  std::uint32_t depth = 0;
  for (;; ++depth) {
    if (options.onPhase) options.onPhase("smt: bounded model checking, depth " + std::to_string(depth) + " of " + std::to_string(options.maxDepth));
    if (depth > 0) {
      // An update that leaves a declared range is a modelling error, as in the explicit engine.
      z3::check_result r = rangesKept ? z3::unsat : checkWith(bmc, !enc.inRange(depth));
      if (r == z3::sat) {
        Trace t = traceOf(bmc.get_model(), enc, model, depth);
        bmc.pop();
        t.kind = "range";
        t.property = "variable ranges";
        result.rangeError = std::move(t);
        result.limitReached = "an update left a variable's declared range";
        break;
      }
      bmc.add(enc.inRange(depth));
      // No path of `depth` steps at all: every reachable state lies within depth - 1 steps.
      z3::check_result any = bmc.check();
      if (any == z3::unsat) {
        complete = true;
        --depth;
        break;
      }
      if (any == z3::unknown) limited = true;
    }
    for (auto it = open.begin(); it != open.end();) {
      z3::check_result r = checkWith(bmc, !good(enc, model, props[*it], depth));
      if (r == z3::sat) {
        Trace t = traceOf(bmc.get_model(), enc, model, depth);
        bmc.pop();
        t.property = props[*it].name;
        t.kind = props[*it].invariant != nullptr ? "invariant" : "deadlock";
        result.properties[*it].verdict = Verdict::Violated;
        result.properties[*it].counterexample = std::move(t);
        it = open.erase(it);
      } else {
        if (r == z3::unknown) limited = true;
        ++it;
      }
    }
    if (open.empty() || depth >= options.maxDepth) break;
    bmc.add(enc.transition(depth));
  }
  out.bmcDepth = depth;
  result.depth = depth;
  if (complete && !limited) {
    for (std::size_t j : open) {
      result.properties[j].verdict = Verdict::Proven;
      out.proof[j] = SmtProof::Exhausted;
    }
    result.complete = true;
  } else {
    result.depthBounded = !result.rangeError;
  }

  // k-induction on what BMC did not decide: the base case is the BMC above (no violation within
  // `depth` steps), so k <= depth + 1 (and at most maxInduction: deeper levels cost much and rarely
  // succeed where IC3, next, does not). Candidates (and the ranges, which the reachable states keep
  // unless an update leaves them) are assumed at steps 0 .. k-1 of a loop-free path and must hold
  // at step k; a candidate that fails is dropped and the rest tried again, so that what remains
  // is inductive as a whole (and so proven).
  std::vector<char> inductiveFlags(props.size() + 1, 0);  // proven by induction: per property, and last the ranges
  inductiveFlags.back() = rangesHold ? 1 : 0;
  const bool unbounded = (options.induction || options.ic3) && !result.rangeError && !result.complete && !open.empty();
  const bool lemmas = unbounded && lemmasInductive(model, options);
  if (lemmas) out.lemmasProven = options.lemmas.size();
  if (options.induction && !result.rangeError && !result.complete && !open.empty()) {
    z3::context ictx;
    SmtEncoding ind(ictx, model);
    z3::solver step(ictx);
    z3::params iparams(ictx);
    if (options.timeoutMs != 0) iparams.set("timeout", options.timeoutMs);
    step.set(iparams);
    const std::size_t ranges = props.size();  // the pseudo-property "every variable in range"
    std::vector<std::size_t> candidates = open;
    candidates.push_back(ranges);
    z3::expr_vector flags(ictx);
    for (std::size_t j = 0; j <= props.size(); ++j) flags.push_back(ictx.bool_const(("assume_" + std::to_string(j)).c_str()));
    auto predicate = [&](std::size_t j, std::size_t k) {
      return j == ranges ? ind.inRange(k) : good(ind, model, props[j], k);
    };
    std::vector<char>& proven = inductiveFlags;
    const std::uint32_t maxK = std::min(depth + 1, options.maxInduction);
    // The proven lemmas hold in every reachable state, so in every state of the path.
    auto assumeLemmas = [&](std::size_t k) {
      if (!lemmas) return;
      for (const ir::Expr& l : options.lemmas) step.add(ind.holds(l, k));
    };
    assumeLemmas(0);
    for (std::uint32_t k = 1; k <= maxK; ++k) {
      if (options.onPhase) options.onPhase("smt: k-induction, k = " + std::to_string(k) + " of " + std::to_string(maxK));
      step.add(ind.transition(k - 1));
      assumeLemmas(k);
      for (std::size_t i = 0; i < k; ++i) step.add(!ind.sameState(i, k));
      for (std::size_t j : candidates) step.add(z3::implies(flags[static_cast<int>(j)], predicate(j, k - 1)));
      std::vector<std::size_t> inductive = candidates;
      for (bool changed = true; changed;) {
        changed = false;
        z3::expr_vector assumed(ictx);
        for (std::size_t j : inductive) assumed.push_back(flags[static_cast<int>(j)]);
        for (auto it = inductive.begin(); it != inductive.end(); ++it) {
          if (proven[*it]) continue;
          step.push();
          step.add(!predicate(*it, k));
          z3::check_result r = step.check(assumed);
          step.pop();
          if (r != z3::unsat) {
            if (r == z3::unknown) out.note = "a solver call of the induction gave up (--smt-timeout)";
            inductive.erase(it);
            changed = true;
            break;
          }
        }
      }
      for (std::size_t j : inductive) {
        if (proven[j]) continue;
        proven[j] = 1;
        if (j == ranges && options.onRangesHold) options.onRangesHold();
        if (j != ranges) {
          result.properties[j].verdict = Verdict::Proven;
          out.proof[j] = SmtProof::Induction;
          out.inductionDepth[j] = k;
        }
      }
      if (std::all_of(candidates.begin(), candidates.end(), [&](std::size_t j) { return proven[j] || j == ranges; })) break;
    }
  }
  if (options.ic3 && !result.rangeError && !result.complete) runIc3(model, props, options, inductiveFlags.back() != 0, lemmas, out);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace semo::checker
