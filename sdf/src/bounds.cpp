// Chosen buffer bounds and their Z3 proofs (bounds.hpp).
#include "semo/sdf/bounds.hpp"

#include <numeric>

#include <z3++.h>

#include "semo/sdf/throughput.hpp"

namespace semo::sdf {

namespace {

bool bounded(const Channel& c, const std::vector<std::int64_t>& capacities, std::size_t i) {
  return !c.selfLoop() && i < capacities.size() && capacities[i] >= 0;
}

z3::solver solverWith(z3::context& ctx, unsigned timeoutMs) {
  z3::solver s(ctx);
  z3::params p(ctx);
  p.set("timeout", timeoutMs);
  s.set(p);
  return s;
}

ProofStatus statusOf(z3::check_result r) {
  return r == z3::unsat ? ProofStatus::Proven : r == z3::sat ? ProofStatus::Refuted : ProofStatus::Unknown;
}

}  // namespace

const char* proofStatusName(ProofStatus s) {
  switch (s) {
    case ProofStatus::Proven: return "proven";
    case ProofStatus::Refuted: return "refuted";
    case ProofStatus::Unknown: return "unknown";
  }
  return "unknown";
}

Graph withCapacities(const Graph& g, const std::vector<std::int64_t>& capacities) {
  Graph out = g;
  for (std::size_t i = 0; i < g.channels.size(); ++i) {
    const Channel& c = g.channels[i];
    if (!bounded(c, capacities, i)) continue;
    out.channels.push_back({c.name + ".space", c.target, c.source, c.consumption, c.production, capacities[i] - c.initialTokens, c.at});
  }
  return out;
}

// One Z3 context per thread for all the queries: a context is megabytes of tables, and making one
// per query (hundreds for a mission: a schedule and a minimality query per channel and scenario)
// was half of the scouting mission's analysis (6.5 s -> 3.6 s; more under the sanitizers, whose
// allocator maps every such block afresh). The queries' answers do not depend on it.
namespace {
z3::context& queryContext() {
  static thread_local z3::context ctx;
  return ctx;
}
}  // namespace

ProofStatus proveScheduleSafe(const Graph& g, const std::vector<std::int64_t>& capacities, const std::vector<FiringRun>& schedule,
                              unsigned timeoutMs, std::string* note) {
  z3::context& ctx = queryContext();
  z3::solver s = solverWith(ctx, timeoutMs);
  // n: how many whole iterations ran before the one looked at; any n >= 0.
  z3::expr n = ctx.int_const("n");
  s.add(n >= 0);
  z3::expr_vector violations(ctx);
  for (std::size_t i = 0; i < g.channels.size(); ++i) {
    const Channel& c = g.channels[i];
    if (c.selfLoop()) continue;
    std::int64_t net = 0;
    for (const FiringRun& run : schedule) {
      if (run.actor == c.source) net += run.times * c.production;
      if (run.actor == c.target) net -= run.times * c.consumption;
    }
    const z3::expr atStart = ctx.int_val(static_cast<int64_t>(c.initialTokens)) + n * ctx.int_val(static_cast<int64_t>(net));
    std::int64_t prefix = 0;
    for (const FiringRun& run : schedule) {
      const z3::expr before = atStart + ctx.int_val(static_cast<int64_t>(prefix));
      // Within a run the count moves one way: its last firing is the worst case.
      if (run.actor == c.target) {
        violations.push_back(before < ctx.int_val(static_cast<int64_t>(run.times * c.consumption)));
        prefix -= run.times * c.consumption;
      }
      if (run.actor == c.source) {
        if (bounded(c, capacities, i)) {
          violations.push_back(before + ctx.int_val(static_cast<int64_t>(run.times * c.production)) >
                               ctx.int_val(static_cast<int64_t>(capacities[i])));
        }
        prefix += run.times * c.production;
      }
    }
  }
  if (violations.empty()) return ProofStatus::Proven;
  s.add(z3::mk_or(violations));
  const z3::check_result r = s.check();
  if (r == z3::sat && note != nullptr) *note = "after " + s.get_model().eval(n).to_string() + " iterations a channel leaves its bounds";
  return statusOf(r);
}

ProofStatus proveIterationImpossible(const Graph& g, const std::vector<std::int64_t>& q, const std::vector<std::int64_t>& capacities,
                                     unsigned timeoutMs) {
  const Graph full = withCapacities(g, capacities);
  for (const Channel& c : full.channels) {
    if (c.initialTokens < 0) return ProofStatus::Proven;  // a capacity below the initial tokens: nothing can run
  }
  const std::size_t actors = g.actors.size();
  const std::int64_t steps = std::accumulate(q.begin(), q.end(), std::int64_t{0});
  std::vector<std::vector<const Channel*>> inputs(actors);
  for (const Channel& c : full.channels) inputs[c.target].push_back(&c);
  z3::context& ctx = queryContext();
  z3::solver s = solverWith(ctx, timeoutMs);
  // One Boolean per step and actor, exactly one true per step. count[a] after k steps is a sum of
  // them; a channel's tokens are its initial tokens plus what its source produced minus what its
  // target consumed, so no per-channel state is needed.
  std::vector<z3::expr> count;
  for (std::size_t a = 0; a < actors; ++a) count.push_back(ctx.int_val(0));
  for (std::int64_t k = 0; k < steps; ++k) {
    z3::expr_vector fires(ctx);
    for (std::size_t a = 0; a < actors; ++a) fires.push_back(ctx.bool_const(("fire_" + std::to_string(k) + "_" + std::to_string(a)).c_str()));
    s.add(z3::mk_or(fires));
    s.add(z3::atmost(fires, 1));
    for (std::size_t a = 0; a < actors; ++a) {
      for (const Channel* c : inputs[a]) {
        const z3::expr tokens = ctx.int_val(static_cast<int64_t>(c->initialTokens)) +
                                count[c->source] * ctx.int_val(static_cast<int64_t>(c->production)) -
                                count[c->target] * ctx.int_val(static_cast<int64_t>(c->consumption));
        s.add(z3::implies(fires[static_cast<unsigned>(a)], tokens >= ctx.int_val(static_cast<int64_t>(c->consumption))));
      }
    }
    for (std::size_t a = 0; a < actors; ++a) {
      z3::expr next = ctx.int_const(("count_" + std::to_string(a) + "_" + std::to_string(k + 1)).c_str());
      s.add(next == count[a] + z3::ite(fires[static_cast<unsigned>(a)], ctx.int_val(1), ctx.int_val(0)));
      s.add(next <= ctx.int_val(static_cast<int64_t>(q[a])));  // redundant, prunes early
      count[a] = next;
    }
  }
  for (std::size_t a = 0; a < actors; ++a) s.add(count[a] == ctx.int_val(static_cast<int64_t>(q[a])));
  return statusOf(s.check());
}

namespace {

bool slowerThan(const Period& a, const Period& b) {
  __extension__ typedef __int128 Wide;
  return static_cast<Wide>(a.num) * b.den > static_cast<Wide>(b.num) * a.den;
}

ChosenBounds prove(const Graph& g, const std::vector<std::int64_t>& q, const BufferPoint& point, bool throughputMatters,
                   const BoundsOptions& options) {
  ChosenBounds out;
  out.capacities = point.capacities;
  out.total = point.total;
  out.period = point.period;
  const Iteration it = runIteration(withCapacities(g, point.capacities), q);
  out.schedule = it.schedule;
  if (!it.deadlockFree) {
    out.safety = ProofStatus::Refuted;
    out.safetyNote = "no iteration runs within these capacities";
    return out;
  }
  out.safety = proveScheduleSafe(g, point.capacities, it.schedule, options.timeoutMs, &out.safetyNote);
  if (!options.proveMinimality) {
    out.minimalityNote = "not asked for (only the safety of the schedule)";
    return out;
  }
  const std::int64_t firings = std::accumulate(q.begin(), q.end(), std::int64_t{0});
  bool allMinimal = true, anyUnknown = false;
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (g.channels[c].selfLoop()) continue;
    ChannelMinimality cm;
    cm.channel = c;
    std::vector<std::int64_t> less = point.capacities;
    --less[c];
    if (static_cast<std::uint64_t>(firings) > options.maxFiringsForProof) {
      cm.note = "an iteration has " + std::to_string(firings) + " firings, more than the " + std::to_string(options.maxFiringsForProof) +
                " encoded";
    } else {
      const ProofStatus impossible = proveIterationImpossible(g, q, less, options.timeoutMs);
      if (impossible == ProofStatus::Proven) {
        cm.outcome = ChannelMinimality::Outcome::Deadlocks;
      } else if (impossible == ProofStatus::Refuted) {
        cm.outcome = ChannelMinimality::Outcome::NotMinimal;
        if (throughputMatters) {
          ThroughputOptions to;
          to.capacities.resize(g.channels.size());
          for (std::size_t i = 0; i < g.channels.size(); ++i) {
            if (!g.channels[i].selfLoop()) to.capacities[i] = less[i];
          }
          const ThroughputResult r = throughput(g, q, to);
          if (!r.error.empty()) {
            cm.outcome = ChannelMinimality::Outcome::Unknown;
            cm.note = r.error;
          } else if (r.deadlock || slowerThan(r.period, point.period)) {
            cm.outcome = ChannelMinimality::Outcome::SlowerPeriod;
            cm.periodWithOneLess = r.period;
          }
        }
      } else {
        cm.note = "Z3 gave no answer within " + std::to_string(options.timeoutMs) + " ms";
      }
    }
    allMinimal = allMinimal && (cm.outcome == ChannelMinimality::Outcome::Deadlocks || cm.outcome == ChannelMinimality::Outcome::SlowerPeriod);
    anyUnknown = anyUnknown || cm.outcome == ChannelMinimality::Outcome::Unknown;
    out.channels.push_back(std::move(cm));
  }
  out.minimality = allMinimal ? ProofStatus::Proven : anyUnknown ? ProofStatus::Unknown : ProofStatus::Refuted;
  return out;
}

}  // namespace

ScenarioBounds chooseAndProveBounds(const Graph& g, const std::vector<std::int64_t>& q, const BoundsOptions& options) {
  ScenarioBounds out;
  out.front = bufferParetoFront(g, q, options.maxDistributions);
  const BufferPoint* first = nullptr;
  for (const BufferPoint& p : out.front.points) {
    if (!p.deadlock) {
      first = &p;
      break;
    }
  }
  if (first == nullptr || !out.front.error.empty()) {
    out.error = out.front.error.empty() ? "no buffer distribution gives a throughput" : out.front.error;
    return out;
  }
  out.haveBounds = true;
  out.deadlockFree = prove(g, q, *first, false, options);
  out.maxThroughput = prove(g, q, out.front.points.back(), true, options);
  return out;
}

}  // namespace semo::sdf
