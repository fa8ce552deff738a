// verify(): the engines run as `check` runs them, and their results gathered into one Report
// (verify.hpp). The words each verdict's coverage is given in are those `check` prints.
#include "semo/checker/verify.hpp"

#include <z3.h>

#include <algorithm>
#include <future>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "semo/checker/fingerprint.hpp"

namespace semo::checker {

namespace {

// A safety search that covered the whole state space within this many states makes each LTL
// property's product be searched whole first, within ten times as many product states (at least
// kWholeFirstProduct, at most kWholeFirstProductMost; LivenessOptions::wholeFirstStates); larger
// models go to the slices first. A swarm's properties read every robot, so its slices start with
// half the model and never end (100 robots: 530,646 states, the largest product 4.7 million,
// searched whole in about a minute, where the slices ran past 400 s).
constexpr std::uint64_t kWholeFirstReachable = 1'000'000;
constexpr std::uint64_t kWholeFirstProduct = 2'000'000;
constexpr std::uint64_t kWholeFirstProductMost = 10'000'000;

std::string steps(std::size_t n) { return std::to_string(n) + (n == 1 ? " step" : " steps"); }

bool anyViolated(const std::vector<PropertyResult>& properties) {
  return std::any_of(properties.begin(), properties.end(), [](const PropertyResult& p) { return p.verdict == Verdict::Violated; });
}

PropertyVerdict verdictOf(const PropertyResult& p, PropertyVerdict::Kind kind, const char* engine) {
  PropertyVerdict v;
  v.name = p.name;
  v.origin = p.origin;
  v.kind = kind;
  v.verdict = p.verdict;
  v.engine = engine;
  v.counterexample = p.counterexample;
  return v;
}

// The explicit engine's verdicts on the invariants.
void explicitSafetyVerdicts(Report& out) {
  const SearchResult& r = out.safety;
  for (const PropertyResult& p : r.properties) {
    PropertyVerdict v = verdictOf(p, PropertyVerdict::Kind::Safety, "explicit");
    if (p.verdict == Verdict::Proven) {
      v.proof = ProofKind::CompleteSearch;
      v.coverage = "all " + std::to_string(r.states) + " reachable states" + (r.symmetry.empty() ? "" : " up to symmetry") +
                   ", under the assumptions above";
    } else if (p.verdict == Verdict::Unknown && r.depthBounded) {
      v.coverage = "holds on every path of up to " + steps(r.depth) + ", " + std::to_string(r.states) + " states; longer paths not explored";
    } else if (p.verdict == Verdict::Unknown) {
      v.coverage = "not violated in the " + std::to_string(r.states) + " states explored; the search was not complete";
    } else if (p.counterexample) {
      v.coverage = "counterexample of " + steps(p.counterexample->steps.size()) + " below";
    }
    out.properties.push_back(std::move(v));
  }
}

// Where a liveness verdict was searched for: "on a slice of 8 of 64 variables, 558 product
// states" or "on the whole model, 1204 product states".
std::string livenessSearchText(const LivenessMethod& m, std::size_t variables) {
  const std::string states = std::to_string(m.states) + " product states";
  if (m.sliced && m.onCone) {
    std::string within = fmt::format("{:.0f}", m.symbolicStates) + " product states counted";
    if (!m.assumedInvariants.empty()) {
      within = "within a superset of the reachable states bounded by the proven invariants ";
      for (std::size_t i = 0; i < m.assumedInvariants.size(); ++i) within += (i == 0 ? "" : ", ") + m.assumedInvariants[i];
      within += " (" + fmt::format("{:.0f}", m.symbolicStates) + " product states counted)";
    }
    return "symbolically (decision diagrams) on the property's exact cone of influence (" + std::to_string(m.keptVariables) + " of " +
           std::to_string(variables) + " variables, crashes included), every settling world, " + within;
  }
  if (m.sliced && m.symbolic) {
    return "symbolically (decision diagrams) on a slice of " + std::to_string(m.keptVariables) + " of " + std::to_string(variables) +
           " variables, " + fmt::format("{:.0f}", m.symbolicStates) + " product states counted, after " + states + " enumerated";
  }
  if (m.sliced) return "on a slice of " + std::to_string(m.keptVariables) + " of " + std::to_string(variables) + " variables, " + states;
  return "on the whole model, " + states;
}

// The explicit engine's verdicts on the LTL properties (after the others).
void livenessVerdicts(Report& out, const ir::Model& model) {
  const LivenessResult& live = out.liveness;
  for (std::size_t k = 0; k < live.properties.size(); ++k) {
    const PropertyResult& p = live.properties[k];
    PropertyVerdict v = verdictOf(p, PropertyVerdict::Kind::Liveness, "explicit");
    const std::string note = k < live.notes.size() ? live.notes[k] : std::string();
    const bool searched = k < live.methods.size() && out.livenessSkipped.empty();
    const std::string where = searched ? livenessSearchText(live.methods[k], model.variables.size()) : std::string();
    // A settled property assumes that each sensed condition is in the end answered one way.
    const bool settled = k < model.properties.size() && model.properties[k].settled;
    const std::string world = settled ? " once what the robots sense settles" : "";
    if (p.verdict == Verdict::Proven) {
      v.proof = ProofKind::CompleteSearch;
      v.coverage = "every fair run" + world + ", under the assumptions above; searched " + where;
    } else if (p.verdict == Verdict::Unknown && out.livenessSkipped.empty()) {
      v.coverage = "no violation found in the part explored; the search was not complete";
      if (searched && !live.methods[k].slicingGaveUp.empty()) v.coverage += " (slices: " + live.methods[k].slicingGaveUp + ")";
    } else if (!note.empty()) {
      v.coverage = note;
    } else if (p.counterexample) {
      const Trace& t = *p.counterexample;
      v.coverage = "lasso of " + steps(t.steps.size()) + " below, " +
                   (t.loopStart >= t.steps.size() ? std::string("then it stays for ever") : "loop from step " + std::to_string(t.loopStart + 1)) +
                   (settled ? ", in which what the robots sense settles" : "");
      if (searched && live.methods[k].roundRobin) v.coverage += "; found with the robots taking turns, after no slice decided";
      if (searched && live.methods[k].walked) {
        v.coverage += "; found by random walks on the whole model (walk " + std::to_string(live.methods[k].walks) +
                      "), checked on it, after no slice decided";
      }
      if (searched && live.methods[k].onCone) {
        v.coverage += "; found symbolically on the property's exact cone (" + std::to_string(live.methods[k].keptVariables) + " of " +
                      std::to_string(model.variables.size()) + " variables), after no slice decided";
      }
      if (searched && live.methods[k].hunted) {
        v.coverage += "; found symbolically on the property's cone (" + std::to_string(live.methods[k].keptVariables) + " of " +
                      std::to_string(model.variables.size()) + " variables) without crashes, after no slice decided";
      }
    }
    out.properties.push_back(std::move(v));
  }
}

// The invariants a safety search proved (it lists them first, in the model's order).
std::vector<std::size_t> provenInvariants(const ir::Model& model, const SearchResult& r) {
  std::vector<std::size_t> proven;
  for (std::size_t i = 0; i < model.invariants.size() && i < r.properties.size(); ++i) {
    if (r.properties[i].verdict == Verdict::Proven && r.properties[i].name == model.invariants[i].name) proven.push_back(i);
  }
  return proven;
}

// The LTL properties: not after a modelling error, never depth-bounded (a lasso needs the whole
// product, or a slice's), not with --safety-only.
void runLiveness(Report& out, const ir::Model& model, const VerifyOptions& options, const SearchLimits& limits,
                 const LivenessOptions& liveness) {
  LivenessResult& live = out.liveness;
  if (model.properties.empty()) return;
  const SearchResult& r = out.safety;
  if (options.safetyOnly) out.livenessSkipped = "not checked: --safety-only";
  else if (r.rangeError) out.livenessSkipped = "not checked: the model has an error";
  else if (limits.maxDepth != UINT32_MAX) out.livenessSkipped = "not checked: --max-depth bounds safety only";
  if (out.livenessSkipped.empty()) {
    // A small state space, explored whole: each product is searched whole first (exact, fast).
    LivenessOptions tuned = liveness;
    tuned.provenInvariants = provenInvariants(model, r);
    if (tuned.wholeProduct && !tuned.slicesFirst && r.complete && r.states > 0 && r.states <= kWholeFirstReachable) {
      tuned.wholeFirstStates = std::clamp<std::uint64_t>(10 * r.states, kWholeFirstProduct, kWholeFirstProductMost);
    }
    live = checkLiveness(model, limits, tuned);
  } else {
    live.complete = false;
    live.limitReached = out.livenessSkipped;
    for (const ir::Property& p : model.properties) live.properties.push_back({p.name, p.origin, Verdict::Unknown, {}});
  }
  livenessVerdicts(out, model);
}

void runSmt(Report& out, const ir::Model& model, const model::MissionModel* mission, const VerifyOptions& options,
            const SourceManager& sources) {
  out.engine = Engine::Smt;
  SmtOptions smt = options.smt;
  if (options.limits.maxDepth != UINT32_MAX) smt.maxDepth = options.limits.maxDepth;
  // The LTL properties on slices of the model, whose products are small whatever the whole state
  // space: the explicit engine's, never its whole product (too large, or smt would not have run).
  LivenessOptions liveness = options.liveness;
  liveness.wholeProduct = false;
  SearchLimits limits = options.limits;
  limits.maxDepth = UINT32_MAX;  // BMC's depth, not the slices'
  // They start beside the safety proofs as soon as Z3 knows every variable stays in its range (a
  // model with a range error has its LTL properties left unchecked): the slices need nothing else,
  // and only an exact cone waits for the proven invariants. On scouting the proofs take 8 to 15 s
  // of one core, which the slices used to wait for.
  std::future<LivenessResult> beside;  // declared before the promise: a broken one frees the cone first
  std::promise<std::vector<std::size_t>> invariantsProven;
  if (!options.safetyOnly && !model.properties.empty()) {
    smt.onRangesHold = [&] {
      if (beside.valid()) return;
      LivenessOptions early = liveness;
      early.provenInvariantsLater = invariantsProven.get_future().share();
      beside = std::async(std::launch::async, [&model, &limits, early] { return checkLiveness(model, limits, early); });
    };
  }
  out.smt = checkSafetySmt(model, smt);
  const SmtResult& s = *out.smt;
  out.safety = s.search;
  invariantsProven.set_value(provenInvariants(model, out.safety));
  if (mission != nullptr) {
    const model::MissionModel& m = *mission;
    std::vector<std::int64_t> budget = m.assumptions.crashBudget;  // or the one --crash asks for, as the translation took it
    for (std::size_t t = 0; t < m.teams.size() && t < budget.size(); ++t) {
      auto team = options.crashPerTeam.find(m.teams[t].name);
      if (team != options.crashPerTeam.end()) {
        budget[t] = std::min<std::int64_t>(team->second, static_cast<std::int64_t>(m.teams[t].robots.size()));
      } else if (options.crashOverride) {
        budget[t] = std::min<std::int64_t>(*options.crashOverride, static_cast<std::int64_t>(m.teams[t].robots.size()));
      }
    }
    out.formation = checkGroupFormation(m, &budget);
    if (!options.propertyGlobs.empty()) {
      std::erase_if(out.formation,
                    [&](const FormationVerdict& v) { return !propertySelected(options.propertyGlobs, {"group_formation[" + v.block + "]"}); });
    }
    for (const FormationVerdict& v : out.formation) {
      const SourceRange& at = m.groupBlocks[v.blockIndex].at;
      out.formationOrigins.push_back(at.begin.valid() ? sources.path(at.begin.file) + ":" + std::to_string(at.begin.line) + ":" +
                                                            std::to_string(at.begin.column)
                                                      : "");
    }
  }
  const SearchResult& r = out.safety;
  for (std::size_t j = 0; j < r.properties.size(); ++j) {
    const PropertyResult& p = r.properties[j];
    PropertyVerdict v = verdictOf(p, PropertyVerdict::Kind::Safety, "smt");
    if (s.proof[j] == SmtProof::Induction) {
      v.proof = ProofKind::KInduction;
      v.k = s.inductionDepth[j];
      v.coverage = "proven by k-induction at k = " + std::to_string(v.k) + ", under the assumptions above";
    } else if (s.proof[j] == SmtProof::Ic3) {
      v.proof = ProofKind::Ic3;
      v.conjuncts = s.invariantConjuncts[j];
      v.coverage = "proven by induction with a strengthening invariant of " + std::to_string(v.conjuncts) +
                   (v.conjuncts == 1 ? " conjunct" : " conjuncts") + " found by IC3 and checked independently, under the assumptions above";
    } else if (p.verdict == Verdict::Proven) {
      v.proof = ProofKind::Exhausted;
      v.coverage = "no path is longer than " + std::to_string(s.bmcDepth) + " steps: every reachable state checked, under the assumptions above";
    } else if (p.verdict == Verdict::Unknown && !r.rangeError) {
      v.coverage = "holds on every path of up to " + std::to_string(s.bmcDepth) + " steps; not proven for longer ones" +
                   (!smt.induction && !smt.ic3 ? std::string()
                                               : ": no induction up to k = " + std::to_string(std::min(s.bmcDepth + 1, smt.maxInduction)) +
                                                     ", IC3 undecided");
    } else if (p.counterexample) {
      v.coverage = "counterexample of " + steps(p.counterexample->steps.size()) + " below" +
                   (s.deepCounterexample[j] != 0 ? ", found by IC3 beyond depth " + std::to_string(s.bmcDepth) + "; a shorter one may exist" : "");
    }
    out.properties.push_back(std::move(v));
  }
  for (std::size_t b = 0; b < out.formation.size(); ++b) {
    const FormationVerdict& f = out.formation[b];
    PropertyVerdict v;
    v.name = "group_formation[" + f.block + "]";
    v.origin = out.formationOrigins[b];
    v.kind = PropertyVerdict::Kind::GroupFormation;
    v.engine = "smt";
    v.verdict = f.holds() ? Verdict::Proven : Verdict::Violated;
    if (f.holds()) {
      v.proof = ProofKind::Z3Formation;
      v.coverage = formationCoverage(f);
    }
    out.properties.push_back(std::move(v));
  }
  if (beside.valid()) {
    out.liveness = beside.get();
    livenessVerdicts(out, model);
  } else {
    runLiveness(out, model, options, limits, liveness);
  }
  bool violated = r.rangeError.has_value() || anyViolated(r.properties) || anyViolated(out.liveness.properties);
  for (const FormationVerdict& f : out.formation) violated = violated || !f.holds();
  bool undecided = !out.liveness.complete;
  for (const PropertyResult& p : r.properties) undecided = undecided || p.verdict == Verdict::Unknown;
  out.exitCode = violated ? 1 : undecided ? 3 : 0;
}

// The counter abstraction (counter_abstraction.hpp) on a model with team counts; false when it
// does not apply (Report::counting says why).
bool runCounting(Report& out, const ir::Model& model, const VerifyOptions& options) {
  CountingOptions counting;
  counting.onPhase = options.limits.onPhase;
  counting.maxStates = std::min<std::uint64_t>(options.limits.maxStates, kAutoStateBudget);
  counting.countedTeamsFrom = options.countedTeamsFrom;
  out.counting = checkByCounting(model, options.smt.lemmas, counting);
  return out.counting->applicable;
}

bool countingDecides(const CountingResult& c, bool safetyOnly) {
  if (!c.applicable) return false;
  if (!safetyOnly) return c.allProven();
  auto proven = [](const CountingVerdict& v) { return v.verdict == Verdict::Proven; };
  return std::all_of(c.invariants.begin(), c.invariants.end(), proven) && (!c.deadlockChecked || proven(c.deadlock));
}

// The counter abstraction's verdicts, as the report's.
void countingVerdicts(Report& out, const ir::Model& model, bool safetyOnly) {
  const CountingResult& c = *out.counting;
  out.engine = Engine::Counting;
  out.safety.states = c.states;
  out.safety.transitions = c.transitions;
  out.safety.complete = c.applicable;
  out.safety.seconds = c.seconds;
  if (!c.applicable) out.safety.limitReached = "the counter abstraction does not apply: " + c.why;
  const std::string counted = std::to_string(c.robots) + " robots counted per local state (0, 1, " + std::to_string(c.threshold) + " or more)";
  auto add = [&](const CountingVerdict* cv, const std::string& name, const std::string& origin, PropertyVerdict::Kind kind, bool settled) {
    PropertyVerdict v;
    v.name = name;
    v.origin = origin;
    v.kind = kind;
    v.engine = "counting";
    if (cv == nullptr) {
      v.coverage = c.applicable ? "not checked: --safety-only" : "the counter abstraction does not apply: " + c.why;
    } else if (cv->verdict == Verdict::Proven) {
      v.verdict = Verdict::Proven;
      v.proof = ProofKind::Counting;
      const std::string apart = cv->explicitRobots.empty() ? "" : ", " + fmt::format("{}", fmt::join(cv->explicitRobots, ", ")) + " apart";
      v.coverage = (kind == PropertyVerdict::Kind::Safety ? "all " + std::to_string(c.states) + " states"
                                                          : "every fair run" + std::string(settled ? " (settled or not)" : "")) +
                   " of the counter abstraction (" + counted + apart + ", " + std::to_string(c.localStates) + " local states" +
                   (kind == PropertyVerdict::Kind::Liveness ? ", " + std::to_string(cv->productStates) + " product states" : "") +
                   "), under the assumptions above";
      v.everyTeamFrom = cv->everyTeamFrom;
      if (cv->everyTeamFrom > 0) v.coverage += "; the same for a team of any size from " + std::to_string(cv->everyTeamFrom) + " robots";
    } else {
      v.coverage = "undecided by the counter abstraction: " + cv->why;
    }
    out.properties.push_back(std::move(v));
  };
  for (std::size_t i = 0; i < model.invariants.size(); ++i) {
    add(i < c.invariants.size() ? &c.invariants[i] : nullptr, model.invariants[i].name, model.invariants[i].origin, PropertyVerdict::Kind::Safety, false);
  }
  if (model.validEnd) add(c.deadlockChecked ? &c.deadlock : nullptr, "deadlock_freedom", "", PropertyVerdict::Kind::Safety, false);
  if (safetyOnly && !model.properties.empty()) out.livenessSkipped = "not checked: --safety-only";
  for (std::size_t k = 0; k < model.properties.size(); ++k) {
    const ir::Property& p = model.properties[k];
    add(safetyOnly || k >= c.properties.size() ? nullptr : &c.properties[k], p.name, p.origin, PropertyVerdict::Kind::Liveness, p.settled);
  }
  // As the explicit engine: LTL properties left unchecked (--safety-only) make a partial result.
  out.exitCode = countingDecides(c, safetyOnly) && (!safetyOnly || model.properties.empty()) ? 0 : 3;
}

void runExplicit(Report& out, const ir::Model& model, const model::MissionModel* mission, const VerifyOptions& options,
                 const SourceManager& sources) {
  const bool automatic = options.engine == Engine::Auto;
  std::string counted;
  if (automatic && !options.smt.lemmas.empty()) {
    // A team with counts: counting first, whose cost does not grow with the team.
    if (runCounting(out, model, options) && countingDecides(*out.counting, options.safetyOnly)) {
      out.engineReason = "a team of " + std::to_string(out.counting->robots) +
                         " interchangeable robots, counted per local state: the counter abstraction proves every property";
      countingVerdicts(out, model, options.safetyOnly);
      return;
    }
    const CountingResult& c = *out.counting;
    if (c.applicable) {
      std::vector<std::string> open;
      for (const CountingVerdict& v : c.invariants) {
        if (v.verdict != Verdict::Proven) open.push_back(v.name);
      }
      if (c.deadlockChecked && c.deadlock.verdict != Verdict::Proven) open.push_back(c.deadlock.name);
      for (const CountingVerdict& v : c.properties) {
        if (v.verdict != Verdict::Proven && !options.safetyOnly) open.push_back(v.name);
      }
      counted = "the counter abstraction left " + fmt::format("{}", fmt::join(open, ", ")) + " undecided, so ";
    } else {
      counted = "the counter abstraction does not apply (" + c.why + "), so ";
    }
  }
  const bool ltl = !options.safetyOnly && !model.properties.empty();
  SearchLimits limits = options.limits;
  if (automatic) {
    // The probe is never depth-bounded: a bound is for BMC, should smt be chosen.
    limits.maxStates = std::min(options.limits.maxStates, kAutoStateBudget);
    limits.maxDepth = UINT32_MAX;
  }
  out.engine = Engine::Explicit;
  out.safety = checkSafety(model, limits);
  const SearchResult& r = out.safety;
  if (automatic) {
    const bool found = r.rangeError.has_value() || anyViolated(r.properties);
    if (!r.complete && !found && !r.depthBounded) {
      out.engineReason = counted + "the explicit search did not cover the state space within its budget of " + withThousands(limits.maxStates) +
                         " states, so smt" + (ltl ? "; the LTL properties on slices of the model (cone of influence, refined by counterexamples), " +
                                                        std::string("never on the whole product")
                                                  : std::string());
      runSmt(out, model, mission, options, sources);
      return;
    }
    out.engineReason = counted + (found ? "the explicit search found a violation within its budget of " + withThousands(kAutoStateBudget) + " states"
                                        : "the state space fits the explicit engine's budget of " + withThousands(kAutoStateBudget) + " states");
    if (ltl && options.liveness.slicing) out.engineReason += "; the LTL properties on slices of the model first, on the whole product where no slice decides";
    limits.maxStates = options.limits.maxStates;  // the liveness products get the usual limit
  }
  explicitSafetyVerdicts(out);

  runLiveness(out, model, options, limits, options.liveness);
  const LivenessResult& live = out.liveness;
  const bool violated = r.rangeError.has_value() || anyViolated(r.properties) || anyViolated(live.properties);
  out.exitCode = violated ? 1 : r.complete && live.complete ? 0 : 3;
}

// 0 sound everywhere; 1 a real defect (inconsistent, deadlocking, a bound refuted); 3 undecided.
int taskGraphCode(const std::vector<TaskGraphReport>& graphs) {
  bool sound = true, decided = true;
  for (const TaskGraphReport& g : graphs) {
    for (const sdf::ScenarioAnalysis& a : g.analysis.scenarios) {
      sound = sound && a.sound();
      decided = decided && a.decided();
    }
  }
  return sound ? 0 : decided ? 1 : 3;
}

// Why a scenario is not sound, in the words `sdf` prints.
std::string scenarioDefect(const sdf::ScenarioAnalysis& a) {
  if (!a.repetition.consistent()) return "inconsistent (" + a.repetition.error + ")";
  if (!a.iteration.error.empty()) return "deadlock freedom unknown (" + a.iteration.error + ")";
  if (!a.iteration.deadlockFree) return "deadlocks";
  if (!a.unbounded.error.empty()) return "period not computed (" + a.unbounded.error + ")";
  if (!a.bounds.haveBounds) return "buffer bounds unknown (" + a.bounds.error + ")";
  std::string out;
  for (const auto* b : {&a.bounds.deadlockFree, &a.bounds.maxThroughput}) {
    const char* which = b == &a.bounds.deadlockFree ? "deadlock-free" : "max-throughput";
    if (b->safety != sdf::ProofStatus::Proven) out += std::string(out.empty() ? "" : "; ") + which + " bounds: no overflow/underflow " + sdf::proofStatusName(b->safety);
    if (b->minimality != sdf::ProofStatus::Proven) out += std::string(out.empty() ? "" : "; ") + which + " bounds: minimal " + sdf::proofStatusName(b->minimality);
  }
  return out;
}

}  // namespace

std::string withThousands(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

const char* const kTaskGraphAssumptions =
    "execution times are the strategy's worst cases (generated control and communication tasks: 1 ms nominal); "
    "a task's firings run one at a time; channels are FIFO with space claimed when a firing starts and freed when "
    "the consuming firing ends; messages between robots are outside these graphs";

std::string z3Version() {
  unsigned major = 0, minor = 0, build = 0, revision = 0;
  Z3_get_version(&major, &minor, &build, &revision);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(build) + "." + std::to_string(revision);
}

const char* proofKindName(ProofKind k) {
  switch (k) {
    case ProofKind::None: return "none";
    case ProofKind::CompleteSearch: return "complete search";
    case ProofKind::Exhausted: return "bounded model checking, every path exhausted";
    case ProofKind::KInduction: return "k-induction";
    case ProofKind::Ic3: return "IC3 invariant";
    case ProofKind::Z3Formation: return "Z3, every crash set";
    case ProofKind::Counting: return "counter abstraction";
  }
  return "none";
}

const char* propertyKindName(PropertyVerdict::Kind k) {
  switch (k) {
    case PropertyVerdict::Kind::Safety: return "safety";
    case PropertyVerdict::Kind::Liveness: return "liveness";
    case PropertyVerdict::Kind::GroupFormation: return "group formation";
  }
  return "safety";
}

std::vector<std::string> Report::unproven() const {
  std::vector<std::string> out;
  if (safety.rangeError) out.push_back("the model has an error: " + safety.limitReached);
  for (const PropertyVerdict& p : properties) {
    if (p.verdict == Verdict::Proven) continue;
    out.push_back(std::string(verdictName(p.verdict)) + " " + p.name + (p.coverage.empty() ? "" : " (" + p.coverage + ")"));
  }
  for (const TaskGraphReport& g : taskGraphs) {
    for (const sdf::ScenarioAnalysis& a : g.analysis.scenarios) {
      if (!a.sound()) out.push_back("task graph of " + g.graph.robot + ", scenario " + a.scenario + ": " + scenarioDefect(a));
    }
  }
  return out;
}

void addTaskGraphs(Report& report, std::vector<sdf::TaskGraph> graphs, const sdf::BoundsOptions& bounds) {
  report.taskGraphAssumptions = kTaskGraphAssumptions;
  sdf::ScenarioCache cache;  // robots of one type in one role: each distinct scenario graph once
  for (std::size_t i = 0; i < graphs.size(); ++i) {
    sdf::TaskGraph& g = graphs[i];
    if (bounds.onPhase) {
      bounds.onPhase("sdf: " + g.robot + " (" + std::to_string(i + 1) + " of " + std::to_string(graphs.size()) + "): " +
                     std::to_string(g.scenarios.size()) + " scenarios, buffer fronts and proofs");
    }
    sdf::TaskGraphAnalysis analysis = sdf::analyseTaskGraph(g, bounds, &cache);
    report.taskGraphs.push_back({std::move(g), std::move(analysis)});
  }
  const int code = taskGraphCode(report.taskGraphs);
  // A violation anywhere wins; then anything undecided; 0 only when both halves are.
  if (report.exitCode == 1 || code == 1) report.exitCode = 1;
  else if (report.exitCode == 3 || code == 3) report.exitCode = 3;
}

namespace {

// The checks the verify block names that this mission gives nothing to check: reported proven,
// with the reason, rather than silently left out. Only those the selection (--prop) asks for.
void addVacuousVerdicts(Report& out, const ir::Model& model, const model::MissionModel& m, const std::vector<std::string>& globs) {
  if (!m.assumptions.checksListed) return;
  auto family = [](const std::string& name, const std::string& check) { return name == check || name.rfind(check + "[", 0) == 0; };
  for (const std::string& check : m.assumptions.checks) {
    if (!globs.empty() && !propertySelected(globs, {check, check + "[*]", check + "[]"})) continue;
    bool any = check == "deadlock_freedom" ? model.validEnd.has_value() : false;
    for (const ir::Invariant& i : model.invariants) any = any || family(i.name, check);
    for (const ir::Property& p : model.properties) any = any || family(p.name, check);
    for (const PropertyVerdict& v : out.properties) any = any || family(v.name, check);
    if (any) continue;
    std::string why;
    bool leaders = false, groups = !m.groupBlocks.empty(), knowledge = false, sends = false, teams = false;
    for (const model::GroupBlock& b : m.groupBlocks) leaders = leaders || b.isLeaderBlock;
    for (const model::Topic& t : m.topics) sends = sends || (t.reliable && t.written);
    for (const strategy::Service& s : m.strategy.services) knowledge = knowledge || (s.kind == strategy::Service::Kind::Group && !s.knowledge.empty());
    for (const model::Team& t : m.teams) teams = teams || (t.robots.size() >= 2 && t.modes.size() >= 2);
    if (check == "group_formation") why = groups ? "no group block is reached" : "the mission has no group block";
    else if (check == "unique_leader" || check == "leader_reelection") why = leaders ? "no leader block is reached" : "the mission has no leader block";
    else if (check == "buffer_bounds") why = sends ? "no channel is used" : "the mission sends nothing (no send/receive channel)";
    else if (check == "knowledge_convergence") why = knowledge ? "no group service with knowledge runs in the mission" : "no group service shares knowledge";
    else if (check == "mode_agreement") why = teams ? "no team can disagree" : "no team has two robots and two modes";
    else why = "nothing in the mission to check";
    PropertyVerdict v;
    v.name = check;
    v.kind = check == "mode_agreement" || check == "knowledge_convergence" || check == "leader_reelection" ? PropertyVerdict::Kind::Liveness
                                                                                                      : PropertyVerdict::Kind::Safety;
    v.verdict = Verdict::Proven;
    v.engine = out.engine == Engine::Smt ? "smt" : out.engine == Engine::Counting ? "counting" : "explicit";
    v.vacuous = why;
    v.coverage = "vacuous: " + why;
    out.properties.push_back(std::move(v));
  }
}

}  // namespace

std::optional<Report> verify(const ir::Model& model, const model::MissionModel* mission, const VerifyOptions& options,
                             DiagnosticEngine& diags) {
  for (const ir::Rule& r : model.rules) {
    // The searches number a rule's outcomes in 8 bits; the quantitative engine takes more.
    if (options.properties && r.branches.size() > ir::kMaxSearchedOutcomes) {
      diags.error({}, "rule '" + r.name + "' has " + std::to_string(r.branches.size()) + " outcomes; the searches of `check` take rules of at most " +
                          std::to_string(ir::kMaxSearchedOutcomes) + " (only the quantitative engine takes more)");
      return std::nullopt;
    }
  }
  Report out;
  out.modelFingerprint = modelFingerprint(model);
  out.assumptions = model.assumptions;
  if (options.properties) {
    if (options.engine == Engine::Smt) {
      runSmt(out, model, mission, options, diags.sources());
    } else if (options.engine == Engine::Counting) {
      runCounting(out, model, options);
      countingVerdicts(out, model, options.safetyOnly);
    } else {
      runExplicit(out, model, mission, options, diags.sources());
    }
    if (mission != nullptr) addVacuousVerdicts(out, model, *mission, options.propertyGlobs);
  }
  if (options.taskGraphs && mission != nullptr) {
    std::optional<std::vector<sdf::TaskGraph>> graphs = sdf::generateTaskGraphs(*mission, diags);
    if (!graphs) return std::nullopt;
    addTaskGraphs(out, std::move(*graphs), options.bounds);
  }
  return out;
}

}  // namespace semo::checker
