#include "semo/checker/round_models.hpp"

#include <cmath>
#include <string>

namespace semo::checker {
namespace {

using ir::Expr;
using ir::Op;

ir::Rule rule(std::string name, Expr guard, std::vector<ir::Branch> branches) {
  ir::Rule r;
  r.name = std::move(name);
  r.guard = std::move(guard);
  r.branches = std::move(branches);
  return r;
}

Expr is(ir::VarId v, std::int32_t value) { return Expr::binary(Op::Eq, Expr::var(v), Expr::constant(value)); }

}  // namespace

ir::Model knowledgeSpreadModel(const SpreadParameters& p) {
  ir::Model m;
  const std::size_t n = p.robots;
  const auto messages = static_cast<std::int32_t>(n * (n - 1));
  for (std::size_t i = 0; i < n; ++i) m.variables.push_back({"knows[" + std::to_string(i) + "]", 0, 1, i == p.firstKnower ? 1 : 0, true, ir::kNoRobot, {}, {}});
  const auto phase = static_cast<ir::VarId>(n);
  m.variables.push_back({"phase", 0, messages, 0, false, ir::kNoRobot, {}, {}});
  m.rules.push_back(rule("round", is(phase, 0), {{1.0, {{phase, Expr::constant(messages > 0 ? 1 : 0)}}}}));
  const double lost = std::pow(p.lossPerCopy, static_cast<double>(p.retransmissions + 1));
  std::int32_t index = 0;
  for (std::size_t s = 0; s < n; ++s) {
    for (std::size_t r = 0; r < n; ++r) {
      if (r == s) continue;
      ++index;
      const Expr next = Expr::constant(index == messages ? 0 : index + 1);
      const auto sv = static_cast<ir::VarId>(s), rv = static_cast<ir::VarId>(r);
      const Expr news = Expr::binary(Op::And, is(sv, 1), is(rv, 0));
      const std::string name = std::to_string(s) + ".to." + std::to_string(r);
      std::vector<ir::Branch> sent;
      if (lost < 1) sent.push_back({1.0 - lost, {{rv, Expr::constant(1)}, {phase, next}}});
      if (lost > 0) sent.push_back({lost, {{phase, next}}});
      m.rules.push_back(rule("sends." + name, Expr::binary(Op::And, is(phase, index), news), std::move(sent)));
      m.rules.push_back(rule("nothing.new." + name, Expr::binary(Op::And, is(phase, index), Expr::unary(Op::Not, news)), {{1.0, {{phase, next}}}}));
    }
  }
  return m;
}

SpreadAnswer analyzeSpread(const SpreadParameters& p, std::size_t horizonRounds, const MarkovLimits& limits) {
  const ir::Model model = knowledgeSpreadModel(p);
  const MarkovModel chain = buildMarkovModel(model, limits);
  std::vector<char> everyone(chain.size(), 1);
  for (std::size_t s = 0; s < chain.size(); ++s) {
    for (std::size_t i = 0; i < p.robots; ++i) everyone[s] = everyone[s] != 0 && chain.states[s][i] == 1 ? 1 : 0;
  }
  // A round is 1 + n(n - 1) steps: every robot knows by the end of round t exactly when it does
  // within t such steps.
  const std::size_t perRound = 1 + p.robots * (p.robots - 1);
  const std::vector<double> bySteps = boundedReachability(chain, everyone, horizonRounds * perRound);
  SpreadAnswer out;
  out.states = chain.size();
  for (std::size_t t = 0; t <= horizonRounds; ++t) out.withinRounds.push_back(bySteps[t * perRound]);
  std::vector<double> reward(model.rules.size(), 0.0);
  reward[0] = 1.0;  // `round`
  out.expectedRounds = expectedReward(chain, everyone, reward);
  return out;
}

SampledAnswer sampleSpread(const SpreadParameters& p, SamplingOptions options) {
  const ir::Model model = knowledgeSpreadModel(p);
  std::vector<ir::Expr> everyone;
  for (std::size_t i = 0; i < p.robots; ++i) everyone.push_back(is(static_cast<ir::VarId>(i), 1));
  std::vector<char> round(model.rules.size(), 0);
  round[0] = 1;  // `round`
  return sampleRuns(model, ir::conjunction(std::move(everyone)), round, options);
}

ir::Model lossRunModel(std::size_t length, double loss) {
  ir::Model m;
  const auto top = static_cast<std::int32_t>(length);
  m.variables.push_back({"run", 0, top, 0, false, ir::kNoRobot, {}, {}});
  std::vector<ir::Branch> period;
  if (loss > 0) period.push_back({loss, {{0, Expr::binary(Op::Add, Expr::var(0), Expr::constant(1))}}});
  if (loss < 1) period.push_back({1 - loss, {{0, Expr::constant(0)}}});
  m.rules.push_back(rule("period", Expr::binary(Op::Lt, Expr::var(0), Expr::constant(top)), std::move(period)));
  return m;
}

LossRunAnswer analyzeLossRun(std::size_t length, double loss, std::size_t horizonPeriods) {
  const ir::Model model = lossRunModel(length, loss);
  const MarkovModel chain = buildMarkovModel(model);
  std::vector<char> burst(chain.size());
  for (std::size_t s = 0; s < chain.size(); ++s) burst[s] = chain.states[s][0] == static_cast<std::int32_t>(length) ? 1 : 0;
  LossRunAnswer out;
  out.withinPeriods = boundedReachability(chain, burst, horizonPeriods);
  out.expectedPeriods = expectedReward(chain, burst, {1.0});
  return out;
}

}  // namespace semo::checker
