// The quantitative engine (checker/markov.hpp) against closed forms and published results: the
// models are written here in the IR text form, as a user would write them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "semo/checker/markov.hpp"
#include "semo/checker/round_models.hpp"
#include "semo/checker/statistical.hpp"
#include "semo/frontend/diagnostics.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo::checker {
namespace {

ir::Model parse(const std::string& text) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const FileId file = sources.add("model.ir", text);
  auto model = ir::parseText(sources, file, diags);
  EXPECT_TRUE(model.has_value()) << text.substr(0, 400);
  return model ? *model : ir::Model{};
}

ir::Expr condition(const std::string& text, const std::string& declarations) {
  // The reader parses expressions inside a model: a throwaway invariant carries it.
  ir::Model m = parse("semo-ir 1;\n" + declarations + "invariant target : " + text + ";\n");
  return m.invariants.at(0).holds;
}

std::string declarations(const ir::Model& m) {
  std::string out;
  for (const ir::Variable& v : m.variables) out += "var " + v.name + " : " + std::to_string(v.min) + ".." + std::to_string(v.max) + ";\n";
  return out;
}

std::vector<char> where(const MarkovModel& chain, const ir::Model& model, const std::string& text) {
  return statesWhere(chain, condition(text, declarations(model)));
}

std::vector<double> rewardOn(const ir::Model& m, const std::string& rule) {
  std::vector<double> out(m.rules.size(), 0.0);
  for (std::size_t r = 0; r < m.rules.size(); ++r) out[r] = m.rules[r].name == rule ? 1.0 : 0.0;
  return out;
}

// Two robots, one fact, each round the knower broadcasts once and the message is lost with
// probability p: P(known by round t) = 1 - p^t, expected rounds 1 / (1 - p).
TEST(Markov, OneFactOneBroadcastPerRoundMatchesTheClosedForm) {
  struct Case {
    std::string delivered, lost;
    double p;
  };
  for (const Case& c : {Case{"0.8", "0.2", 0.2}, Case{"2/3", "1/3", 1.0 / 3.0}, Case{"0.5", "0.5", 0.5}, Case{"1/10", "9/10", 0.9}}) {
    const ir::Model m = parse("semo-ir 1;\nvar b.knows : bool = false;\nrule round : !b.knows -> " + c.delivered + " : b.knows' = true + " +
                              c.lost + " : skip;\n");
    const MarkovModel chain = buildMarkovModel(m);
    EXPECT_EQ(chain.size(), 2u);
    EXPECT_TRUE(chain.deterministic());
    const std::vector<char> known = where(chain, m, "b.knows");
    const std::vector<double> byRound = boundedReachability(chain, known, 30);
    for (std::size_t t = 0; t <= 30; ++t) EXPECT_NEAR(byRound[t], 1.0 - std::pow(c.p, static_cast<double>(t)), 1e-9) << c.p << " t=" << t;
    const QuantitativeResult rounds = expectedReward(chain, known, rewardOn(m, "round"));
    EXPECT_FALSE(rounds.infinite);
    EXPECT_NEAR(rounds.value, 1.0 / (1.0 - c.p), 1e-9) << rounds.method;
    EXPECT_NEAR(reachability(chain, known).value, 1.0, 1e-12);
  }
}

// The synchronous leader election of Itai and Rodeh as PRISM's case study leader_sync models it:
// N processes in a ring pick ids in 0..K-1 in one synchronous step, pass them round the ring
// (a counter c says how far), then all decide (a unique id among them: done) or pick again.
std::string itaiRodeh(int n, int k) {
  auto at = [n](int i) { return std::to_string((i % n) + 1); };
  std::string t = "semo-ir 1;\nvar c : 1.." + std::to_string(n - 1) + " = 1;\n";
  for (int i = 1; i <= n; ++i) {
    const std::string s = std::to_string(i);
    t += "var s" + s + " : 0..3;\nvar u" + s + " : bool;\nvar v" + s + " : 0.." + std::to_string(k - 1) + ";\nvar p" + s + " : 0.." +
         std::to_string(k - 1) + ";\n";
  }
  std::string anyUnique;
  for (int i = 1; i <= n; ++i) anyUnique += (i > 1 ? " || " : "") + std::string("u") + std::to_string(i);
  // pick: every combination of ids, each with probability 1/K^N
  int outcomes = 1;
  for (int i = 0; i < n; ++i) outcomes *= k;
  t += "rule pick : ";
  for (int i = 1; i <= n; ++i) t += (i > 1 ? " && " : "") + std::string("s") + std::to_string(i) + " == 0";
  t += " ->";
  for (int o = 0; o < outcomes; ++o) {
    t += o == 0 ? " " : "\n  + ";
    t += "1/" + std::to_string(outcomes) + " :";
    int rest = o;
    for (int i = 1; i <= n; ++i, rest /= k) {
      const std::string s = std::to_string(i), id = std::to_string(rest % k);
      t += (i > 1 ? ", " : " ") + std::string("s") + s + "' = 1, p" + s + "' = " + id + ", v" + s + "' = " + id + ", u" + s + "' = true";
    }
  }
  t += ";\n";
  // read: process i reads its neighbour's value; the last read moves everyone to deciding
  const std::string last = "c == " + std::to_string(n - 1);
  t += "rule read : ";
  for (int i = 1; i <= n; ++i) t += (i > 1 ? " && " : "") + std::string("s") + std::to_string(i) + " == 1";
  t += " -> c' = (" + last + " ? c : c + 1)";
  for (int i = 1; i <= n; ++i) {
    const std::string s = std::to_string(i), next = at(i);
    t += ", s" + s + "' = (" + last + " ? 2 : 1)";
    t += ", u" + s + "' = (u" + s + " ? p" + s + " != v" + next + " : false)";
    t += ", v" + s + "' = (" + last + " ? 0 : v" + next + ")";
    t += ", p" + s + "' = (" + last + " ? (u" + s + " ? 0 : p" + s + ") : (u" + s + " ? p" + s + " : 0))";
  }
  t += ";\n";
  std::string deciding;
  for (int i = 1; i <= n; ++i) deciding += (i > 1 ? " && " : "") + std::string("s") + std::to_string(i) + " == 2";
  std::string reset;
  for (int i = 1; i <= n; ++i) {
    const std::string s = std::to_string(i);
    reset += ", u" + s + "' = false, v" + s + "' = 0, p" + s + "' = 0";
  }
  std::string doneSet, retrySet;
  for (int i = 1; i <= n; ++i) doneSet += (i > 1 ? ", " : "") + std::string("s") + std::to_string(i) + "' = 3";
  for (int i = 1; i <= n; ++i) retrySet += (i > 1 ? ", " : "") + std::string("s") + std::to_string(i) + "' = 0";
  t += "rule done : " + deciding + " && (" + anyUnique + ") -> " + doneSet + reset + ";\n";
  t += "rule retry : " + deciding + " && !(" + anyUnique + ") -> c' = 1, " + retrySet + reset + ";\n";
  std::string finished;
  for (int i = 1; i <= n; ++i) finished += (i > 1 ? " && " : "") + std::string("s") + std::to_string(i) + " == 3";
  t += "rule loop : " + finished + " -> skip;\n";
  return t;
}

TEST(Markov, SynchronousLeaderElectionReproducesPrismsPublishedNumbers) {
  struct Case {
    int n, k;
    std::size_t states;
    double rounds;
  };
  for (const Case& c : {Case{3, 2, 26, 4.0 / 3.0}, Case{4, 4, 812, 32.0 / 27.0}, Case{5, 4, 4244, 256.0 / 225.0}}) {
    const ir::Model m = parse(itaiRodeh(c.n, c.k));
    const MarkovModel chain = buildMarkovModel(m);
    EXPECT_EQ(chain.size(), c.states) << "N=" << c.n << " K=" << c.k;
    EXPECT_TRUE(chain.deterministic());
    std::string elected;
    for (int i = 1; i <= c.n; ++i) elected += (i > 1 ? " && " : "") + std::string("s") + std::to_string(i) + " == 3";
    const std::vector<char> target = where(chain, m, elected);
    const QuantitativeResult rounds = expectedReward(chain, target, rewardOn(m, "pick"));
    EXPECT_NEAR(rounds.value, c.rounds, 1e-9) << rounds.method;
    EXPECT_NE(rounds.method.find("sparse LU"), std::string::npos);
    EXPECT_NEAR(reachability(chain, target).value, 1.0, 1e-12);
  }
}

// Herman's self-stabilising ring: each process holding a token (its bit equals its left
// neighbour's) flips a fair coin, the others copy their neighbour, all at once. From three tokens
// equally spaced, the expected steps to one token are 4 N^2 / 27.
std::string herman(int n, const std::string& initial) {
  std::string t = "semo-ir 1;\n";
  for (int i = 0; i < n; ++i) t += "var x" + std::to_string(i) + " : bool = " + (initial[static_cast<std::size_t>(i)] == '1' ? "true" : "false") + ";\n";
  const int outcomes = 1 << n;
  t += "rule step : true ->";
  for (int o = 0; o < outcomes; ++o) {
    t += o == 0 ? " " : "\n  + ";
    t += "1/" + std::to_string(outcomes) + " :";
    for (int i = 0; i < n; ++i) {
      const std::string x = "x" + std::to_string(i), left = "x" + std::to_string((i + n - 1) % n);
      t += (i > 0 ? ", " : " ") + x + "' = (" + x + " == " + left + " ? " + ((o >> i) & 1 ? "true" : "false") + " : " + left + ")";
    }
  }
  return t + ";\n";
}

TEST(Markov, HermansRingFromThreeEquallySpacedTokensTakesFourNSquaredOver27Steps) {
  for (const auto& [n, initial] : {std::pair{3, std::string("000")}, std::pair{9, std::string("010010010")}}) {
    const ir::Model m = parse(herman(n, initial));
    const MarkovModel chain = buildMarkovModel(m);
    std::string tokens;
    for (int i = 0; i < n; ++i) tokens += (i > 0 ? " + " : "") + std::string("(x") + std::to_string(i) + " == x" + std::to_string((i + n - 1) % n) + ")";
    EXPECT_TRUE(where(chain, m, tokens + " == 3")[0]) << "three tokens at the start";
    const std::vector<char> stable = where(chain, m, tokens + " == 1");
    const QuantitativeResult steps = expectedReward(chain, stable, rewardOn(m, "step"));
    EXPECT_NEAR(steps.value, 4.0 * n * n / 27.0, 1e-6) << steps.method;
  }
}

// A scheduler's choice: from x = 0, `gamble` reaches x = 1 or the dead end x = 2 with even odds,
// `coin` reaches x = 1 or stays, `quit` goes to the dead end.
TEST(Markov, NondeterministicChoicesGiveTheMinimumAndMaximumOverSchedulers) {
  const ir::Model m = parse(
      "semo-ir 1;\nvar x : 0..2 = 0;\n"
      "rule gamble : x == 0 -> 1/2 : x' = 1 + 1/2 : x' = 2;\n"
      "rule coin : x == 0 -> 0.5 : x' = 1 + 0.5 : skip;\n"
      "rule quit : x == 0 -> x' = 2;\n");
  const MarkovModel chain = buildMarkovModel(m);
  EXPECT_FALSE(chain.deterministic());
  const std::vector<char> one = where(chain, m, "x == 1");
  EXPECT_NEAR(reachability(chain, one, Optimum::Max).value, 1.0, 1e-9);
  EXPECT_NEAR(reachability(chain, one, Optimum::Min).value, 0.0, 1e-12);
  const std::vector<double> withinMax = boundedReachability(chain, one, 3, Optimum::Max);
  EXPECT_NEAR(withinMax[1], 0.5, 1e-12);
  EXPECT_NEAR(withinMax[3], 0.875, 1e-12);  // coin three times
  const std::vector<double> steps(m.rules.size(), 1.0);
  const QuantitativeResult fewest = expectedReward(chain, one, steps, Optimum::Min);
  EXPECT_NEAR(fewest.value, 2.0, 1e-9) << fewest.method;  // only `coin` reaches x = 1 surely
  EXPECT_TRUE(expectedReward(chain, one, steps, Optimum::Max).infinite);
}

// Two states a scheduler can go between for ever (an end component): from x = 0 `try` reaches the
// goal with 0.3, from x = 1 `try` with 0.6, the rest of each try the dead end. The best schedule
// walks to x = 1 first: 0.6. An upper bound iterated from 1 without collapsing the component would
// stay at 1 (each state seems to reach 1 through the other); the worst schedule walks for ever: 0.
TEST(Markov, IntervalIterationCollapsesEndComponentsAndBracketsTheAnswer) {
  const ir::Model m = parse(
      "semo-ir 1;\nvar x : 0..3 = 0;\n"
      "rule walk : x == 0 -> x' = 1;\n"
      "rule back : x == 1 -> x' = 0;\n"
      "rule try0 : x == 0 -> 3/10 : x' = 2 + 7/10 : x' = 3;\n"
      "rule try1 : x == 1 -> 3/5 : x' = 2 + 2/5 : x' = 3;\n");
  const MarkovModel chain = buildMarkovModel(m);
  const std::vector<char> goal = where(chain, m, "x == 2");
  std::vector<char> walking(chain.size(), 0);
  for (std::size_t s = 0; s < chain.size(); ++s) walking[s] = chain.states[s][0] < 2 ? 1 : 0;
  const std::vector<std::int64_t> mec = maximalEndComponents(chain, walking);
  EXPECT_GE(mec[0], 0);
  EXPECT_EQ(mec[0], mec[1]) << "x = 0 and x = 1 form one end component";
  const QuantitativeResult best = reachability(chain, goal, Optimum::Max);
  EXPECT_NEAR(best.value, 0.6, 1e-9) << best.method;
  EXPECT_LE(best.lower, 0.6 + 1e-15);
  EXPECT_GE(best.upper, 0.6 - 1e-15);
  EXPECT_LE(best.upper - best.lower, 2e-9) << best.method;
  EXPECT_NE(best.method.find("interval iteration"), std::string::npos) << best.method;
  EXPECT_NE(best.method.find("1 end component collapsed"), std::string::npos) << best.method;
  EXPECT_NEAR(reachability(chain, goal, Optimum::Min).value, 0.0, 1e-12);
}

// Random small MDPs: interval iteration against every memoryless deterministic scheduler (which
// suffice for reachability), each one's chain solved exactly by sparse LU.
TEST(Markov, IntervalIterationAgreesWithTheBestAndWorstOfAllSchedulers) {
  std::uint64_t seed = 0x9e3779b97f4a7c15ull;
  auto next = [&seed](std::uint32_t bound) {
    seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
    return static_cast<std::uint32_t>(seed % bound);
  };
  int strictlyBetween = 0, schedulesDiffer = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::uint32_t n = 4 + next(5);  // the last state is the target, the one before a dead end
    MarkovModel mdp;
    mdp.states.resize(n);
    mdp.outcomeStart.push_back(0);
    for (std::uint32_t s = 0; s < n; ++s) {
      mdp.actionStart.push_back(static_cast<std::uint32_t>(mdp.actionRule.size()));
      const std::uint32_t actions = s + 2 >= n ? 0 : 1 + next(2);
      for (std::uint32_t a = 0; a < actions; ++a) {
        const std::uint32_t outcomes = 1 + next(2), first = next(n), second = (first + 1 + next(n - 1)) % n;
        const double p = outcomes == 1 ? 1.0 : 0.1 * (1 + next(9));
        mdp.actionRule.push_back(a);
        mdp.successor.push_back(first), mdp.probability.push_back(p);
        if (outcomes == 2) mdp.successor.push_back(second), mdp.probability.push_back(1 - p);
        mdp.outcomeStart.push_back(static_cast<std::uint32_t>(mdp.successor.size()));
      }
    }
    mdp.actionStart.push_back(static_cast<std::uint32_t>(mdp.actionRule.size()));
    std::vector<char> target(n, 0);
    target[n - 1] = 1;
    double lowest = 1, highest = 0;
    std::uint32_t schedulers = 1;
    for (std::uint32_t s = 0; s < n; ++s) schedulers *= std::max<std::uint32_t>(1, mdp.actionStart[s + 1] - mdp.actionStart[s]);
    for (std::uint32_t k = 0; k < schedulers; ++k) {
      MarkovModel fixed;  // the chain this scheduler leaves
      fixed.states.resize(n);
      fixed.outcomeStart.push_back(0);
      std::uint32_t code = k;
      for (std::uint32_t s = 0; s < n; ++s) {
        fixed.actionStart.push_back(static_cast<std::uint32_t>(fixed.actionRule.size()));
        const std::uint32_t choices = mdp.actionStart[s + 1] - mdp.actionStart[s];
        if (choices == 0) continue;
        const std::uint32_t a = mdp.actionStart[s] + code % choices;
        code /= choices;
        fixed.actionRule.push_back(0);
        for (std::uint32_t o = mdp.outcomeStart[a]; o < mdp.outcomeStart[a + 1]; ++o) {
          fixed.successor.push_back(mdp.successor[o]), fixed.probability.push_back(mdp.probability[o]);
        }
        fixed.outcomeStart.push_back(static_cast<std::uint32_t>(fixed.successor.size()));
      }
      fixed.actionStart.push_back(static_cast<std::uint32_t>(fixed.actionRule.size()));
      const double v = reachability(fixed, target, Optimum::Max).value;
      lowest = std::min(lowest, v), highest = std::max(highest, v);
    }
    const QuantitativeResult mx = reachability(mdp, target, Optimum::Max), mn = reachability(mdp, target, Optimum::Min);
    EXPECT_NEAR(mx.value, highest, 1e-8) << "trial " << trial << ": " << mx.method;
    EXPECT_NEAR(mn.value, lowest, 1e-8) << "trial " << trial << ": " << mn.method;
    EXPECT_LE(mx.lower, highest + 1e-12);
    EXPECT_GE(mx.upper, highest - 1e-12);
    EXPECT_LE(mn.lower, lowest + 1e-12);
    EXPECT_GE(mn.upper, lowest - 1e-12);
    strictlyBetween += highest > 1e-6 && highest < 1 - 1e-6 ? 1 : 0;
    schedulesDiffer += highest - lowest > 1e-6 ? 1 : 0;
  }
  EXPECT_GE(strictlyBetween, 30) << "the random models must not all be decided on the graph";
  EXPECT_GE(schedulesDiffer, 50);
}

// Simulated runs of a round model against the exact answer: every P(within t) inside the
// Dvoretzky-Kiefer-Wolfowitz band, the mean inside its interval (both at 95 %: the seeds are fixed,
// so this test does not flicker), the same seed giving the same estimate.
TEST(Markov, SampledRunsOfARoundModelFallWithinTheirBandsOfTheExactAnswer) {
  const SpreadParameters p{.robots = 5, .firstKnower = 1, .lossPerCopy = 0.5, .retransmissions = 0};
  const SpreadAnswer exact = analyzeSpread(p, 6);
  const SampledAnswer sampled = sampleSpread(p, {.runs = 4000, .seed = 7, .horizon = 6});
  EXPECT_FALSE(sampled.scheduled) << "a round model enables one rule at a time";
  EXPECT_EQ(sampled.unfinished, 0u);
  EXPECT_NEAR(sampled.band, std::sqrt(std::log(40.0) / 8000.0), 1e-12);
  ASSERT_EQ(sampled.within.size(), exact.withinRounds.size());
  double widest = 0;
  for (std::size_t t = 0; t < exact.withinRounds.size(); ++t) {
    EXPECT_LE(std::fabs(sampled.within[t] - exact.withinRounds[t]), sampled.band) << "t = " << t;
    widest = std::max(widest, std::fabs(sampled.within[t] - exact.withinRounds[t]));
  }
  EXPECT_GT(widest, 0.0) << "an estimate, not the exact answer copied";
  EXPECT_LE(std::fabs(sampled.meanUnits - exact.expectedRounds.value), sampled.meanHalfWidth) << sampled.method;
  EXPECT_NE(sampled.method.find("not exact"), std::string::npos);
  const SampledAnswer again = sampleSpread(p, {.runs = 4000, .seed = 7, .horizon = 6});
  EXPECT_EQ(again.within, sampled.within);
  EXPECT_EQ(again.meanUnits, sampled.meanUnits);
  EXPECT_NE(sampleSpread(p, {.runs = 4000, .seed = 8, .horizon = 6}).within, sampled.within);
}

// Where several rules are enabled a run draws one uniformly, and says so: gamble, coin and quit
// drawn with a third each reach the goal with 2/5 (1/6 + 1/6 + P/6 = P); the rest end at the dead
// end (runs that end short of the target, so no mean).
TEST(Markov, SampledRunsOfAnMdpDrawTheSchedulerAndSayItWasDrawn) {
  const ir::Model m = parse(
      "semo-ir 1;\nvar x : 0..2 = 0;\n"
      "rule gamble : x == 0 -> 1/2 : x' = 1 + 1/2 : x' = 2;\n"
      "rule coin : x == 0 -> 0.5 : x' = 1 + 0.5 : skip;\n"
      "rule quit : x == 0 -> x' = 2;\n");
  const SampledAnswer a = sampleRuns(m, condition("x == 1", "var x : 0..2;\n"), std::vector<char>(3, 1), {.runs = 20000, .seed = 3, .horizon = 60});
  EXPECT_TRUE(a.scheduled);
  EXPECT_NEAR(a.within.back(), 0.4, a.band);
  EXPECT_GT(a.unfinished, 0u);
  EXPECT_NE(a.method.find("uniformly drawn"), std::string::npos) << a.method;
  EXPECT_NE(a.method.find("no mean"), std::string::npos) << a.method;
}

// Knowledge spread in the runtime's gossip rounds. When the last robot in the team's order finds
// the fact, its first round is everyone's broadcast at once: three robots, loss 1/5 per message,
// P(all know within 1 round) = 0.8^2, within 2 rounds 0.9728, expected rounds 25/18.
TEST(Markov, GossipRoundsMatchTheClosedFormsOfOneFactInThreeRobots) {
  SpreadAnswer a = analyzeSpread({.robots = 3, .firstKnower = 2, .lossPerCopy = 0.2, .retransmissions = 0}, 4);
  EXPECT_NEAR(a.withinRounds[0], 0.0, 1e-12);
  EXPECT_NEAR(a.withinRounds[1], 0.64, 1e-9);
  EXPECT_NEAR(a.withinRounds[2], 0.9728, 1e-9);
  EXPECT_NEAR(a.expectedRounds.value, 25.0 / 18.0, 1e-9) << a.expectedRounds.method;
  // Three copies more per message: a message is lost only if all four are (0.2^4).
  const double lost = std::pow(0.2, 4), heard = 1 - lost;
  const double both = heard * heard, none = lost * lost, one = 2 * heard * lost;
  const double lastOne = 1 / (1 - lost * lost);  // the third robot hears one of two senders
  a = analyzeSpread({.robots = 3, .firstKnower = 2, .lossPerCopy = 0.2, .retransmissions = 3}, 2);
  EXPECT_NEAR(a.withinRounds[1], both, 1e-9);
  EXPECT_NEAR(a.expectedRounds.value, (1 + one * lastOne) / (1 - none), 1e-9);
  EXPECT_NEAR(a.expectedRounds.value, 1.003197, 1e-6);
  // The first robot in order: whichever of the other two learns from it passes it on to the third
  // later in the same round (robot 1 to robot 2, or robot 2 to robot 1).
  a = analyzeSpread({.robots = 3, .firstKnower = 0, .lossPerCopy = 0.2, .retransmissions = 0}, 1);
  EXPECT_NEAR(a.withinRounds[1], 0.8 * 0.8 + 2 * (0.8 * 0.2) * 0.8, 1e-9);
  // No loss: one round; certain loss: never.
  EXPECT_NEAR(analyzeSpread({.robots = 5, .firstKnower = 1, .lossPerCopy = 0, .retransmissions = 0}, 1).withinRounds[1], 1.0, 1e-12);
  EXPECT_TRUE(analyzeSpread({.robots = 3, .firstKnower = 1, .lossPerCopy = 1, .retransmissions = 2}, 1).expectedRounds.infinite);
}

// k heartbeats lost in a row, each with probability p: expected periods (1 - p^k) / ((1 - p) p^k),
// 780 for k = 4 and p = 0.2 (scouting's light watch: a takeover after 4 silent periods of 500 ms),
// and a 14 % chance of such a run within 60 s (120 periods).
TEST(Markov, LossesInARowTakeTheClosedFormTimeAndHaveTheirChanceWithinAMinute) {
  const LossRunAnswer a = analyzeLossRun(4, 0.2, 120);
  EXPECT_NEAR(a.expectedPeriods.value, (1 - std::pow(0.2, 4)) / (0.8 * std::pow(0.2, 4)), 1e-6) << a.expectedPeriods.method;
  EXPECT_NEAR(a.expectedPeriods.value, 780.0, 1e-6);
  EXPECT_NEAR(a.withinPeriods[4], std::pow(0.2, 4), 1e-12);
  EXPECT_NEAR(a.withinPeriods[5], std::pow(0.2, 4) + 0.8 * std::pow(0.2, 4), 1e-12);  // or lost after one heard
  EXPECT_NEAR(a.withinPeriods[120], 0.1401, 5e-5);
  EXPECT_TRUE(analyzeLossRun(2, 0.0, 10).expectedPeriods.infinite);
  EXPECT_NEAR(analyzeLossRun(2, 1.0, 10).withinPeriods[2], 1.0, 1e-12);
}

TEST(Markov, AStepOutsideARangeOrTooManyStatesIsAnErrorNotAnAnswer) {
  EXPECT_THROW(buildMarkovModel(parse("semo-ir 1;\nvar x : 0..2 = 0;\nrule up : true -> x' = x + 1;\n")), MarkovError);
  MarkovLimits small;
  small.maxStates = 10;
  EXPECT_THROW(buildMarkovModel(parse("semo-ir 1;\nvar x : 0..100 = 0;\nrule up : x < 100 -> x' = x + 1;\n"), small), MarkovError);
  // A horizon too long to sweep is refused at once, not computed for hours.
  const MarkovModel chain = buildMarkovModel(parse("semo-ir 1;\nvar x : 0..1 = 0;\nrule up : x == 0 -> x' = 1;\n"));
  try {
    (void)boundedReachability(chain, std::vector<char>{0, 1}, 20'000'000);
    ADD_FAILURE() << "no error";
  } catch (const MarkovError& e) {
    EXPECT_TRUE(e.limitReached);
  }
  EXPECT_THROW((void)analyzeLossRun(4, 0.2, 100'000'000), MarkovError);
}

}  // namespace
}  // namespace semo::checker
