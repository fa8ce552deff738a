#include "semo/checker/markov.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <fmt/format.h>

#include "semo/checker/compiled_model.hpp"
#include "semo/checker/stepper.hpp"

namespace semo::checker {
namespace {

using State = std::vector<std::int32_t>;

struct StateHash {
  std::size_t operator()(const State& s) const noexcept {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int32_t v : s) h = (h ^ static_cast<std::uint32_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

// A change below this between two sweeps ends value iteration (expected rewards on an MDP). Not a
// bound on the error: the iterates approach from below, so the answer is a lower bound, and the
// method text says so. Probabilities use interval iteration instead, which has a bound.
constexpr double kConvergence = 1e-12;
constexpr std::size_t kMaxSweeps = 10'000'000;
constexpr std::size_t kMaxHorizon = 10'000'000;
constexpr double kMaxHorizonWork = 5e9;

template <typename F>
void forEachOutcome(const MarkovModel& m, std::uint32_t a, F&& f) {
  for (std::uint32_t k = m.outcomeStart[a]; k < m.outcomeStart[a + 1]; ++k) f(m.successor[k], m.probability[k]);
}

// The states from which `target` can be reached at all (some action, some outcome, step by step).
std::vector<char> canReach(const MarkovModel& m, const std::vector<char>& target, const std::vector<char>& through) {
  std::vector<std::vector<std::uint32_t>> predecessors(m.size());
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
      forEachOutcome(m, a, [&](std::uint32_t t, double) { predecessors[t].push_back(s); });
    }
  }
  std::vector<char> reached(target);
  std::deque<std::uint32_t> frontier;
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (reached[s] != 0) frontier.push_back(s);
  }
  while (!frontier.empty()) {
    const std::uint32_t t = frontier.front();
    frontier.pop_front();
    for (std::uint32_t s : predecessors[t]) {
      if (reached[s] == 0 && through[s] != 0) reached[s] = 1, frontier.push_back(s);
    }
  }
  return reached;
}

// The states where some scheduler keeps away from `target` for ever (probability 0 of reaching it):
// the largest set of non-target states each of which has an action staying inside it (a state with
// no action stays where it is).
std::vector<char> someSchedulerAvoids(const MarkovModel& m, const std::vector<char>& target) {
  std::vector<char> avoid(m.size());
  for (std::size_t s = 0; s < m.size(); ++s) avoid[s] = target[s] == 0 ? 1 : 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (avoid[s] == 0 || m.actionStart[s] == m.actionStart[s + 1]) continue;
      bool stays = false;
      for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1] && !stays; ++a) {
        bool inside = true;
        forEachOutcome(m, a, [&](std::uint32_t t, double) { inside = inside && avoid[t] != 0; });
        stays = inside;
      }
      if (!stays) avoid[s] = 0, changed = true;
    }
  }
  return avoid;
}

// The states from which the target is reached with probability 1: under every scheduler (Min), or
// under some scheduler (Max, the largest set U such that from each state some action keeps to U
// and the target can be reached inside U).
std::vector<char> almostSurely(const MarkovModel& m, const std::vector<char>& target, Optimum optimum) {
  std::vector<char> all(m.size(), 1);
  if (optimum == Optimum::Min) {
    // Every scheduler reaches it surely exactly where no scheduler can get, outside the target, to
    // a state where some scheduler avoids it.
    std::vector<char> outside(m.size());
    for (std::size_t s = 0; s < m.size(); ++s) outside[s] = target[s] == 0 ? 1 : 0;
    const std::vector<char> bad = canReach(m, someSchedulerAvoids(m, target), outside);
    std::vector<char> sure(m.size());
    for (std::size_t s = 0; s < m.size(); ++s) sure[s] = bad[s] == 0 ? 1 : 0;
    return sure;
  }
  std::vector<char> u = all;
  while (true) {
    // R: the states of U that reach the target through actions staying in U.
    std::vector<char> r(target);
    for (bool changed = true; changed;) {
      changed = false;
      for (std::uint32_t s = 0; s < m.size(); ++s) {
        if (r[s] != 0 || u[s] == 0) continue;
        for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
          bool inside = true, towards = false;
          forEachOutcome(m, a, [&](std::uint32_t t, double) {
            inside = inside && u[t] != 0;
            towards = towards || r[t] != 0;
          });
          if (inside && towards) {
            r[s] = 1, changed = true;
            break;
          }
        }
      }
    }
    if (r == u) return u;
    u = r;
  }
}

QuantitativeResult infinite(const char* why) {
  QuantitativeResult out;
  out.value = out.lower = out.upper = std::numeric_limits<double>::infinity();
  out.infinite = true;
  out.method = why;
  return out;
}

// x = A x + b over the states `unknown` marks, A the one action's probabilities among them: a
// sparse LU factorisation of I - A, BiCGSTAB where the factorisation fails.
std::vector<double> solveChain(const MarkovModel& m, const std::vector<char>& unknown, const std::vector<double>& constant,
                               std::string& method) {
  std::vector<std::int64_t> column(m.size(), -1);
  std::int64_t n = 0;
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (unknown[s] != 0) column[s] = n++;
  }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd b(n);
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (column[s] < 0) continue;
    entries.emplace_back(column[s], column[s], 1.0);
    b(column[s]) = constant[s];
    if (m.actionStart[s] == m.actionStart[s + 1]) continue;
    forEachOutcome(m, m.actionStart[s], [&](std::uint32_t t, double p) {
      if (column[t] >= 0) entries.emplace_back(column[s], column[t], -p);
    });
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());  // duplicates add up
  a.makeCompressed();
  Eigen::VectorXd x;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(a);
  if (lu.info() == Eigen::Success) {
    x = lu.solve(b);
    method = fmt::format("exact: a Markov chain, linear equations over {} state{} solved by sparse LU", n, n == 1 ? "" : "s");
  } else {
    Eigen::BiCGSTAB<Eigen::SparseMatrix<double>> iterative;
    iterative.setTolerance(1e-14);
    iterative.compute(a);
    x = iterative.solve(b);
    method = fmt::format("a Markov chain, linear equations over {} states solved by BiCGSTAB (estimated error {:.1e}; LU failed)", n,
                         iterative.error());
  }
  std::vector<double> out(m.size(), 0.0);
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (column[s] >= 0) out[s] = x(column[s]);
  }
  return out;
}

// Value iteration from 0: x(s) = constant(s) + opt over the allowed actions of sum p * x(t), over
// the states `unknown` marks (the others keep `fixed`).
std::vector<double> iterate(const MarkovModel& m, const std::vector<char>& unknown, const std::vector<double>& fixed,
                            const std::vector<double>& rewardOfAction, const std::vector<char>& actionAllowed, Optimum optimum,
                            std::string& method) {
  std::vector<double> x = fixed;
  std::size_t sweeps = 0;
  for (double change = 1; change >= kConvergence && sweeps < kMaxSweeps; ++sweeps) {
    change = 0;
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (unknown[s] == 0) continue;
      double best = optimum == Optimum::Min ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
      bool any = false;
      for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
        if (actionAllowed[a] == 0) continue;
        double v = rewardOfAction[a];
        forEachOutcome(m, a, [&](std::uint32_t t, double p) { v += p * x[t]; });
        best = optimum == Optimum::Min ? std::min(best, v) : std::max(best, v);
        any = true;
      }
      if (!any) best = x[s];
      change = std::max(change, std::fabs(best - x[s]) / std::max(1.0, std::fabs(best)));
      x[s] = best;  // Gauss-Seidel: later states read the new value
    }
  }
  method = fmt::format("value iteration over {} states, {} sweeps, stopped when no value changed by more than {:.0e} (relative); "
                       "a lower bound, its error not bounded",
                       m.size(), sweeps, kConvergence);
  return x;
}

// Interval iteration: a lower bound from 0 and an upper bound from 1 over the `unknown` states (the
// others keep `fixed`), swept together until the initial state's bounds are within 2 * precision.
// Both converge to the one solution once the states with probability 0 are fixed and, for Max, each
// maximal end component among the unknown states is read as one state whose actions are those that
// leave it (inside it a scheduler may go anywhere, so its states share the best way out); for Min
// there are none (a scheduler could stay in one for ever: those states are in the 0 set).
QuantitativeResult intervalIteration(const MarkovModel& m, const std::vector<char>& unknown, const std::vector<double>& fixed,
                                     Optimum optimum, double precision) {
  std::vector<std::int64_t> component(m.size(), -1);
  if (optimum == Optimum::Max) component = maximalEndComponents(m, unknown);
  std::int64_t components = 0;
  for (std::int64_t c : component) components = std::max(components, c + 1);
  auto internal = [&](std::uint32_t s, std::uint32_t a) {
    if (component[s] < 0) return false;
    bool inside = true;
    forEachOutcome(m, a, [&](std::uint32_t t, double) { inside = inside && component[t] == component[s]; });
    return inside;
  };
  std::vector<char> leaves(m.actions(), 1);
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (unknown[s] == 0) continue;
    for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) leaves[a] = internal(s, a) ? 0 : 1;
  }
  std::vector<double> lower = fixed, upper = fixed;
  for (std::size_t s = 0; s < m.size(); ++s) {
    if (unknown[s] != 0) upper[s] = 1.0;
  }
  std::vector<double> bestLower(static_cast<std::size_t>(components)), bestUpper(static_cast<std::size_t>(components));
  const double perSweep = static_cast<double>(std::max<std::size_t>(1, m.successor.size()));
  std::size_t sweeps = 0;
  bool converged = false;
  while (!converged && static_cast<double>(sweeps) * perSweep < kMaxHorizonWork) {
    ++sweeps;
    std::fill(bestLower.begin(), bestLower.end(), 0.0);
    std::fill(bestUpper.begin(), bestUpper.end(), 0.0);
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (unknown[s] == 0) continue;
      double lo = optimum == Optimum::Min ? 1.0 : 0.0, hi = lo;
      bool any = false;
      for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
        if (leaves[a] == 0) continue;
        double l = 0, h = 0;
        forEachOutcome(m, a, [&](std::uint32_t t, double p) { l += p * lower[t], h += p * upper[t]; });
        lo = optimum == Optimum::Min ? std::min(lo, l) : std::max(lo, l);
        hi = optimum == Optimum::Min ? std::min(hi, h) : std::max(hi, h);
        any = true;
      }
      if (!any && component[s] < 0) lo = lower[s], hi = upper[s];
      if (component[s] >= 0) {
        const auto c = static_cast<std::size_t>(component[s]);
        bestLower[c] = std::max(bestLower[c], any ? lo : 0.0);
        bestUpper[c] = std::max(bestUpper[c], any ? hi : 0.0);
        continue;
      }
      lower[s] = lo, upper[s] = hi;  // Gauss-Seidel: later states read the new values
    }
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (unknown[s] == 0 || component[s] < 0) continue;
      lower[s] = bestLower[static_cast<std::size_t>(component[s])];
      upper[s] = bestUpper[static_cast<std::size_t>(component[s])];
    }
    converged = upper[0] - lower[0] <= 2 * precision;
  }
  QuantitativeResult out;
  out.lower = std::clamp(lower[0], 0.0, 1.0);
  out.upper = std::clamp(upper[0], out.lower, 1.0);
  out.value = (out.lower + out.upper) / 2;
  out.method = fmt::format("interval iteration over {} states{}, {} sweep{}: the value lies in [{:.12g}, {:.12g}]{}", m.size(),
                           components > 0 ? fmt::format(" ({} end component{} collapsed)", components, components == 1 ? "" : "s") : "",
                           sweeps, sweeps == 1 ? "" : "s", out.lower, out.upper,
                           converged ? fmt::format(" (within {:.0e} of the midpoint)", precision)
                                     : fmt::format(" (the precision {:.0e} not reached within {:.0e} transition visits)", precision,
                                                   kMaxHorizonWork));
  return out;
}

// Strongly connected components of the graph whose nodes `node` marks and whose edges are the
// outcomes of the actions `allowed` marks (iteratively: models have millions of states).
std::vector<std::int64_t> stronglyConnected(const MarkovModel& m, const std::vector<char>& node, const std::vector<char>& allowed) {
  const std::size_t n = m.size();
  std::vector<std::int64_t> index(n, -1), low(n, 0), scc(n, -1);
  std::vector<char> onStack(n, 0);
  std::vector<std::uint32_t> stack;
  struct Frame {
    std::uint32_t state, action, outcome;
  };
  std::vector<Frame> calls;
  std::int64_t counter = 0, sccs = 0;
  for (std::uint32_t root = 0; root < n; ++root) {
    if (node[root] == 0 || index[root] >= 0) continue;
    auto open = [&](std::uint32_t s) {
      index[s] = low[s] = counter++;
      stack.push_back(s), onStack[s] = 1;
      calls.push_back({s, m.actionStart[s], m.actionStart[s] < m.actionStart[s + 1] ? m.outcomeStart[m.actionStart[s]] : 0});
    };
    open(root);
    while (!calls.empty()) {
      Frame& f = calls.back();
      const std::uint32_t s = f.state;
      bool descended = false;
      // `descended` first: once open() has grown `calls`, f dangles and must not be read.
      while (!descended && f.action < m.actionStart[s + 1]) {
        if (allowed[f.action] == 0 || f.outcome >= m.outcomeStart[f.action + 1]) {
          ++f.action;
          if (f.action < m.actionStart[s + 1]) f.outcome = m.outcomeStart[f.action];
          continue;
        }
        const std::uint32_t t = m.successor[f.outcome++];
        if (node[t] == 0) continue;
        if (index[t] < 0) {
          open(t);  // invalidates f
          descended = true;
        } else if (onStack[t] != 0) {
          low[s] = std::min(low[s], index[t]);
        }
      }
      if (descended) continue;
      if (low[s] == index[s]) {
        std::uint32_t t = 0;
        do {
          t = stack.back();
          stack.pop_back(), onStack[t] = 0;
          scc[t] = sccs;
        } while (t != s);
        ++sccs;
      }
      calls.pop_back();
      if (!calls.empty()) low[calls.back().state] = std::min(low[calls.back().state], low[s]);
    }
  }
  return scc;
}

}  // namespace

bool MarkovModel::deterministic() const {
  for (std::size_t s = 0; s + 1 < actionStart.size(); ++s) {
    if (actionStart[s + 1] - actionStart[s] > 1) return false;
  }
  return true;
}

MarkovModel buildMarkovModel(const ir::Model& model, const MarkovLimits& limits) {
  const Stepper stepper(model);
  MarkovModel m;
  std::unordered_map<State, std::uint32_t, StateHash> index;
  auto add = [&](State s) -> std::uint32_t {
    auto [it, fresh] = index.emplace(s, static_cast<std::uint32_t>(m.states.size()));
    if (fresh) {
      if (m.states.size() >= limits.maxStates) {
        throw MarkovError(fmt::format("more than {} reachable states (the limit of the quantitative engine)", limits.maxStates), true, true);
      }
      m.states.push_back(std::move(s));
    }
    return it->second;
  };
  add(stepper.initial());
  m.outcomeStart.push_back(0);
  std::vector<std::pair<std::uint32_t, double>> merged;
  for (std::uint32_t s = 0; s < m.states.size(); ++s) {
    m.actionStart.push_back(static_cast<std::uint32_t>(m.actionRule.size()));
    const State from = m.states[s];  // add() may move the vector's storage
    for (std::size_t r : stepper.enabledRules(from)) {
      merged.clear();
      for (std::size_t b = 0; b < model.rules[r].branches.size(); ++b) {
        Stepper::Outcome o = stepper.apply(from, {r, b});
        if (!o.outOfRange.empty()) {
          throw MarkovError(fmt::format("rule '{}' sets '{}' outside its declared range", model.rules[r].name,
                                        model.variables[o.outOfRange.front()].name));
        }
        const std::uint32_t t = add(std::move(o.state));
        auto same = std::find_if(merged.begin(), merged.end(), [t](const auto& e) { return e.first == t; });
        if (same != merged.end()) same->second += model.rules[r].branches[b].probability;
        else merged.emplace_back(t, model.rules[r].branches[b].probability);
      }
      m.actionRule.push_back(static_cast<std::uint32_t>(r));
      for (const auto& [t, p] : merged) m.successor.push_back(t), m.probability.push_back(p);
      m.outcomeStart.push_back(static_cast<std::uint32_t>(m.successor.size()));
    }
  }
  m.actionStart.push_back(static_cast<std::uint32_t>(m.actionRule.size()));
  return m;
}

std::vector<std::int64_t> maximalEndComponents(const MarkovModel& m, const std::vector<char>& within) {
  // Refine: keep the actions that stay inside their state's strongly connected component, drop the
  // states left with no action, until nothing changes; the components left are the MECs.
  std::vector<char> node = within, allowed(m.actions(), 0);
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (node[s] == 0) continue;
    for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
      bool inside = true;
      forEachOutcome(m, a, [&](std::uint32_t t, double) { inside = inside && node[t] != 0; });
      allowed[a] = inside ? 1 : 0;
    }
  }
  std::vector<std::int64_t> scc;
  for (bool changed = true; changed;) {
    changed = false;
    scc = stronglyConnected(m, node, allowed);
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (node[s] == 0) continue;
      bool any = false;
      for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
        if (allowed[a] == 0) continue;
        bool inside = true;
        forEachOutcome(m, a, [&](std::uint32_t t, double) { inside = inside && node[t] != 0 && scc[t] == scc[s]; });
        if (!inside) allowed[a] = 0, changed = true;
        any = any || inside;
      }
      if (!any) node[s] = 0, changed = true;
    }
  }
  // Number the components densely, in the order of their first state.
  std::vector<std::int64_t> out(m.size(), -1);
  std::unordered_map<std::int64_t, std::int64_t> dense;
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (node[s] == 0) continue;
    out[s] = dense.emplace(scc[s], static_cast<std::int64_t>(dense.size())).first->second;
  }
  return out;
}

std::vector<char> statesWhere(const MarkovModel& m, const ir::Expr& condition) {
  const Program program(condition);
  std::vector<char> out(m.size());
  for (std::size_t s = 0; s < m.size(); ++s) out[s] = program.eval(m.states[s].data()) != 0 ? 1 : 0;
  return out;
}

std::vector<double> boundedReachability(const MarkovModel& m, const std::vector<char>& target, std::size_t horizon, Optimum optimum) {
  // A sweep per step over every transition: a horizon the user asks for must not hang or exhaust
  // memory (one value per step is kept).
  const double work = static_cast<double>(horizon) * static_cast<double>(std::max<std::size_t>(1, m.successor.size()));
  if (horizon > kMaxHorizon || work > kMaxHorizonWork) {
    throw MarkovError(fmt::format("a horizon of {} steps over {} transitions is beyond the engine's limits ({} steps, {:.0e} "
                                  "transition visits)",
                                  horizon, m.successor.size(), kMaxHorizon, kMaxHorizonWork),
                      true);
  }
  std::vector<double> x(m.size()), next(m.size());
  for (std::size_t s = 0; s < m.size(); ++s) x[s] = target[s] != 0 ? 1.0 : 0.0;
  std::vector<double> out{x.empty() ? 0.0 : x[0]};
  for (std::size_t t = 1; t <= horizon; ++t) {
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (target[s] != 0 || m.actionStart[s] == m.actionStart[s + 1]) {
        next[s] = x[s];
        continue;
      }
      double best = optimum == Optimum::Min ? 1.0 : 0.0;
      for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
        double v = 0;
        forEachOutcome(m, a, [&](std::uint32_t u, double p) { v += p * x[u]; });
        best = optimum == Optimum::Min ? std::min(best, v) : std::max(best, v);
      }
      next[s] = best;
    }
    std::swap(x, next);
    out.push_back(x[0]);
  }
  return out;
}

QuantitativeResult reachability(const MarkovModel& m, const std::vector<char>& target, Optimum optimum, double precision) {
  // Probability 0 decided on the graph first: the equations then have one solution.
  std::vector<char> everywhere(m.size(), 1);
  std::vector<char> zero(m.size());
  if (optimum == Optimum::Max) {
    const std::vector<char> reach = canReach(m, target, everywhere);
    for (std::size_t s = 0; s < m.size(); ++s) zero[s] = reach[s] == 0 ? 1 : 0;
  } else {
    zero = someSchedulerAvoids(m, target);
  }
  const std::vector<char> one = almostSurely(m, target, optimum);
  std::vector<char> unknown(m.size());
  std::vector<double> fixed(m.size(), 0.0), constant(m.size(), 0.0);
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (one[s] != 0) fixed[s] = 1.0;
    unknown[s] = zero[s] == 0 && one[s] == 0 ? 1 : 0;
  }
  QuantitativeResult out;
  if (unknown[0] == 0) {
    out.value = out.lower = out.upper = fixed[0];
    out.method = "exact: decided on the graph (probability 0 or 1)";
    return out;
  }
  if (m.deterministic()) {
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (unknown[s] == 0 || m.actionStart[s] == m.actionStart[s + 1]) continue;
      forEachOutcome(m, m.actionStart[s], [&](std::uint32_t t, double p) { constant[s] += p * fixed[t]; });
    }
    out.value = out.lower = out.upper = std::clamp(solveChain(m, unknown, constant, out.method)[0], 0.0, 1.0);
    return out;
  }
  return intervalIteration(m, unknown, fixed, optimum, precision);
}

QuantitativeResult expectedReward(const MarkovModel& m, const std::vector<char>& target, const std::vector<double>& rewardOfRule,
                                  Optimum optimum) {
  // Finite exactly where the target is reached with probability 1: under some scheduler for the
  // minimum (the others would pay for ever), under every scheduler for the maximum.
  const std::vector<char> finite = almostSurely(m, target, optimum == Optimum::Min ? Optimum::Max : Optimum::Min);
  if (finite[0] == 0) return infinite("infinite: the target is missed with positive probability");
  std::vector<char> unknown(m.size());
  for (std::size_t s = 0; s < m.size(); ++s) unknown[s] = finite[s] != 0 && target[s] == 0 ? 1 : 0;
  std::vector<double> rewardOfAction(m.actions());
  for (std::size_t a = 0; a < m.actions(); ++a) {
    const std::uint32_t r = m.actionRule[a];
    rewardOfAction[a] = r < rewardOfRule.size() ? rewardOfRule[r] : 0.0;
  }
  QuantitativeResult out;
  if (m.deterministic()) {
    std::vector<double> constant(m.size(), 0.0);
    for (std::uint32_t s = 0; s < m.size(); ++s) {
      if (unknown[s] != 0 && m.actionStart[s] != m.actionStart[s + 1]) constant[s] = rewardOfAction[m.actionStart[s]];
    }
    out.value = out.lower = out.upper = solveChain(m, unknown, constant, out.method)[0];
    return out;
  }
  // The minimum uses only actions that keep to the finite states. Value iteration from 0 finds the
  // least solution, which is the answer when every step there earns something; a scheduler that
  // circles for ever for nothing would otherwise be counted as cheap.
  std::vector<char> allowed(m.actions(), 1);
  for (std::uint32_t s = 0; s < m.size(); ++s) {
    if (unknown[s] == 0) continue;
    for (std::uint32_t a = m.actionStart[s]; a < m.actionStart[s + 1]; ++a) {
      bool inside = true;
      forEachOutcome(m, a, [&](std::uint32_t t, double) { inside = inside && finite[t] != 0; });
      allowed[a] = inside ? 1 : 0;
      if (optimum == Optimum::Min && inside && !(rewardOfAction[a] > 0)) {
        throw MarkovError(fmt::format("the minimum expected reward of a nondeterministic model with steps that earn nothing "
                                      "(rule number {}) is not computed yet",
                                      m.actionRule[a]));
      }
    }
  }
  std::vector<double> fixed(m.size(), 0.0);
  out.value = out.lower = iterate(m, unknown, fixed, rewardOfAction, allowed, optimum, out.method)[0];
  out.upper = std::numeric_limits<double>::infinity();  // iterates from 0 only ever approach from below
  return out;
}

}  // namespace semo::checker
