// The symbolic liveness search (checker/src/symbolic_liveness.hpp): on random models it must give
// the explicit search's verdict on every property, and every lasso it builds must pass the
// independent lasso check; the sliced search that hands its large slices to it must agree too, and
// so must its hunt for quiet loops; a node table too small for the model gives up without harm;
// searches on several threads, some of them in child processes, agree with one at a time.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <thread>

#include "../../checker/src/sliced_liveness.hpp"
#include "../../checker/src/symbolic_apart.hpp"
#include "../../checker/src/symbolic_liveness.hpp"
#include "ir_support.hpp"
#include "random_model.hpp"
#include "true_invariant.hpp"
#include "semo/checker/compiled_model.hpp"
#include "semo/checker/lasso_check.hpp"
#include "semo/checker/liveness_search.hpp"

namespace semo::checker {
namespace {

using detail::SymbolicOutcome;

LivenessResult explicitSearch(const ir::Model& m) {
  LivenessOptions options;
  options.slicing = false;
  return checkLiveness(m, SearchLimits{}, options);
}

// Calls f(model, the explicit search's result, property index) for every property of the random
// models 1..seeds, traced with the seed, the model's text and the property's name. With
// `trueInvariant`, each model gets one of its true invariants where it has one (true_invariant.hpp).
template <typename F>
void forEachRandomProperty(std::uint32_t seeds, F f, bool trueInvariant = false) {
  for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
    std::string text = test::RandomModel(seed).text();
    if (trueInvariant) {
      const std::vector<std::string> invariants = test::trueInvariants(test::parseIr(text), 1);
      if (!invariants.empty()) text += invariants.front();
    }
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    const LivenessResult reference = explicitSearch(m);
    ASSERT_TRUE(reference.complete);
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      SCOPED_TRACE(m.properties[k].name);
      f(m, reference, k);
    }
  }
}

TEST(SymbolicLiveness, RandomModelsGetTheExplicitVerdictsAndCheckedLassos) {
  int proven = 0, violated = 0;
  forEachRandomProperty(test::randomModels(300), [&](const ir::Model& m, const LivenessResult& reference, std::size_t k) {
    const SymbolicOutcome s = detail::decideSymbolically(m, k, {});
    ASSERT_NE(s.kind, SymbolicOutcome::Kind::GaveUp) << s.why;
    const Verdict expected = reference.properties[k].verdict;
    EXPECT_EQ(s.kind == SymbolicOutcome::Kind::Violation ? Verdict::Violated : Verdict::Proven, expected);
    if (s.kind != SymbolicOutcome::Kind::Violation) {
      ++proven;
      return;
    }
    ++violated;
    ASSERT_TRUE(s.lasso.has_value());
    const LassoCheck c = checkLasso(m, *s.lasso, m.properties[k]);
    EXPECT_TRUE(c.counterexample()) << c.why << " unfair " << c.unfairGroups.size() << " unsettled " << c.unsettled.size();
  });
  EXPECT_GT(proven, test::atLeast(100));
  EXPECT_GT(violated, test::atLeast(100));
}

// Searched within the projected superset of the reachable states (SymbolicLimits::overApproximate,
// as on an exact cone), bounded by a true invariant where the model has one (as the check's proven
// ones): the explicit verdict every time, proofs found within the superset on some models, and
// the exact reachable states searched again on others, where the superset's fair states were not
// reachable (that fallback must not turn a proof into a violation, nor miss one).
TEST(SymbolicLiveness, SearchesWithinTheProjectedSupersetGetTheExplicitVerdicts) {
  int withinSuperset = 0, exactAgain = 0, violated = 0;
  forEachRandomProperty(
      test::randomModels(300),
      [&](const ir::Model& m, const LivenessResult& reference, std::size_t k) {
        detail::SymbolicLimits limits;
        limits.overApproximate = true;
        limits.everyWorld = true;
        const SymbolicOutcome s = detail::decideSymbolically(m, k, limits);
        ASSERT_NE(s.kind, SymbolicOutcome::Kind::GaveUp) << s.why;
        EXPECT_EQ(s.kind == SymbolicOutcome::Kind::Violation ? Verdict::Violated : Verdict::Proven, reference.properties[k].verdict);
        if (s.kind == SymbolicOutcome::Kind::Violation) {
          ++violated;
          ASSERT_TRUE(s.lasso.has_value());
          const LassoCheck c = checkLasso(m, *s.lasso, m.properties[k]);
          EXPECT_TRUE(c.counterexample()) << c.why;
        } else {
          ++(s.overApproximated ? withinSuperset : exactAgain);
        }
      },
      true);
  std::printf("%d proofs within the superset, %d on the exact states again, %d violations\n", withinSuperset, exactAgain, violated);
  EXPECT_GT(withinSuperset, test::atLeast(100));
  EXPECT_GT(exactAgain, test::atLeast(5));
  EXPECT_GT(violated, test::atLeast(100));
}

// With a slice budget of one state, every slice is searched symbolically: its lasso refines the
// slice as an enumerated one would, and a proof on a slice is a proof on the model.
TEST(SymbolicLiveness, SlicesTooLargeToEnumerateAreDecidedSymbolically) {
  int symbolicProofs = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(150); ++seed) {
    const std::string text = test::RandomModel(seed).text();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    const ir::Model m = test::parseIr(text);
    const LivenessResult reference = explicitSearch(m);
    LivenessOptions options;
    options.sliceStates = 1;
    options.wholeProduct = false;
    const LivenessResult sliced = checkLiveness(m, SearchLimits{}, options);
    for (std::size_t k = 0; k < m.properties.size(); ++k) {
      SCOPED_TRACE(m.properties[k].name);
      const Verdict v = sliced.properties[k].verdict;
      // Without the whole product, a violation whose slice lasso cannot be rebuilt stays unknown;
      // whatever is decided must be what the explicit search decides.
      if (v != Verdict::Unknown) {
        EXPECT_EQ(v, reference.properties[k].verdict);
      }
      if (v == Verdict::Proven && sliced.methods[k].symbolic) ++symbolicProofs;
      if (v == Verdict::Violated) {
        ASSERT_TRUE(sliced.properties[k].counterexample.has_value());
        EXPECT_TRUE(checkLasso(m, *sliced.properties[k].counterexample, m.properties[k]).counterexample());
      }
    }
  }
  EXPECT_GT(symbolicProofs, test::atLeast(50));
}

// Eight counters cycle (65,536 values); z may sense p once and leave m = 0 for good. The
// property reads every counter, so no slice is smaller than the model, far beyond a budget of
// 1,000 states: the symbolic search proves the model without the way out, and finds the lasso of
// the one with it.
TEST(SymbolicLiveness, ASliceFarBeyondTheBudgetIsDecidedSymbolically) {
  std::string m = "semo-ir 1;\nvar m : 0..1 = 0;\n";
  std::string sum;
  for (int k = 1; k <= 8; ++k) {
    const std::string c = "c" + std::to_string(k);
    m += "var " + c + " : 0..3 = 0;\nrule tick" + std::to_string(k) + " @fair : true -> " + c + "' = (" + c + " + 1) % 4;\n";
    sum += (sum.empty() ? "" : " + ") + c;
  }
  const std::string property = "property p : always eventually {m == 0 || " + sum + " == 99};\n";
  const std::string way = "rule go @fair(z) @senses(\"z.p=1\") : m == 0 -> m' = 1;\n";
  const std::string stay = "rule stay @fair(z) @senses(\"z.p=0\") : m == 0 -> skip;\n";
  SearchLimits small;
  small.maxStates = 1000;
  LivenessOptions options;
  options.sliceStates = 1000;
  options.wholeProduct = false;
  const LivenessResult violated = checkLiveness(test::parseIr(m + way + stay + property), small, options);
  ASSERT_EQ(violated.properties[0].verdict, Verdict::Violated);
  const ir::Model withWay = test::parseIr(m + way + stay + property);
  EXPECT_TRUE(checkLasso(withWay, *violated.properties[0].counterexample, withWay.properties[0]).counterexample());
  const LivenessResult proven = checkLiveness(test::parseIr(m + stay + property), small, options);
  EXPECT_EQ(proven.properties[0].verdict, Verdict::Proven);
  ASSERT_EQ(proven.methods.size(), 1u);
  EXPECT_TRUE(proven.methods[0].symbolic);
  EXPECT_GE(proven.methods[0].symbolicStates, 65536.0);  // every value of the counters, with m = 0
  // Without the symbolic search, the same budget decides nothing.
  options.symbolic = false;
  EXPECT_EQ(checkLiveness(test::parseIr(m + stay + property), small, options).properties[0].verdict, Verdict::Unknown);
}

// The hunt's question (SymbolicLimits::quietLoop): a fair violation whose loop senses nothing. It
// is asked of the property's cone without crashes (sliced_liveness.cpp), so it must never find
// what is not there: every lasso it builds is a violation of the model, and on a model where the
// explicit search proves the property it finds nothing.
TEST(SymbolicLiveness, AHuntForQuietLoopsFindsOnlyRealViolations) {
  int found = 0, violations = 0;
  forEachRandomProperty(test::randomModels(300), [&](const ir::Model& m, const LivenessResult& reference, std::size_t k) {
    detail::SymbolicLimits quiet;
    quiet.quietLoop = true;
    const SymbolicOutcome s = detail::decideSymbolically(m, k, quiet);
    ASSERT_NE(s.kind, SymbolicOutcome::Kind::GaveUp) << s.why;
    if (reference.properties[k].verdict == Verdict::Violated) ++violations;
    if (s.kind != SymbolicOutcome::Kind::Violation) return;
    ++found;
    EXPECT_EQ(reference.properties[k].verdict, Verdict::Violated);
    ASSERT_TRUE(s.lasso.has_value());
    EXPECT_TRUE(checkLasso(m, *s.lasso, m.properties[k]).counterexample());
    for (std::size_t i = s.lasso->loopStart; i < s.lasso->steps.size(); ++i) {
      EXPECT_TRUE(m.rules[s.lasso->steps[i].rule].sensed.empty()) << "the loop senses at step " << i + 1;
    }
  });
  // Most violations of these models have a quiet loop; not all (some need the world's help).
  EXPECT_GT(found, test::atLeast(50));
  EXPECT_LE(found, violations);
}

// A hunt that finds no quiet loop goes on to every settling world (SymbolicLimits::thenSettled).
// Asked of the whole model (nothing left out), it is then the proof's search: it finds a violation
// exactly where the explicit search does, including those whose loop needs the world's help,
// and each lasso passes the independent check.
TEST(SymbolicLiveness, AHuntThatGoesOnToTheSettlingWorldsFindsEveryViolation) {
  int found = 0, sensing = 0;
  forEachRandomProperty(test::randomModels(300), [&](const ir::Model& m, const LivenessResult& reference, std::size_t k) {
    detail::SymbolicLimits hunt;
    hunt.quietLoop = true;
    hunt.thenSettled = true;
    const SymbolicOutcome s = detail::decideSymbolically(m, k, hunt);
    ASSERT_NE(s.kind, SymbolicOutcome::Kind::GaveUp) << s.why;
    EXPECT_EQ(s.kind == SymbolicOutcome::Kind::Violation, reference.properties[k].verdict == Verdict::Violated);
    if (s.kind != SymbolicOutcome::Kind::Violation) return;
    ++found;
    ASSERT_TRUE(s.lasso.has_value());
    EXPECT_TRUE(checkLasso(m, *s.lasso, m.properties[k]).counterexample());
    bool senses = false;
    for (std::size_t i = s.lasso->loopStart; i < s.lasso->steps.size(); ++i) senses = senses || !m.rules[s.lasso->steps[i].rule].sensed.empty();
    if (senses) ++sensing;
  });
  EXPECT_GT(found, test::atLeast(50));
  EXPECT_GT(sensing, 0);  // some violations were found only on a settling world
}

// The whole hunt, as checkSliced runs it after the slices: the cone, the quiet loop, and the
// rebuild on the model. A violation it reports is the explicit search's verdict, with a lasso that
// passes the independent check; what it does not find, it leaves unknown with the reason.
TEST(SymbolicLiveness, TheHuntOnTheConeReportsOnlyRebuiltViolations) {
  int hunted = 0;
  forEachRandomProperty(test::randomModels(300), [&](const ir::Model& m, const LivenessResult& reference, std::size_t k) {
    const CompiledModel cm(m);
    detail::SlicedOutcome out;
    detail::huntOnCone(cm, k, SearchLimits{}, out);
    if (out.property.verdict != Verdict::Violated) {
      EXPECT_EQ(out.property.verdict, Verdict::Unknown);
      EXPECT_NE(out.why.find("a hunt on the property's cone"), std::string::npos) << out.why;
      return;
    }
    ++hunted;
    EXPECT_TRUE(out.hunted);
    EXPECT_EQ(reference.properties[k].verdict, Verdict::Violated);
    ASSERT_TRUE(out.property.counterexample.has_value());
    EXPECT_TRUE(checkLasso(m, *out.property.counterexample, m.properties[k]).counterexample());
  });
  EXPECT_GT(hunted, test::atLeast(50));
}

TEST(SymbolicLiveness, ANodeTableTooSmallGivesUpAndTheNextSearchStillWorks) {
  const ir::Model m = test::parseIr(test::RandomModel(7).text());
  detail::SymbolicLimits tiny;
  tiny.maxMemoryBytes = 1;  // the smallest table the package accepts: far too small
  const SymbolicOutcome starved = detail::decideSymbolically(m, 0, tiny);
  EXPECT_EQ(starved.kind, SymbolicOutcome::Kind::GaveUp);
  EXPECT_NE(starved.why.find("decision diagrams"), std::string::npos) << starved.why;
  const SymbolicOutcome fed = detail::decideSymbolically(m, 0, {});
  EXPECT_NE(fed.kind, SymbolicOutcome::Kind::GaveUp) << fed.why;
}

// A random model with 48 more bits of state, none of them read: a "large" model, whose search
// runs in a child process when another thread is inside the decision-diagram package.
ir::Model paddedModel(std::uint32_t seed) {
  std::string text = test::RandomModel(seed).text();
  const std::string slot = "var slot : 0..2 = 0;\n";
  text.insert(text.find(slot) + slot.size(), "var pad0 : 0..65535 = 0;\nvar pad1 : 0..65535 = 0;\nvar pad2 : 0..65535 = 0;\n");
  return test::parseIr(text);
}

TEST(SymbolicLiveness, SearchesOnSeveralThreadsSomeInChildProcessesAgreeWithOneAtATime) {
  std::vector<ir::Model> models;
  for (std::uint32_t seed = 1; seed <= (SEMO_TESTS_SANITIZED ? 2u : 3u); ++seed) models.push_back(paddedModel(seed));
  struct Result {
    SymbolicOutcome::Kind kind;
    double reachable;
  };
  std::vector<std::vector<Result>> alone(models.size());
  for (std::size_t i = 0; i < models.size(); ++i) {
    for (std::size_t k = 0; k < models[i].properties.size(); ++k) {
      const SymbolicOutcome s = detail::decideSymbolically(models[i], k, {});
      ASSERT_NE(s.kind, SymbolicOutcome::Kind::GaveUp) << s.why;
      alone[i].push_back({s.kind, s.reachable});
    }
  }
  const std::uint64_t before = detail::searchesInChildProcesses();
  // Three threads through the same searches, each from a different model on: the package is often
  // busy when one of them starts a search (and a release build forks then; a sanitized one waits).
  std::vector<std::string> disagreements[3];
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 3; ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t n = 0; n < models.size(); ++n) {
        const std::size_t i = (n + t * models.size() / 3) % models.size();
        for (std::size_t k = 0; k < models[i].properties.size(); ++k) {
          const SymbolicOutcome s = detail::decideSymbolically(models[i], k, {});
          const bool lassoHolds = s.kind != SymbolicOutcome::Kind::Violation ||
                                  (s.lasso && checkLasso(models[i], *s.lasso, models[i].properties[k]).counterexample());
          if (s.kind != alone[i][k].kind || s.reachable != alone[i][k].reachable || !lassoHolds) {
            disagreements[t].push_back("model " + std::to_string(i + 1) + " property " + models[i].properties[k].name + ": " + s.why);
          }
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (const auto& d : disagreements) EXPECT_TRUE(d.empty()) << d.front();
  if (SEMO_TESTS_SANITIZED) {
    EXPECT_EQ(detail::searchesInChildProcesses(), before);  // no fork beside other threads there
  } else {
    EXPECT_GT(detail::searchesInChildProcesses(), before);  // some searches did run apart
  }
}

TEST(SymbolicLiveness, AChildProcessPassesOnItsProgressAndItsOutcome) {
  detail::SymbolicLimits limits;
  std::vector<std::uint64_t> seen;
  limits.onProgress = [&](const Progress& p) { seen.push_back(p.states); };
  const std::optional<SymbolicOutcome> got = detail::searchInChildProcess(limits, [](const detail::SymbolicLimits& mine) {
    for (std::uint64_t states : {17u, 4242u}) {
      Progress p;
      p.states = states;
      p.counted = true;
      mine.onProgress(p);
    }
    SymbolicOutcome out;
    out.kind = SymbolicOutcome::Kind::Violation;
    out.reachable = 1.5e20;
    out.worlds = 3;
    out.why = "why not";
    Trace lasso;
    lasso.property = "p";
    lasso.kind = "lasso";
    lasso.initial = {0, -7, 1};
    lasso.steps = {{2, 1, {{0, 0, 1}, {1, -7, 5}}}, {0, 0, {}}};
    lasso.loopStart = 1;
    out.lasso = lasso;
    return out;
  });
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{17, 4242}));
  EXPECT_EQ(got->kind, SymbolicOutcome::Kind::Violation);
  EXPECT_EQ(got->reachable, 1.5e20);
  EXPECT_EQ(got->worlds, 3u);
  EXPECT_EQ(got->why, "why not");
  ASSERT_TRUE(got->lasso.has_value());
  EXPECT_EQ(got->lasso->initial, (std::vector<std::int32_t>{0, -7, 1}));
  ASSERT_EQ(got->lasso->steps.size(), 2u);
  EXPECT_EQ(got->lasso->steps[0].rule, 2u);
  EXPECT_EQ(got->lasso->steps[0].branch, 1u);
  ASSERT_EQ(got->lasso->steps[0].changes.size(), 2u);
  EXPECT_EQ(got->lasso->steps[0].changes[1].before, -7);
  EXPECT_EQ(got->lasso->steps[0].changes[1].after, 5);
  EXPECT_EQ(got->lasso->loopStart, 1u);
  EXPECT_EQ(got->lasso->property, "p");
}

TEST(SymbolicLiveness, AChildProcessThatDiesGivesUpSayingHow) {
  const std::optional<SymbolicOutcome> killed =
      detail::searchInChildProcess({}, [](const detail::SymbolicLimits&) -> SymbolicOutcome { ::kill(::getpid(), SIGKILL); return {}; });
  ASSERT_TRUE(killed.has_value());
  EXPECT_EQ(killed->kind, SymbolicOutcome::Kind::GaveUp);
  EXPECT_NE(killed->why.find("ended by signal 9"), std::string::npos) << killed->why;
  const std::optional<SymbolicOutcome> quit =
      detail::searchInChildProcess({}, [](const detail::SymbolicLimits&) -> SymbolicOutcome { ::_exit(7); });
  ASSERT_TRUE(quit.has_value());
  EXPECT_EQ(quit->kind, SymbolicOutcome::Kind::GaveUp);
  EXPECT_NE(quit->why.find("without an answer (exit code 7)"), std::string::npos) << quit->why;
}

}  // namespace
}  // namespace semo::checker
