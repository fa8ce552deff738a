// The counter abstraction (counter_abstraction.hpp) proves only what holds: on random teams of
// interchangeable robots with counts, and on the swarm example with properties that fail, it never
// proves a property the explicit search refutes; and it proves the swarm's properties with as many
// abstract states for 10,000 robots as for 10.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "ir_support.hpp"
#include "random_model.hpp"
#include "semo/checker/counter_abstraction.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

using checker::Verdict;

// A team of 3 or 4 robots, each with a program counter and a flag; two counts (robots alive at a
// program counter, robots alive with the flag up) that the rules read and keep; a crash budget of
// one; a global switch. Properties over every robot, some robot, one robot and the counts.
struct RandomTeam {
  std::string text;
  std::vector<std::string> countDefinitions;  // "count == sum", parsed after the model
};

RandomTeam randomTeam(std::uint32_t seed) {
  std::mt19937 rng(seed);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const int n = pick(3, 4);
  const int at = pick(0, 2);  // the program counter counted
  std::ostringstream out;
  out << "semo-ir 1;\nrobots";
  for (int i = 0; i < n; ++i) out << " r" << i;
  out << ";\nvar crashed : 0..1 = 0;\nvar g : bool = false;\n";
  const int init = pick(0, 1);
  out << "var at : 0.." << n << " = " << (init == at ? n : 0) << ";\nvar up : 0.." << n << " = 0;\n";
  for (int i = 0; i < n; ++i) {
    const std::string r = "r" + std::to_string(i);
    out << "var " << r << ".alive : bool = true @robot(" << r << ");\nvar " << r << ".pc : 0..2 = " << init << " @robot(" << r << ");\nvar " << r
        << ".flag : bool = false @robot(" << r << ");\n";
  }
  // The template: from pc, a guard on the counts or the switch, to pc' with the flag set, cleared,
  // flipped or kept.
  struct Step {
    int from, to, flag, guard, fairness, sets;
  };
  std::vector<Step> steps;
  for (int k = pick(3, 6); k > 0; --k) steps.push_back({pick(0, 2), pick(0, 2), pick(0, 3), pick(0, 4), pick(0, 3), pick(0, 3)});
  for (int i = 0; i < n; ++i) {
    const std::string r = "r" + std::to_string(i);
    const std::string a = r + ".alive", pc = r + ".pc", fl = r + ".flag";
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const Step& s = steps[k];
      std::string guard = a + " && " + pc + " == " + std::to_string(s.from);
      if (s.guard == 0) guard += " && at == 0";
      if (s.guard == 1) guard += " && up - (" + fl + " ? 1 : 0) > 0";
      if (s.guard == 2) guard += " && g";
      if (s.guard == 3) guard += " && at - (" + pc + " == " + std::to_string(at) + " ? 1 : 0) >= 1";
      const std::string newFlag = s.flag == 0 ? "1" : s.flag == 1 ? "0" : s.flag == 2 ? "(" + fl + " ? 0 : 1)" : "(" + fl + " ? 1 : 0)";
      const std::string attrs = s.fairness == 0 ? "" : s.fairness == 1 ? " @strongly_fair" : s.fairness == 2 ? " @fair" : " @fair(" + r + ".at" + std::to_string(s.from) + ")";
      out << "rule " << r << ".s" << k << " @robot(" << r << ")" << attrs << " : " << guard << " -> " << pc << "' = " << s.to << ", " << fl << "' = "
          << newFlag << ", at' = at - (" << pc << " == " << at << " ? 1 : 0) + (" << (s.to == at ? 1 : 0) << "), up' = up - (" << fl << " ? 1 : 0) + "
          << newFlag << (s.sets == 0 ? ", g' = !g" : "") << ";\n";
    }
    out << "rule " << r << ".crash @robot(" << r << ") @kind(crash) : " << a << " && crashed < 1 -> " << a << "' = false, crashed' = crashed + 1, " << pc
        << "' = " << init << ", " << fl << "' = false, at' = at - (" << pc << " == " << at << " ? 1 : 0), up' = up - (" << fl << " ? 1 : 0);\n";
  }
  auto every = [&](const std::string& body, const char* join) {
    std::string f;
    for (int i = 0; i < n; ++i) {
      std::string b = body;
      for (std::size_t p; (p = b.find("$")) != std::string::npos;) b.replace(p, 1, "r" + std::to_string(i));
      f += (i == 0 ? "" : join) + ("(" + b + ")");
    }
    return f;
  };
  const std::string local[] = {"!$.alive || $.pc == " + std::to_string(pick(0, 2)), "$.alive && $.flag", "!$.flag", "$.alive && $.pc != " + std::to_string(pick(0, 2))};
  auto condition = [&] {
    switch (pick(0, 5)) {
      case 0: return every(local[pick(0, 3)], " && ");
      case 1: return every(local[pick(0, 3)], " || ");
      case 2: return std::string("at == 0");
      case 3: return std::string("up > 1");
      case 4: return std::string("g");
      default: return "r0.pc == " + std::to_string(pick(0, 2));
    }
  };
  const char* shapes[] = {"eventually A", "always eventually A", "always (A => eventually B)", "eventually always A", "A until B"};
  for (int p = 0; p < 3; ++p) {
    std::string f = shapes[pick(0, 4)];
    f.replace(f.find('A'), 1, "{" + condition() + "}");
    if (const auto b = f.find('B'); b != std::string::npos) f.replace(b, 1, "{" + condition() + "}");
    out << "property p" << p << " : " << f << ";\n";
  }
  out << "invariant i0 : " << condition() << ";\n";
  out << "valid_end : " << every("!$.alive || $.pc == " + std::to_string(pick(0, 2)), " && ") << ";\n";
  RandomTeam t;
  t.text = out.str();
  t.countDefinitions = {"at == " + every("$.alive && $.pc == " + std::to_string(at) + " ? 1 : 0", " + "),
                        "up == " + every("$.alive && $.flag ? 1 : 0", " + ")};
  return t;
}

// The definitions, read as the invariant of a throwaway model with the same variables.
std::vector<ir::Expr> definitions(const std::string& text, const std::vector<std::string>& defs) {
  std::vector<ir::Expr> out;
  for (const std::string& d : defs) {
    std::string t = text.substr(0, text.find("rule "));
    t += "invariant d : " + d + ";\n";
    out.push_back(test::parseIr(t).invariants.back().holds);
  }
  return out;
}

struct Explicit {
  std::vector<Verdict> safety, liveness;
};

Explicit explicitVerdicts(const ir::Model& m) {
  checker::SearchLimits limits;
  Explicit out;
  for (const auto& p : checker::checkSafety(m, limits).properties) out.safety.push_back(p.verdict);
  for (const auto& p : checker::checkLiveness(m, limits).properties) out.liveness.push_back(p.verdict);
  return out;
}

// Exact counts (a threshold above the team's size) give as many states as the explicit search
// stores with symmetry, on every random team: both keep apart the robots the invariants name.
TEST(CounterAbstraction, ExactCountsMatchTheSymmetricSearchOnRandomTeams) {
  int compared = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(100); ++seed) {
    const RandomTeam t = randomTeam(seed);
    const ir::Model m = test::parseIr(t.text);
    checker::CountingOptions exact;
    exact.threshold = static_cast<std::uint32_t>(m.robots.size()) + 1;
    const checker::CountingResult c = checker::checkByCounting(m, definitions(t.text, t.countDefinitions), exact);
    ASSERT_TRUE(c.applicable) << c.why;
    const checker::SearchResult s = checker::checkSafety(m, checker::SearchLimits{});
    if (!s.complete) continue;  // stopped at a violation
    ++compared;
    EXPECT_EQ(c.states, s.states) << "seed " << seed << "\n" << t.text;
  }
  RecordProperty("compared", compared);
  EXPECT_GE(compared, test::atLeast(30));
}

TEST(CounterAbstraction, NeverProvesWhatTheExplicitSearchRefutesOnRandomTeams) {
  int proven = 0, refutedByExplicit = 0, applicable = 0, missed = 0;
  for (std::uint32_t seed = 1; seed <= test::randomModels(300); ++seed) {
    const RandomTeam t = randomTeam(seed);
    const ir::Model m = test::parseIr(t.text);
    const checker::CountingResult c = checker::checkByCounting(m, definitions(t.text, t.countDefinitions));
    ASSERT_TRUE(c.applicable) << "seed " << seed << ": " << c.why << "\n" << t.text;
    ++applicable;
    const Explicit e = explicitVerdicts(m);
    std::vector<Verdict> counted;
    for (const auto& v : c.invariants) counted.push_back(v.verdict);
    counted.push_back(c.deadlock.verdict);
    ASSERT_EQ(counted.size(), e.safety.size()) << seed;
    for (const auto& v : c.properties) counted.push_back(v.verdict);
    std::vector<Verdict> expected = e.safety;
    expected.insert(expected.end(), e.liveness.begin(), e.liveness.end());
    for (std::size_t k = 0; k < counted.size(); ++k) {
      EXPECT_NE(counted[k], Verdict::Violated) << "seed " << seed << " property " << k;
      if (counted[k] == Verdict::Proven) {
        ++proven;
        EXPECT_EQ(expected[k], Verdict::Proven) << "seed " << seed << " property " << k << " proven by counting only\n" << t.text;
      }
      if (expected[k] == Verdict::Violated) ++refutedByExplicit;
      if (expected[k] == Verdict::Proven && counted[k] != Verdict::Proven) ++missed;
    }
  }
  // Not vacuous: the abstraction proves many, and the explicit search refutes many it leaves open.
  RecordProperty("proven", proven);
  RecordProperty("refuted", refutedByExplicit);
  RecordProperty("missed", missed);  // proven by the explicit search only (the abstraction is coarser)
  EXPECT_GE(proven, test::atLeast(400)) << applicable;
  EXPECT_GE(refutedByExplicit, test::atLeast(600));
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

struct TranslatedTeam {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<Translation> translation;
};

// The swarm example with its team line changed, and more properties.
std::unique_ptr<TranslatedTeam> swarm(int robots, const std::string& extra = "", std::size_t countTeamsAbove = TranslationOptions{}.countTeamsAbove) {
  const std::string dir = SEMO_SOURCE_DIR "/specs/examples/swarm/";
  std::string text = readFile(dir + "swarm10.semo");
  text.replace(text.find("legged[10]"), 10, "legged[" + std::to_string(robots) + "]");
  text.replace(text.find("  property all_turn_back"), 0, extra);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / ("semo_counting_swarm" + std::to_string(robots) + ".semo");
  std::ofstream(file) << text;
  auto t = std::make_unique<TranslatedTeam>();
  auto m = loadMission({file.string(), dir + "strategy.xml", std::nullopt}, t->sources, t->diags);
  TranslationOptions options;
  options.countTeamsAbove = countTeamsAbove;
  if (m) t->translation = translateMission(*m, options, t->sources, t->diags);
  return t;
}

// From the smallest team translated with counts (9 robots) on, the abstraction is the same: the
// same abstract states, and the same product per property (specs/ir.md, "Counter abstraction").
TEST(CounterAbstraction, ProvesTheSwarmWithTheSameAbstractionForAnyTeamSize) {
  std::vector<std::uint64_t> first;
  // 10,000 robots take 10 s to translate under the sanitizers: 1,000 there.
  for (int robots : {9, 10, 100, SEMO_TESTS_SANITIZED ? 1000 : 10000}) {
    auto t = swarm(robots);
    ASSERT_TRUE(t->translation) << robots;
    checker::CountingOptions options;
    options.countedTeamsFrom = TranslationOptions{}.countTeamsAbove + 1;
    const checker::CountingResult c = checker::checkByCounting(t->translation->model, t->translation->lowering.countDefinitions, options);
    ASSERT_TRUE(c.applicable) << c.why;
    EXPECT_TRUE(c.allProven()) << robots;
    EXPECT_EQ(c.localStates, 8u);
    ASSERT_EQ(c.properties.size(), 3u);
    EXPECT_EQ(c.properties[0].explicitRobots, std::vector<std::string>{"legged_0"}) << "all_turn_back names legged_0";
    std::vector<std::uint64_t> figures{c.states, c.transitions};
    for (const auto& p : c.properties) {
      figures.push_back(p.productStates);
      EXPECT_EQ(p.everyTeamFrom, 9u) << p.name;
    }
    if (first.empty()) first = figures;
    EXPECT_EQ(figures, first) << robots << " robots";
  }
}

// With a threshold above the team's size no count is "K or more": the abstraction is exact, its
// states are the orbits of the robots' permutations, as many as the explicit search stores with
// symmetry (and every property it proves stays proven).
TEST(CounterAbstraction, CountsAboveTheTeamsSizeAreTheSymmetricSearchsStates) {
  auto t = swarm(10);
  ASSERT_TRUE(t->translation);
  const ir::Model& m = t->translation->model;
  checker::CountingOptions exact;
  exact.threshold = 11;
  const checker::CountingResult c = checker::checkByCounting(m, t->translation->lowering.countDefinitions, exact);
  ASSERT_TRUE(c.applicable) << c.why;
  EXPECT_TRUE(c.allProven());
  const checker::SearchResult s = checker::checkSafety(m, checker::SearchLimits{});
  ASSERT_TRUE(s.complete);
  EXPECT_EQ(c.states, s.states);
  EXPECT_EQ(c.states, 861u);
}

TEST(CounterAbstraction, LeavesTheSwarmsFailingPropertiesUndecided) {
  // Four robots with counts (as a team of more than 8 has them), for the explicit search to refute
  // the failing properties quickly.
  auto t = swarm(4,
                 "  property never_retreat: always (legged_0.mode == MARCH_MODE)\n"
                 "  property someone_crashes: eventually (not legged_3.alive)\n"
                 "  property march_again: always eventually (Swarm.mode == MARCH_MODE)\n"
                 "  property all_retreat_eventually: eventually (Swarm.mode == RETREAT_MODE)\n",
                 2);
  ASSERT_TRUE(t->translation);
  const ir::Model& m = t->translation->model;
  const checker::CountingResult c = checker::checkByCounting(m, t->translation->lowering.countDefinitions);
  ASSERT_TRUE(c.applicable) << c.why;
  const Explicit e = explicitVerdicts(m);
  ASSERT_EQ(c.properties.size(), e.liveness.size());
  int refuted = 0, proven = 0;
  for (std::size_t k = 0; k < c.properties.size(); ++k) {
    if (e.liveness[k] == Verdict::Violated) {
      ++refuted;
      EXPECT_EQ(c.properties[k].verdict, Verdict::Unknown) << c.properties[k].name;
      EXPECT_FALSE(c.properties[k].why.empty());
    }
    proven += c.properties[k].verdict == Verdict::Proven ? 1 : 0;
  }
  // all_turn_back and mode_agreement; knowledge_convergence of four robots compares them pair by
  // pair, which the abstraction does not read (a larger team's form, "every robot holds c facts
  // for some c", it does).
  EXPECT_EQ(proven, 2);
  EXPECT_EQ(refuted, 3);  // someone_crashes, march_again, all_retreat_eventually (an invariant: never_retreat)
  for (std::size_t k = 0; k < c.invariants.size(); ++k) {
    if (e.safety[k] == Verdict::Violated) {
      EXPECT_EQ(c.invariants[k].verdict, Verdict::Unknown) << c.invariants[k].name;
    }
  }
}

// Weak fairness is a robot's: one that leaves its local state before a step it has enabled there
// is taken owes nothing. Three robots take turns stepping out of program counter 1 and back, one
// at a time, so that counter 1 is never empty and the step to 2 is always enabled for some robot
// there, never for one robot throughout: no robot need reach 2. The abstraction must let robots
// leaving a local state discharge what the state enables, or it would prove `eventually` here.
TEST(CounterAbstraction, ARobotThatLeavesInTimeOwesNoStep) {
  std::string text = "semo-ir 1;\nrobots r0 r1 r2;\nvar at : 0..3 = 3;\n";
  for (const char* r : {"r0", "r1", "r2"}) text += std::string("var ") + r + ".pc : 0..2 = 1 @robot(" + r + ");\n";
  for (const std::string r : {"r0", "r1", "r2"}) {
    text += "rule " + r + ".out @robot(" + r + ") @fair : " + r + ".pc == 1 && at - 1 >= 1 -> " + r + ".pc' = 0, at' = at - 1;\n";
    text += "rule " + r + ".back @robot(" + r + ") @fair : " + r + ".pc == 0 -> " + r + ".pc' = 1, at' = at + 1;\n";
    text += "rule " + r + ".on @robot(" + r + ") @fair : " + r + ".pc == 1 -> " + r + ".pc' = 2, at' = at - 1;\n";
  }
  text += "property someone_on : eventually {r0.pc == 2 || r1.pc == 2 || r2.pc == 2};\n";
  const ir::Model m = test::parseIr(text);
  ASSERT_EQ(explicitVerdicts(m).liveness, std::vector<Verdict>{Verdict::Violated});
  const checker::CountingResult c = checker::checkByCounting(m, definitions(text, {"at == (r0.pc == 1 ? 1 : 0) + (r1.pc == 1 ? 1 : 0) + (r2.pc == 1 ? 1 : 0)"}));
  ASSERT_TRUE(c.applicable) << c.why;
  EXPECT_EQ(c.properties[0].verdict, Verdict::Unknown);
}

TEST(CounterAbstraction, RefusesCountsThatRulesDoNotKeep) {
  RandomTeam t = randomTeam(3);
  // Every step now adds one to `up` whatever it does to the flag: no longer the count it claims.
  for (std::size_t p = 0; (p = t.text.find("up' = up - (", p)) != std::string::npos; ++p) t.text.replace(p, 12, "up' = up + 1 + 0 * (");
  const ir::Model m = test::parseIr(t.text);
  const checker::CountingResult c = checker::checkByCounting(m, definitions(t.text, t.countDefinitions));
  EXPECT_FALSE(c.applicable);
  EXPECT_NE(c.why.find("otherwise than its definition"), std::string::npos) << c.why;
}

TEST(CounterAbstraction, DoesNotApplyWithoutCountsOrToRobotsThatReadEachOther) {
  auto t = swarm(3);
  ASSERT_TRUE(t->translation);
  const checker::CountingResult none = checker::checkByCounting(t->translation->model, t->translation->lowering.countDefinitions);
  EXPECT_FALSE(none.applicable);  // three robots read each other, without counts
  EXPECT_NE(none.why.find("counts"), std::string::npos) << none.why;
}

}  // namespace
}  // namespace semo
