#include "semo/checker/statistical.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <unordered_map>

#include <fmt/format.h>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/markov.hpp"
#include "semo/checker/stepper.hpp"

namespace semo::checker {
namespace {

// Rules whose guards all test one variable for a constant (a round model's phase, a program
// counter) are looked up by that variable's value instead of each being evaluated: a step then
// costs the few rules of its phase, not all of them.
struct RuleIndex {
  std::int64_t variable = -1;
  std::unordered_map<std::int32_t, std::vector<std::size_t>> byValue;
  std::vector<std::size_t> all;

  const std::vector<std::size_t>& candidates(const std::vector<std::int32_t>& s) const {
    if (variable < 0) return all;
    static const std::vector<std::size_t> none;
    auto it = byValue.find(s[static_cast<std::size_t>(variable)]);
    return it == byValue.end() ? none : it->second;
  }
};

// `v == c` (or `c == v`) among a guard's top-level conjuncts.
void equalityTests(const ir::Expr& e, std::vector<std::pair<ir::VarId, std::int32_t>>& out) {
  if (e.op == ir::Op::And) {
    for (const ir::Expr& a : e.args) equalityTests(a, out);
    return;
  }
  if (e.op != ir::Op::Eq || e.args.size() != 2) return;
  const ir::Expr &l = e.args[0], &r = e.args[1];
  if (l.op == ir::Op::Var && r.op == ir::Op::Const) out.emplace_back(static_cast<ir::VarId>(l.value), r.value);
  if (r.op == ir::Op::Var && l.op == ir::Op::Const) out.emplace_back(static_cast<ir::VarId>(r.value), l.value);
}

RuleIndex indexRules(const ir::Model& model) {
  RuleIndex index;
  for (std::size_t r = 0; r < model.rules.size(); ++r) index.all.push_back(r);
  std::vector<std::vector<std::pair<ir::VarId, std::int32_t>>> tests(model.rules.size());
  for (std::size_t r = 0; r < model.rules.size(); ++r) equalityTests(model.rules[r].guard, tests[r]);
  if (model.rules.empty()) return index;
  for (const auto& [v, c] : tests[0]) {  // a variable every rule tests
    bool everyRule = true;
    for (std::size_t r = 1; r < model.rules.size() && everyRule; ++r) {
      everyRule = std::any_of(tests[r].begin(), tests[r].end(), [v = v](const auto& t) { return t.first == v; });
    }
    if (!everyRule) continue;
    index.variable = v;
    for (std::size_t r = 0; r < model.rules.size(); ++r) {
      for (const auto& t : tests[r]) {
        if (t.first == v) {
          index.byValue[t.second].push_back(r);
          break;
        }
      }
    }
    break;
  }
  return index;
}

// A uniform double in [0, 1) from 53 random bits: the same on every platform, unlike
// std::uniform_real_distribution, so a seed gives the same estimate everywhere.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

SampledAnswer sampleRuns(const ir::Model& model, const ir::Expr& target, const std::vector<char>& unitRule,
                         const SamplingOptions& options) {
  const Stepper stepper(model);
  const Program isTarget(target);
  const RuleIndex index = indexRules(model);
  std::mt19937_64 rng(options.seed);
  SampledAnswer out;
  out.runs = options.runs;
  std::vector<std::size_t> reachedAt(options.horizon + 1, 0);  // runs first at the target after t units
  double sum = 0, sumSquares = 0;
  std::size_t finished = 0;
  std::vector<std::size_t> enabled;
  auto lastReport = std::chrono::steady_clock::now();
  for (std::size_t run = 0; run < options.runs; ++run) {
    if (options.progress && std::chrono::steady_clock::now() - lastReport > std::chrono::seconds(1)) {
      options.progress(run);
      lastReport = std::chrono::steady_clock::now();
    }
    Stepper::State s = stepper.initial();
    std::size_t units = 0, steps = 0;
    bool reached = isTarget.eval(s.data()) != 0;
    for (; !reached && steps < options.maxSteps && units <= options.maxUnits; ++steps) {
      enabled.clear();
      for (std::size_t r : index.candidates(s)) {
        if (stepper.enabled(s, r)) enabled.push_back(r);
      }
      if (enabled.empty()) break;  // the run has ended short of the target
      if (enabled.size() > 1) out.scheduled = true;
      const std::size_t r = enabled.size() == 1 ? enabled[0] : enabled[static_cast<std::size_t>(rng() % enabled.size())];
      const std::vector<ir::Branch>& branches = model.rules[r].branches;
      std::size_t b = 0;
      if (branches.size() > 1) {
        double u = uniform(rng);
        while (b + 1 < branches.size() && u >= branches[b].probability) u -= branches[b++].probability;
      }
      Stepper::Outcome o = stepper.apply(s, {r, b});
      if (!o.outOfRange.empty()) {
        throw MarkovError(fmt::format("rule '{}' sets '{}' outside its declared range", model.rules[r].name,
                                      model.variables[o.outOfRange.front()].name));
      }
      s = std::move(o.state);
      if (r < unitRule.size() && unitRule[r] != 0) ++units;
      reached = isTarget.eval(s.data()) != 0;
    }
    if (!reached) {
      ++out.unfinished;
      continue;
    }
    ++finished;
    sum += static_cast<double>(units), sumSquares += static_cast<double>(units) * static_cast<double>(units);
    const std::size_t at = options.withinSteps ? steps : units;
    if (at <= options.horizon) ++reachedAt[at];
  }
  const double n = static_cast<double>(std::max<std::size_t>(1, options.runs));
  std::size_t cumulative = 0;
  for (std::size_t t = 0; t <= options.horizon; ++t) {
    cumulative += reachedAt[t];
    out.within.push_back(static_cast<double>(cumulative) / n);
  }
  out.band = std::sqrt(std::log(2 / 0.05) / (2 * n));
  if (finished > 0) {
    const double f = static_cast<double>(finished);
    out.meanUnits = sum / f;
    const double variance = finished > 1 ? std::max(0.0, (sumSquares - f * out.meanUnits * out.meanUnits) / (f - 1)) : 0.0;
    out.meanHalfWidth = 1.96 * std::sqrt(variance / f);
  }
  out.method = fmt::format("statistical estimate, not exact: {} simulated runs (seed {}){}; P(within t) within +-{:.4f} of the "
                           "truth for every t at once with 95 % confidence (Dvoretzky-Kiefer-Wolfowitz)",
                           options.runs, options.seed, out.scheduled ? ", a uniformly drawn rule where several were enabled" : "", out.band);
  if (out.unfinished == 0) {
    out.method += fmt::format("; the mean within +-{:.4g} (95 %, normal approximation)", out.meanHalfWidth);
  } else {
    out.method += fmt::format("; {} run{} did not reach the target (ended, or stopped after {} units): no mean", out.unfinished,
                              out.unfinished == 1 ? "" : "s", options.maxUnits);
  }
  return out;
}

}  // namespace semo::checker
