#include "lasso_walks.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <random>
#include <unordered_map>
#include <unordered_set>

#include "semo/checker/fairness.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/stepper.hpp"
#include "thread_cpu_clock.hpp"

namespace semo::checker::detail {

namespace {

using CpuClock = ThreadCpuClock;  // the budget is processor time (thread_cpu_clock.hpp)
using State = Stepper::State;

std::uint64_t hashOf(const State& s) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (std::int32_t v : s) {
    h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  }
  return h;
}

double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// A path as states and the choices between them.
struct Path {
  std::vector<State> states;  // states.size() == choices.size() + 1
  std::vector<Stepper::Choice> choices;
};

Trace traceOf(const Path& p, std::size_t loopStart, const ir::Property& property) {
  Trace t;
  t.kind = "lasso";
  t.property = property.name;
  t.initial = p.states.front();
  for (std::size_t k = 0; k < p.choices.size(); ++k) {
    Step step{p.choices[k].rule, p.choices[k].branch, {}};
    for (std::size_t v = 0; v < p.states[k].size(); ++v) {
      if (p.states[k][v] != p.states[k + 1][v]) step.changes.push_back({static_cast<ir::VarId>(v), p.states[k][v], p.states[k + 1][v]});
    }
    t.steps.push_back(std::move(step));
  }
  t.loopStart = loopStart;
  return t;
}

Path pathOf(const Stepper& stepper, const Trace& t) {
  Path p;
  p.states.push_back(stepper.initial());
  for (const Step& s : t.steps) {
    Stepper::Choice c{s.rule, s.branch};
    p.choices.push_back(c);
    p.states.push_back(stepper.apply(p.states.back(), c).state);
  }
  return p;
}

// p's states [from, to] without the segments between two visits of one state (first to last).
void appendWithoutLoops(const Path& p, std::size_t from, std::size_t to, Path& out) {
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> last;
  for (std::size_t k = from; k <= to; ++k) last[hashOf(p.states[k])].push_back(k);
  std::size_t k = from;
  if (out.states.empty()) out.states.push_back(p.states[k]);
  while (k < to) {
    for (std::size_t j : last[hashOf(p.states[k])]) {
      if (j > k && p.states[j] == p.states[k]) k = std::max(k, j);
    }
    if (k >= to) break;
    out.choices.push_back(p.choices[k]);
    out.states.push_back(p.states[k + 1]);
    ++k;
  }
}

// The path of `choices` from the initial state, if every one is enabled there and stays in range.
std::optional<Path> replay(const Stepper& stepper, const std::vector<Stepper::Choice>& choices) {
  Path p;
  p.states.push_back(stepper.initial());
  for (const Stepper::Choice& c : choices) {
    Stepper::Outcome o = stepper.apply(p.states.back(), c);
    if (!o.enabled || !o.outOfRange.empty()) return std::nullopt;
    p.choices.push_back(c);
    p.states.push_back(std::move(o.state));
  }
  return p;
}

// Steps of the stem left out where the rest still replays, the loop still closes and checkLasso
// still accepts the lasso: a random walk's stem does much that the violation does not need. Blocks
// of steps first (halving their size, as delta debugging does: a throw and the receipt of the event
// it threw go together), then single steps until none can go. Returns the new loop start.
std::size_t dropNeedlessStemSteps(const Stepper& stepper, const ir::Model& model, const ir::Property& property, Path& path,
                                  std::size_t loopStart) {
  auto tryWithout = [&](std::size_t from, std::size_t count) {
    std::vector<Stepper::Choice> choices = path.choices;
    choices.erase(choices.begin() + static_cast<std::ptrdiff_t>(from), choices.begin() + static_cast<std::ptrdiff_t>(from + count));
    std::optional<Path> p = replay(stepper, choices);
    const std::size_t start = loopStart - count;
    if (!p || p->states.back() != p->states[start]) return false;
    if (!checkLasso(model, traceOf(*p, start, property), property).counterexample()) return false;
    path = std::move(*p);
    loopStart = start;
    return true;
  };
  // From the stem's end back to its start, a block at a time (a block left out shortens the stem
  // behind the next one, never before it).
  for (std::size_t size = loopStart / 2; size > 1; size /= 2) {
    for (std::size_t end = loopStart; end >= size; end -= size) tryWithout(end - size, size);
  }
  for (bool dropped = true; dropped;) {
    dropped = false;
    for (std::size_t k = loopStart; k-- > 0;) dropped = tryWithout(k, 1) || dropped;
  }
  return loopStart;
}

class Walker {
 public:
  Walker(const ir::Model& model, std::size_t property, const LassoWalkLimits& limits)
      : model_(model), property_(model.properties.at(property)), limits_(limits), stepper_(model), sensing_(Sensing::in(model)),
        fairness_(Fairness::of(model)) {
    for (const ir::Rule& r : model.rules) {
      const bool fair = r.weaklyFair || r.stronglyFair || !r.fairGroup.empty();
      kind_.push_back(r.kind == ir::RuleKind::Loss ? kLoss
                      : (r.kind == ir::RuleKind::Crash || r.kind == ir::RuleKind::Environment) && !fair ? kEnvironment
                                                                                                         : kOrdinary);
    }
  }

  LassoWalkOutcome run() {
    LassoWalkOutcome out;
    const auto started = CpuClock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(CpuClock::now() - started).count(); };
    std::uint32_t stale = 0;
    // Once a lasso is found, as many walks again look for a shorter one (the shortest is kept).
    std::uint32_t lastWalk = limits_.walks;
    for (std::uint32_t w = 0; w < lastWalk; ++w) {
      if (elapsed() > limits_.seconds) {
        if (!out.lasso) out.why = "no fair violation in " + std::to_string(w) + " random walks (out of time)";
        break;
      }
      std::mt19937_64 rng(limits_.seed * 0x9e3779b97f4a7c15ull + w);
      const std::size_t known = seenAll_.size();
      std::optional<Trace> t = walk(rng, out);
      out.walks = w + 1;
      if (t) {
        Trace shorter = shortenLasso(model_, *t, property_);
        if (!out.lasso || shorter.steps.size() < out.lasso->steps.size()) out.lasso = std::move(shorter), out.lassoWalk = w + 1;
        out.why.clear();
        lastWalk = std::min(lastWalk, 2 * out.lassoWalk);
        continue;
      }
      if (out.lasso) continue;
      // Walks that meet no state unseen by earlier walks have covered what walks reach: a small
      // model is done with in a few walks, not in the whole budget.
      stale = seenAll_.size() == known ? stale + 1 : 0;
      if (stale == kStaleWalks) {
        out.why = "no fair violation in " + std::to_string(w + 1) + " random walks (the last " + std::to_string(kStaleWalks) +
                  " met no state the earlier ones had not, of " + std::to_string(seenAll_.size()) + ")";
        break;
      }
      if (out.why.empty() || w + 1 == limits_.walks) out.why = "no fair violation in " + std::to_string(w + 1) + " random walks";
    }
    out.seconds = elapsed();
    return out;
  }

 private:
  enum Kind : std::uint8_t { kOrdinary, kLoss, kEnvironment };
  static constexpr std::uint32_t kStaleWalks = 50;

  std::optional<Trace> walk(std::mt19937_64& rng, LassoWalkOutcome& out) {
    // The world: each sensed condition one way. The biases: how often a loss beats its delivery,
    // and whether unfair environment steps (a crash) happen at all.
    // On a settling world a walk decides freely until it settles (at once, or after an eighth of
    // its steps); a property that asks for no settling world leaves every decision free.
    std::vector<std::int8_t> world(sensing_.points), free(sensing_.points, -1);
    for (std::int8_t& d : world) d = static_cast<std::int8_t>(rng() & 1);
    const std::uint32_t settlesAt = !property_.settled ? UINT32_MAX : (rng() & 1) != 0 ? 0 : limits_.stepsPerWalk / 8;
    const double lossWeight = std::array{0.05, 0.5, 2.0, 20.0}[rng() % 4];
    const double environmentWeight = (rng() & 1) != 0 ? 0.0 : 0.002;
    Path path;
    path.states.push_back(stepper_.initial());
    enabledFrom_.clear();
    enabledGroups_.clear();
    markedAt_.assign(fairness_.groups(), 0);
    std::unordered_map<std::uint64_t, std::size_t> firstVisit{{hashOf(path.states[0]), 0}};
    std::vector<std::pair<Stepper::Choice, double>> options;
    std::uint64_t returns = 0;
    for (std::uint32_t step = 1; step <= limits_.stepsPerWalk; ++step) {
      const State& here = path.states.back();
      options.clear();
      double total = 0;
      bool fairEnabled = false;
      enabledFrom_.push_back(static_cast<std::uint32_t>(enabledGroups_.size()));
      for (std::size_t r : stepper_.enabledRules(here)) {
        const ir::Rule& rule = model_.rules[r];
        fairEnabled = fairEnabled || rule.weaklyFair || rule.stronglyFair;
        if (const std::uint32_t g = fairness_.groupOf[r]; g != Fairness::kNone && markedAt_[g] != step) {
          markedAt_[g] = step;  // a group once per state
          enabledGroups_.push_back(g);
        }
        if (!sensing_.agrees(static_cast<std::uint32_t>(r), step > settlesAt ? world : free)) continue;
        const double weight = kind_[r] == kLoss ? lossWeight : kind_[r] == kEnvironment ? environmentWeight : 1.0;
        if (weight <= 0) continue;
        for (std::size_t b = 0; b < stepper_.branches(r); ++b) options.push_back({{r, b}, weight}), total += weight;
      }
      if (!fairEnabled) {  // the run may stay here for ever
        Trace t = traceOf(path, path.choices.size(), property_);
        if (checkLasso(model_, t, property_).counterexample()) return t;
        if (options.empty()) return std::nullopt;
      }
      if (options.empty()) return std::nullopt;  // only steps this world rules out
      double pick = uniform(rng) * total;
      std::size_t chosen = 0;
      while (chosen + 1 < options.size() && pick >= options[chosen].second) pick -= options[chosen++].second;
      Stepper::Outcome next = stepper_.apply(here, options[chosen].first);
      if (!next.outOfRange.empty()) return std::nullopt;  // a modelling error: the safety check reports it
      path.choices.push_back(options[chosen].first);
      path.states.push_back(std::move(next.state));
      ++out.steps;
      const std::size_t now = path.choices.size();
      const std::uint64_t hash = hashOf(path.states.back());
      seenAll_.insert(hash);
      auto [it, fresh] = firstVisit.try_emplace(hash, now);
      // Judge the longest loop when the walk is back in a state it has seen: at its 1st, 2nd, 4th,
      // 8th ... return to any state, at every 512th step, and at the end.
      if (fresh) continue;
      ++returns;
      const bool judge = (returns & (returns - 1)) == 0 || step % 512 == 0 || step == limits_.stepsPerWalk;
      if (judge && path.states[it->second] == path.states.back() && fairOnLoop(path, it->second)) {
        Trace t = traceOf(path, it->second, property_);
        if (checkLasso(model_, t, property_).counterexample()) return t;
      }
    }
    return std::nullopt;
  }

  // A quick look at whether the loop from state `from` to the walk's end is fair and settled (as
  // checkLasso judges it, which then has the last word and also reads the property): most loops a
  // walk closes neglect some group, and this spares building their traces.
  bool fairOnLoop(const Path& path, std::size_t from) {
    const std::size_t to = path.choices.size();
    enabledCount_.assign(fairness_.groups(), 0);
    taken_.assign(fairness_.groups(), 0);
    for (std::size_t k = from; k < to; ++k) {
      const std::uint32_t end = k + 1 < enabledFrom_.size() ? enabledFrom_[k + 1] : static_cast<std::uint32_t>(enabledGroups_.size());
      for (std::uint32_t e = enabledFrom_[k]; e < end; ++e) ++enabledCount_[enabledGroups_[e]];
      if (const std::uint32_t g = fairness_.groupOf[path.choices[k].rule]; g != Fairness::kNone) taken_[g] = 1;
    }
    for (std::uint32_t g = 0; g < fairness_.groups(); ++g) {
      if (taken_[g] != 0 || enabledCount_[g] == 0) continue;
      // Enabled somewhere and never taken: unfair if strongly fair, or if enabled all along.
      if (fairness_.strong[g] != 0 || enabledCount_[g] >= to - from) return false;
    }
    if (property_.settled) {
      decided_.assign(sensing_.points, 0);
      for (std::size_t k = from; k < to; ++k) {
        for (const Sensing::Decision& d : sensing_.of[path.choices[k].rule]) {
          decided_[d.point] |= d.holds ? 2 : 1;
          if (decided_[d.point] == 3) return false;
        }
      }
    }
    return true;
  }

  const ir::Model& model_;
  const ir::Property& property_;
  const LassoWalkLimits& limits_;
  Stepper stepper_;
  Sensing sensing_;
  Fairness fairness_;
  std::vector<Kind> kind_;
  // Per state of the current walk (the state before step k): the fair groups enabled there, as
  // enabledGroups_[enabledFrom_[k] .. enabledFrom_[k + 1]).
  std::vector<std::uint32_t> enabledFrom_, enabledGroups_;
  std::vector<std::uint32_t> enabledCount_, markedAt_;
  std::vector<char> taken_, decided_;
  std::unordered_set<std::uint64_t> seenAll_;  // every state (hash) any walk has met
};

}  // namespace

Trace shortenLasso(const ir::Model& model, const Trace& lasso, const ir::Property& property) {
  const Stepper stepper(model);
  const Path p = pathOf(stepper, lasso);
  const std::size_t l = lasso.loopStart, n = p.choices.size();
  // The stem without its loops, then the loop as it is.
  Path shorter;
  appendWithoutLoops(p, 0, l, shorter);
  const std::size_t loopStart = shorter.choices.size();
  for (std::size_t k = l; k < n; ++k) shorter.choices.push_back(p.choices[k]), shorter.states.push_back(p.states[k + 1]);
  // Inner loops of the loop, the longest first from each position, cut where the rest still
  // violates fairly.
  for (std::size_t a = loopStart; a < shorter.choices.size(); ++a) {
    for (std::size_t b = shorter.choices.size() - 1; b > a; --b) {
      if (shorter.states[b] != shorter.states[a]) continue;
      Path cut;
      cut.states.assign(shorter.states.begin(), shorter.states.begin() + static_cast<std::ptrdiff_t>(a) + 1);
      cut.choices.assign(shorter.choices.begin(), shorter.choices.begin() + static_cast<std::ptrdiff_t>(a));
      for (std::size_t k = b; k < shorter.choices.size(); ++k) cut.choices.push_back(shorter.choices[k]), cut.states.push_back(shorter.states[k + 1]);
      if (checkLasso(model, traceOf(cut, loopStart, property), property).counterexample()) {
        shorter = std::move(cut);
        break;
      }
    }
  }
  // (A best-first search for a shorter way to the loop, by the number of variables that differ,
  // was tried: within 200,000 states it never reached scouting's loop.)
  const std::size_t newLoopStart = dropNeedlessStemSteps(stepper, model, property, shorter, loopStart);
  return traceOf(shorter, newLoopStart, property);
}

LassoWalkOutcome findLassoByWalks(const ir::Model& model, std::size_t property, const LassoWalkLimits& limits) {
  return Walker(model, property, limits).run();
}

}  // namespace semo::checker::detail
