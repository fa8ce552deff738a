// The random walks that hunt fair violations (checker/src/lasso_walks.hpp): they must never report
// a lasso where the explicit search proves the property, every lasso they report must pass the
// independent lasso check, the same seed must give the same lasso, and the shortening must keep a
// counterexample a counterexample.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "../../checker/src/lasso_walks.hpp"
#include "ir_support.hpp"
#include "random_model.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/liveness_search.hpp"

namespace semo::checker {
namespace {

using detail::findLassoByWalks;
using detail::LassoWalkLimits;
using detail::LassoWalkOutcome;

LassoWalkLimits quick() {
  LassoWalkLimits l;
  l.walks = 100;
  l.seconds = 5;
  return l;
}

TEST(LassoWalks, RandomModelsGetOnlyCheckedLassosOfViolatedProperties) {
  int violations = 0, found = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(300); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    LivenessOptions exact;
    exact.slicing = false;
    const LivenessResult reference = checkLiveness(m, SearchLimits{}, exact);
    ASSERT_TRUE(reference.complete);
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      SCOPED_TRACE(m.properties[k].name);
      LassoWalkLimits few = quick();  // small models: short walks, and few of them, suffice
      few.walks = 40;
      few.stepsPerWalk = 256;
      const LassoWalkOutcome w = findLassoByWalks(m, k, few);
      const bool violated = reference.properties[k].verdict == Verdict::Violated;
      violations += violated ? 1 : 0;
      if (!w.lasso) continue;
      ++found;
      EXPECT_TRUE(violated) << "a lasso of a property the explicit search proves";
      const LassoCheck c = checkLasso(m, *w.lasso, m.properties[k]);
      EXPECT_TRUE(c.counterexample()) << c.why << " unfair " << c.unfairGroups.size() << " unsettled " << c.unsettled.size();
    }
  }
  // Small models: the walks find nearly every violation.
  std::printf("random walks found %d of %d violations\n", found, violations);
  EXPECT_GT(violations, test::atLeast(150));
  EXPECT_GE(found * 10, violations * 9);
}

TEST(LassoWalks, TheSameSeedGivesTheSameLasso) {
  const ir::Model m = test::parseIr(test::RandomModel(7).text());
  LassoWalkLimits a = quick(), b = quick();
  b.seed = 2;
  bool compared = false;
  for (std::size_t k = 0; k < m.properties.size(); ++k) {
    const LassoWalkOutcome first = findLassoByWalks(m, k, a), again = findLassoByWalks(m, k, a);
    ASSERT_EQ(first.lasso.has_value(), again.lasso.has_value());
    EXPECT_EQ(first.walks, again.walks);
    EXPECT_EQ(first.steps, again.steps);
    if (!first.lasso) continue;
    EXPECT_EQ(traceToText(m, *first.lasso), traceToText(m, *again.lasso));
    compared = true;
    const LassoWalkOutcome other = findLassoByWalks(m, k, b);  // another seed: other walks
    EXPECT_TRUE(other.steps != first.steps || other.walks != first.walks || !other.lasso ||
                traceToText(m, *other.lasso) != traceToText(m, *first.lasso) || first.walks == 1);
  }
  EXPECT_TRUE(compared) << "random model 7 has no violated property any more: pick another";
}

// A message lost for ever (unfair loss): the lasso's stem went round the send-lose loop five times;
// shortened, it starts in the loop at once, and it is still a counterexample.
TEST(LassoWalks, ShorteningCutsTheStemsLoopsAndKeepsACounterexample) {
  const ir::Model m = test::parseIr(
      "semo-ir 1;\nrobots s r;\nvar msg : bool = false @robot(s);\nvar got : bool = false @robot(r);\n"
      "rule send @robot(s) @fair : !msg && !got -> msg' = true;\n"
      "rule lose @robot(r) @kind(loss) : msg -> msg' = false;\n"
      "rule deliver @robot(r) @fair : msg -> msg' = false, got' = true;\n"
      "property arrives : eventually {got};\n");
  Trace t;
  t.kind = "lasso";
  t.property = "arrives";
  t.initial = {0, 0};
  for (int round = 0; round < 6; ++round) {
    t.steps.push_back({0, 0, {{0, 0, 1}}});
    t.steps.push_back({1, 0, {{0, 1, 0}}});
  }
  t.loopStart = 10;
  ASSERT_TRUE(checkLasso(m, t, m.properties[0]).counterexample());
  const Trace shorter = detail::shortenLasso(m, t, m.properties[0]);
  EXPECT_EQ(shorter.loopStart, 0u);
  EXPECT_EQ(shorter.steps.size(), 2u);
  EXPECT_TRUE(checkLasso(m, shorter, m.properties[0]).counterexample());
}

// The hunt models of liveness_test.cpp, where no slice is smaller than the product and a partial
// breadth-first search holds no loop: the walks find each violation (a lost message, a
// crash) and the liveness search reports it as theirs.
TEST(LassoWalks, FindWhatNoSliceAndNoPartialSearchReaches) {
  const test::ResettingCounters c = test::resettingCounters();
  const std::string counters = c.declarations + c.resetRule;
  const std::string& sum = c.sum;
  const std::string lost = "semo-ir 1;\nvar inbox : bool = false;\nvar got : bool = false;\nvar sent : bool = false;\n" + counters +
                           "rule send @fair : !sent -> sent' = true, inbox' = true;\n"
                           "rule lose @kind(loss) : inbox -> inbox' = false;\n"
                           "rule deliver @fair : inbox -> inbox' = false, got' = true;\n"
                           "property p : eventually {got || " + sum + " == 99};\n";
  const std::string crashed = "semo-ir 1;\nvar alive : bool = true;\nvar done : bool = false;\n" + counters +
                              "rule crash @kind(crash) : alive -> alive' = false;\n"
                              "rule work @fair : alive && !done -> done' = true;\n"
                              "property p : eventually {done || " + sum + " == 99};\n";
  for (const std::string& text : {lost, crashed}) {
    const ir::Model m = test::parseIr(text);
    SearchLimits small;
    small.maxStates = 1000;
    LivenessOptions options;
    options.sliceStates = 1000;
    options.symbolic = false;
    const LivenessResult r = checkLiveness(m, small, options);
    ASSERT_EQ(r.properties[0].verdict, Verdict::Violated) << text;
    EXPECT_TRUE(r.methods[0].walked);
    EXPECT_GE(r.methods[0].walks, 1u);
    EXPECT_TRUE(checkLasso(m, *r.properties[0].counterexample, m.properties[0]).counterexample());
  }
}

}  // namespace
}  // namespace semo::checker
