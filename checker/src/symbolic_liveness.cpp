#include "symbolic_liveness.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "semo/checker/buchi.hpp"
#include "semo/checker/fairness.hpp"
#include "semo/checker/trace.hpp"
#include "recurring_rules.hpp"
#include "projected_reach.hpp"
#include "shared_worlds.hpp"
#include "symbolic_apart.hpp"
#include "symbolic_product.hpp"

namespace semo::checker::detail {
namespace {

std::mutex packageLock;  // BuDDy's package is one per process

}  // namespace
}  // namespace semo::checker::detail

// BuDDy's flag for a started package (kernel.c; exported by libbdd, not in its public header):
// bdd_init refuses to start a package while it is set. A forked child clears it to start its own.
extern "C" int bddrunning;

namespace semo::checker::detail {
namespace {

// A loop on a settling world decides each sensed condition one way only. The fair states are
// first found with every rule allowed in the loop; where their steps decide a condition both ways,
// the search splits in two (the loop decides it one way, or the other), each from the states found,
// as the explicit engine splits a strongly connected component.
constexpr std::uint32_t kMaxWorlds = 512;
// SymbolicLimits::everyWorld searches each of the 2^points worlds only up to this many points.
constexpr std::size_t kEveryWorldPoints = 6;

class SettledSearch {
 public:
  SettledSearch(SymbolicProduct& product, const Sensing& sensing, std::size_t rules, const LoopNarrowing* narrowing)
      : product_(product), sensing_(sensing), rules_(rules), narrowing_(narrowing) {
    for (std::uint32_t p = 0; p < sensing.names.size(); ++p) pointOf_.emplace(sensing.names[p], p);
  }

  bool violated(const bdd& reach, bool settled) {
    std::vector<std::int8_t> world(settled ? sensing_.points : 0, -1);
    return search(reach, world);
  }
  // Every settling world, each sensed condition decided one way or the other: up to 2^points
  // searches, each with its loops narrowed the most (recurring_rules.hpp), where the splitting above
  // starts from the world that decides nothing, whose fixpoint on a large model is the dearest of all
  // (scouting's cone: measured in checker/README.md). A condition whose deciding narrows nothing but
  // the rules that decide it stays open (pointsLeftOpen): its two worlds are searched as one, split only
  // if a loop there decides it both ways. With `helper`, a forked process searches worlds beside
  // this one (shared_worlds.hpp); the answer is the lowest world with fair states either way, and
  // its fair states are this process's for the lasso.
  bool violatedOnEveryWorld(const bdd& reach, bool helper) {
    const std::vector<char> open = pointsLeftOpen();
    opened_ = static_cast<std::uint32_t>(std::count(open.begin(), open.end(), 1));
    std::vector<std::uint32_t> decided;
    for (std::uint32_t p = 0; p < open.size(); ++p) {
      if (open[p] == 0) decided.push_back(p);
    }
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      for (std::uint32_t p = 0; p < open.size(); ++p) {
        if (open[p] != 0) std::fprintf(stderr, "[symbolic] %s left open: its two worlds searched as one\n", sensing_.names[p].c_str());
      }
    }
    const std::uint64_t count = std::uint64_t{1} << decided.size();
    auto searchWorld = [&](std::uint64_t w) {
      std::vector<std::int8_t> world(open.size(), -1);
      for (std::size_t i = 0; i < decided.size(); ++i) world[decided[i]] = static_cast<std::int8_t>((w >> i) & 1);
      return search(reach, world);  // found_ set when true
    };
    std::optional<std::uint64_t> foundHere;
    const auto left = product_.timeLeft();
    const SharedWorlds shared = searchWorldsShared(
        count,
        [&](std::uint64_t w) {
          const bool found = searchWorld(w);
          if (found) foundHere = w;
          return found;
        },
        helper, [&] { product_.continueInHelper(left); });
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr && shared.helperStarted) {
      std::fprintf(stderr, "[symbolic] %llu worlds searched by the helper process\n", static_cast<unsigned long long>(shared.byHelper));
    }
    if (shared.violatedWorld && foundHere != shared.violatedWorld) searchWorld(*shared.violatedWorld);
    // As one process counts them: up to the world with fair states, or all.
    worlds_ = static_cast<std::uint32_t>(shared.violatedWorld ? *shared.violatedWorld + 1 : count);
    return shared.violatedWorld.has_value();
  }
  // Whether a fair violation has a loop that senses nothing (settled whatever the world does):
  // one search, no splitting; a hunt's question, not a proof's.
  bool violatedQuietly(const bdd& reach) {
    std::vector<char> allowed(rules_, 0);
    for (std::uint32_t r = 0; r < rules_; ++r) allowed[r] = sensing_.of[r].empty() ? 1 : 0;
    narrow(allowed, [](const ir::SensedOutcome&) { return false; });
    ++worlds_;
    found_ = product_.fairStates(reach, allowed);
    foundAllowed_ = std::move(allowed);
    return found_ != bddfalse;
  }
  [[nodiscard]] std::uint32_t worlds() const { return worlds_; }
  [[nodiscard]] std::uint32_t openPoints() const { return opened_; }
  // After a violation: the fair states of the world it was found in, and the rules its loop may use.
  [[nodiscard]] const bdd& fairStates() const { return found_; }
  [[nodiscard]] const std::vector<char>& loopRules() const { return foundAllowed_; }

 private:
  bool search(const bdd& from, std::vector<std::int8_t>& world) {
    if (++worlds_ > kMaxWorlds) throw GiveUp("more than 512 ways the world may settle had to be searched");
    std::vector<char> allowed = loopRulesOf(world, true);
    const bdd z = product_.fairStates(from, allowed);
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) std::fprintf(stderr, "[symbolic] world %u: %.0f fair states\n", worlds_, product_.count(z));
    if (z == bddfalse) return false;
    found_ = z;
    foundAllowed_ = allowed;
    const bdd zAfter = product_.automatonPredecessors(z);
    for (std::uint32_t p = 0; p < world.size(); ++p) {
      if (world[p] >= 0) continue;
      bool decides[2] = {false, false};
      for (std::uint32_t r = 0; r < rules_ && !(decides[0] && decides[1]); ++r) {
        if (allowed[r] == 0) continue;
        for (const Sensing::Decision& d : sensing_.of[r]) {
          if (d.point == p && !decides[d.holds ? 1 : 0] && product_.stepsWithin(z, zAfter, r)) decides[d.holds ? 1 : 0] = true;
        }
      }
      if (!(decides[0] && decides[1])) continue;
      for (std::int8_t way : {std::int8_t{1}, std::int8_t{0}}) {
        world[p] = way;
        const bool found = search(z, world);
        world[p] = -1;
        if (found) return true;
      }
      return false;
    }
    return true;  // no step inside decides a condition both ways
  }

  // Leaves out of `allowed` the rules the model the searched one was cut from cannot repeat on a
  // loop that senses as `senses` lets it.
  void narrow(std::vector<char>& allowed, const std::function<bool(const ir::SensedOutcome&)>& senses, bool say = true) const {
    if (narrowing_ == nullptr) return;
    const std::vector<char> recur = narrowing_->loopRules(senses);
    std::size_t left = 0;
    for (std::uint32_t r = 0; r < rules_; ++r) {
      if (allowed[r] != 0 && recur[r] == 0) allowed[r] = 0, ++left;
    }
    if (say && std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) std::fprintf(stderr, "[symbolic] %zu rules cannot recur on this world's loops\n", left);
  }

  // The rules a loop of `world` may take (each point decided 0 or 1, or open: -1): those that
  // decide its conditions its way, narrowed to those that can recur there.
  std::vector<char> loopRulesOf(const std::vector<std::int8_t>& world, bool say = false) const {
    std::vector<char> allowed(rules_, 1);
    for (std::uint32_t r = 0; r < rules_; ++r) allowed[r] = world.empty() || sensing_.agrees(r, world) ? 1 : 0;
    narrow(
        allowed,
        [&](const ir::SensedOutcome& o) {
          const auto p = pointOf_.find(o.point);
          return world.empty() || p == pointOf_.end() || world[p->second] < 0 || world[p->second] == static_cast<std::int8_t>(o.holds);
        },
        say);
    return allowed;
  }

  // The conditions the search of every world may leave open. A point is open when, on every world
  // of the other points, the rules a loop may take with it open are exactly those of its two ways
  // together, and each rule that does not decide it is allowed the same either way: deciding it
  // narrows nothing but its own rules, so the two worlds' fixpoints work on the same loops but for
  // those, and one search costs about what each did. Taken greedily, in order, each on the worlds
  // left. On scouting's mode_agreement cone the first of the four points is open (16 worlds -> 8,
  // the fixpoints' processor time 238 s -> 121 s); the second changes which rules recur, and
  // leaving it open anyway took 556 s (checker/README.md).
  std::vector<char> pointsLeftOpen() const {
    const std::size_t points = sensing_.points;
    std::vector<char> open(points, 0);
    if (narrowing_ == nullptr) return open;  // every point would be open: the dearest search
    std::vector<char> decides(rules_, 0);
    for (std::uint32_t p = 0; p < points; ++p) {
      for (std::uint32_t r = 0; r < rules_; ++r) {
        decides[r] = std::any_of(sensing_.of[r].begin(), sensing_.of[r].end(), [p](const Sensing::Decision& d) { return d.point == p; }) ? 1 : 0;
      }
      bool same = true;
      for (std::uint64_t w = 0; w < (std::uint64_t{1} << points) && same; ++w) {
        if ((w >> p & 1) != 0) continue;
        std::vector<std::int8_t> world(points, 0);
        for (std::size_t q = 0; q < points; ++q) world[q] = open[q] != 0 ? std::int8_t{-1} : static_cast<std::int8_t>((w >> q) & 1);
        bool repeated = false;  // the same world as one with an open point's bit clear: compared then
        for (std::size_t q = 0; q < points && !repeated; ++q) repeated = open[q] != 0 && (w >> q & 1) != 0;
        if (repeated) continue;
        const std::vector<char> no = loopRulesOf(world);
        world[p] = 1;
        const std::vector<char> yes = loopRulesOf(world);
        world[p] = -1;
        const std::vector<char> either = loopRulesOf(world);
        for (std::uint32_t r = 0; r < rules_ && same; ++r) {
          same = decides[r] != 0 ? either[r] == (no[r] | yes[r]) : no[r] == yes[r] && either[r] == no[r];
        }
      }
      open[p] = same ? 1 : 0;
    }
    return open;
  }

  SymbolicProduct& product_;
  const Sensing& sensing_;
  const std::size_t rules_;
  const LoopNarrowing* narrowing_;
  std::unordered_map<std::string, std::uint32_t> pointOf_;
  std::uint32_t worlds_ = 0;
  std::uint32_t opened_ = 0;
  bdd found_;
  std::vector<char> foundAllowed_;
};

// A lasso through the fair states a search found, as the explicit engine prints one: the shortest
// way in, then a loop that meets each obligation in turn (each acceptance set, each weakly fair
// group disabled or taken, each strongly fair rule enabled on the loop taken) and returns to where
// it began. Every fair state reaches each obligation inside the fair states (the fixpoint's
// definition), so the only way to fail is not to get back; the loop then starts again where the
// walk ended, inside what that state reaches. Those sets shrink at each new start, down to at
// worst a bottom component, where every state reaches every other, so the search ends; it rarely
// needs more than a start or two, where narrowing to a bottom component first costs a closure per
// step. Each step is taken concretely, the decision diagrams only saying which states lead on.
class SymbolicLasso {
 public:
  using Concrete = SymbolicProduct::Concrete;
  using Move = SymbolicProduct::Move;

  explicit SymbolicLasso(SymbolicProduct& product) : p_(product), all_(product.rules(), 1) {}

  Trace build(const bdd& reach, const bdd& fair, const std::vector<char>& loopRules) {
    // From an initial state that leads to the fair states (the automaton may have several).
    current_ = p_.initialState(p_.until(reach, fair, all_));
    initial_ = current_.values;
    walkTo(fair, reach, all_);
    bdd region = fair;
    while (true) {
      const std::size_t loopStart = moves_.size();
      const Concrete anchor = current_;
      if (meetObligations(region, loopRules, loopStart, anchor)) return trace(loopStart);
      // Not back: what this state reaches is a smaller region that still holds a fair loop.
      region &= p_.forwardClosure(p_.cubeOf(current_), region, loopRules);
    }
  }

 private:
  // Walks a loop from `anchor` (where the walk is) through every obligation and back; false when
  // the walk ends where `anchor` is out of reach (the steps taken stay, as part of the way in).
  bool meetObligations(const bdd& region, const std::vector<char>& allowed, std::size_t loopStart, const Concrete& anchor) {
    for (std::size_t i = 0; i < p_.acceptanceSets(); ++i) walkTo(region & p_.acceptanceSet(i), region, allowed);
    const Fairness& f = p_.fairness();
    for (std::uint32_t g = 0; g < f.groups(); ++g) {
      if (f.strong[g] != 0 || !p_.contains(p_.groupEnabled(g), current_)) continue;
      // To the nearest state that has the group disabled or takes its step; then that step.
      walkTo(region & (bdd_not(p_.groupEnabled(g)) | takesGroup(g, region, allowed)), region, allowed);
      if (p_.contains(p_.groupEnabled(g), current_)) takeGroup(g, region, allowed);
    }
    if (moves_.size() == loopStart) take(region, allowed);  // a loop has at least one step
    // Strongly fair groups: each one enabled somewhere on the loop is taken on it. Taking one, or
    // the way home, may pass states that enable another: the loop is looked at again until none
    // is missing (each group is taken once at most, so this ends).
    const bdd home = p_.cubeOf(anchor);
    while (true) {
      const std::optional<std::uint32_t> g = missingStrongGroup(loopStart, anchor);
      if (!g) {
        if (p_.contains(home, current_)) return true;
        if (!p_.contains(p_.until(region, home, allowed), current_)) return false;
        walkTo(home, region, allowed);
        continue;
      }
      // A loop state reaches a step of the group (the fixpoint); one that cannot is not back.
      const bdd takes = takesGroup(*g, region, allowed);
      if (!p_.contains(p_.until(region, takes, allowed), current_)) return false;
      walkTo(takes, region, allowed);
      takeGroup(*g, region, allowed);
    }
  }

  // A strongly fair group enabled in a state of the loop walked so far (from `anchor`, the
  // current state included) and not taken on it.
  std::optional<std::uint32_t> missingStrongGroup(std::size_t loopStart, const Concrete& anchor) const {
    const Fairness& f = p_.fairness();
    for (std::uint32_t g = 0; g < f.groups(); ++g) {
      if (f.strong[g] == 0) continue;
      bool enabled = p_.contains(p_.groupEnabled(g), current_), took = false;
      for (std::size_t k = loopStart; k < moves_.size() && !took; ++k) {
        enabled = enabled || p_.contains(p_.groupEnabled(g), k == loopStart ? anchor : moves_[k - 1].after);
        took = std::find(f.members[g].begin(), f.members[g].end(), moves_[k].rule) != f.members[g].end();
      }
      if (enabled && !took) return g;
    }
    return std::nullopt;
  }

  // The states of `region` that take one of the group's steps inside it.
  bdd takesGroup(std::uint32_t g, const bdd& region, const std::vector<char>& allowed) {
    return p_.predecessors(region, allowed, &p_.fairness().members[g], region);
  }

  // One of the group's steps inside `region` (the walk is where one is taken).
  void takeGroup(std::uint32_t g, const bdd& region, const std::vector<char>& allowed) {
    const Fairness& f = p_.fairness();
    std::vector<char> only(p_.rules(), 0);
    for (std::uint32_t r : f.members[g]) only[r] = allowed[r];
    take(region, only);
  }

  // Along a shortest path inside `within` to a state of `goal` (which it reaches).
  void walkTo(const bdd& goal, const bdd& within, const std::vector<char>& allowed) {
    std::vector<bdd> rings{goal & within};
    bdd covered = rings.back();
    while (!p_.contains(covered, current_)) {
      bdd next = p_.predecessors(rings.back(), allowed, nullptr, within & !covered);
      if (next == bddfalse) throw std::logic_error("symbolic lasso: the goal is out of reach");
      rings.push_back(next);
      covered |= next;
    }
    std::size_t k = rings.size() - 1;
    while (!p_.contains(rings[k], current_)) --k;
    for (; k > 0; --k) take(rings[k - 1], allowed);
  }

  // One step to a state of `into`.
  void take(const bdd& into, const std::vector<char>& allowed) {
    for (Move& m : p_.moves(current_, allowed)) {
      if (!p_.contains(into, m.after)) continue;
      current_ = m.after;
      moves_.push_back(std::move(m));
      return;
    }
    throw std::logic_error("symbolic lasso: no step into the next ring");
  }

  // Time passing is no step of the trace (the run has ended, or the automaton alone moved).
  Trace trace(std::size_t loopStart) const {
    Trace t;
    t.kind = "lasso";
    for (std::int64_t v : initial_) t.initial.push_back(static_cast<std::int32_t>(v));
    std::vector<std::int64_t> before = initial_;
    for (std::size_t k = 0; k < moves_.size(); ++k) {
      if (k == loopStart) t.loopStart = t.steps.size();
      const Move& m = moves_[k];
      if (m.rule == SymbolicProduct::kTimePasses) continue;
      Step step{m.rule, m.branch, {}};
      for (ir::VarId v = 0; v < before.size(); ++v) {
        if (before[v] != m.after.values[v]) step.changes.push_back({v, static_cast<std::int32_t>(before[v]), static_cast<std::int32_t>(m.after.values[v])});
      }
      t.steps.push_back(std::move(step));
      before = m.after.values;
    }
    if (loopStart >= moves_.size()) t.loopStart = t.steps.size();
    return t;
  }

  SymbolicProduct& p_;
  const std::vector<char> all_;
  Concrete current_;
  std::vector<std::int64_t> initial_;
  std::vector<Move> moves_;
};

// Not under AddressSanitizer: g++ 12's does not hold its allocator's locks across a fork (it has
// no fork interceptor), so a child forked while another thread allocates could wait for ever on a
// lock nobody will release. A sanitized build waits its turn; its tests fork from one thread.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kForkBesideOtherThreads = false;
#else
constexpr bool kForkBesideOtherThreads = true;
#endif

// A model of more than 32 bits of state: its search may take seconds to minutes.
bool large(const ir::Model& model) {
  std::size_t bits = 0;
  for (const ir::Variable& v : model.variables) bits += static_cast<std::size_t>(std::bit_width(static_cast<std::uint64_t>(v.max - v.min)));
  return bits > 32;
}

// The search itself; the caller holds the package (packageLock, or a child process of its own).
SymbolicOutcome searchHoldingPackage(const ir::Model& model, std::size_t property, const SymbolicLimits& limits) {
  SymbolicOutcome out;
  const ir::Property& prop = model.properties.at(property);
  Buchi ba;
  try {
    ba = buildBuchi(ir::Ltl::unary(ir::Ltl::Kind::Not, prop.formula));
  } catch (const std::length_error& e) {
    out.why = e.what();
    return out;
  }
  const Fairness fairness = Fairness::of(model);
  const Sensing sensing = Sensing::in(model);
  const auto start = CpuClock::now();
  const auto deadline = start + std::chrono::duration_cast<CpuClock::duration>(std::chrono::duration<double>(limits.seconds));
  packageError = 0;
  // BuDDy's node: about 20 bytes, and its operation caches a quarter as many entries again.
  const std::uint64_t nodes = std::clamp<std::uint64_t>(limits.maxMemoryBytes / 32, 10'000, 1u << 28);
  // A small table for a small model (the tests search hundreds), a larger one for a large model;
  // it grows by up to four million nodes at a time.
  const std::uint64_t first = large(model) ? 1u << 20 : 1u << 16;
  bdd_init(static_cast<int>(std::min(nodes, first)), static_cast<int>(first / 4));
  bdd_setmaxincrease(1 << 22);
  bdd_error_hook(recordError);
  bdd_gbc_hook(nullptr);
  bdd_resize_hook(nullptr);
  bdd_setmaxnodenum(static_cast<int>(nodes));
  bdd_setcacheratio(4);
  try {
    SymbolicProduct product(model, ba, fairness, deadline, limits.onProgress);
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] %zu rules compiled, %.1f s\n", model.rules.size(), std::chrono::duration<double>(CpuClock::now() - start).count());
    }
    // The reachable states, the automaton's part over-approximated (reachableAnyAutomaton), or
    // a superset of the model's too (projectedReachable): a proof there is a proof. A violation
    // found there counts only if the initial states reach it (a path from them by the model's
    // steps passes reachable states only); otherwise the exact product states are computed and
    // searched again.
    bdd reach = limits.overApproximate ? projectedReachable(product, model) & product.labels() : product.reachableAnyAutomaton();
    bool exact = false;
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] reachable (any automaton state%s): %.0f states, %d nodes, %.1f s\n",
                   limits.overApproximate ? ", a superset projected" : "", product.count(reach), bdd_nodecount(reach),
                   std::chrono::duration<double>(CpuClock::now() - start).count());
    }
    // A step of a slice (or of the cone) that would leave a declared range is no step: the
    // relation has no such outcome (LivenessOptions::slice says why that is sound).
    std::optional<SettledSearch> search;
    const bool everyWorld = limits.everyWorld && prop.settled && sensing.points <= kEveryWorldPoints;
    // The worlds on two cores when the check has two threads (the helper holds a copy of the
    // package: up to as much memory again). Not under AddressSanitizer, as below.
    const bool helper = kForkBesideOtherThreads && limits.worldsHelper;
    bool violated = false;
    for (;;) {
      search.emplace(product, sensing, model.rules.size(), limits.narrowing);
      violated = limits.quietLoop ? search->violatedQuietly(reach)
                 : everyWorld     ? search->violatedOnEveryWorld(reach, helper)
                                  : search->violated(reach, prop.settled);
      // A hunt with no quiet loop goes on to loops that sense, one settling world at a time, with
      // the time it has left: the dearer search, and the one a violation needs when the loop keeps
      // reading a sensor (two robots that settle on different readings).
      if (!violated && limits.quietLoop && limits.thenSettled) violated = search->violated(reach, prop.settled);
      if (!violated || exact || product.initialReaches(reach, search->fairStates())) break;
      if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) std::fprintf(stderr, "[symbolic] the fair states found are not reachable: the exact set\n");
      reach = product.reachable();
      exact = true;
    }
    out.reachable = product.count(reach);
    out.worlds = search->worlds();
    out.openPoints = search->openPoints();
    out.overApproximated = limits.overApproximate && !exact && !violated;
    if (std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
      std::fprintf(stderr, "[symbolic] fair states searched in %u worlds: %s, %.1f s\n", out.worlds, violated ? "some" : "none",
                   std::chrono::duration<double>(CpuClock::now() - start).count());
    }
    out.kind = violated ? SymbolicOutcome::Kind::Violation : SymbolicOutcome::Kind::NoViolation;
    if (violated && limits.lasso) {
      out.lasso = SymbolicLasso(product).build(reach, search->fairStates(), search->loopRules());
      out.lasso->property = prop.name;
    }
  } catch (const GiveUp& e) {
    out.kind = SymbolicOutcome::Kind::GaveUp;
    out.why = e.what();
  } catch (const std::logic_error& e) {  // a lasso that could not be built: no verdict
    out = SymbolicOutcome{};
    out.why = std::string("internal error: ") + e.what();
  }
  bdd_done();
  packageError = 0;
  out.seconds = std::chrono::duration<double>(CpuClock::now() - start).count();
  if (std::getenv("SEMO_DEBUG_SLICING") != nullptr || std::getenv("SEMO_DEBUG_SYMBOLIC") != nullptr) {
    std::fprintf(stderr, "[slice]   symbolic: %s, %.0f reachable product states, %u worlds, %.1f s %s\n",
                 out.kind == SymbolicOutcome::Kind::NoViolation ? "no fair violation"
                 : out.kind == SymbolicOutcome::Kind::Violation ? "a fair violation" : "gave up",
                 out.reachable, out.worlds, out.seconds, out.why.c_str());
  }
  return out;
}

}  // namespace

// BuDDy's package is one per process. When another thread is inside it, a large model's search
// runs in a child process (symbolic_apart.hpp) instead of waiting its turn, so that the properties
// searched on several threads are searched side by side; otherwise here, as a child costs page
// faults (its writes copy the parent's pages: one property of scouting took 87 s forked against
// 67 s here; checker/README.md). A small model (the tests search hundreds, each in milliseconds)
// waits its turn.
//
SymbolicOutcome decideSymbolically(const ir::Model& model, std::size_t property, const SymbolicLimits& limits) {
  if (kForkBesideOtherThreads && large(model)) {
    std::unique_lock<std::mutex> ours(packageLock, std::try_to_lock);
    if (ours.owns_lock()) return searchHoldingPackage(model, property, limits);
    std::optional<SymbolicOutcome> apart = searchInChildProcess(limits, [&](const SymbolicLimits& mine) {
      // The fork copied the package as another thread was using it: started again from nothing
      // (the copy's tables are left to the child's end).
      bddrunning = 0;
      return searchHoldingPackage(model, property, mine);
    });
    if (apart) return std::move(*apart);
  }
  const std::lock_guard<std::mutex> hold(packageLock);
  return searchHoldingPackage(model, property, limits);
}

}  // namespace semo::checker::detail
