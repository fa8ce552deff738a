// The counts of a large team (specs/semantics.md, "Counts of a large team") mean what the
// robot-by-robot form means: the same mission translated both ways has the same number of
// states, with and without symmetry, and the same verdicts, safety and liveness; in every
// reachable state each count is what counting the robots gives.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "semo/checker/explicit_search.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/smt_search.hpp"
#include "semo/checker/stepper.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

struct TranslatedSwarm {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<ir::Model> model;
};

// The swarm example of three robots (crash <= 2, lossy gossip, a group service with a goal).
std::unique_ptr<TranslatedSwarm> swarm3(std::size_t countTeamsAbove, const std::string& strategy = "strategy.xml") {
  auto t = std::make_unique<TranslatedSwarm>();
  const std::string dir = SEMO_SOURCE_DIR "/specs/examples/swarm/";
  auto m = loadMission({dir + "swarm3.semo", dir + strategy, std::nullopt}, t->sources, t->diags);
  TranslationOptions options;
  options.countTeamsAbove = countTeamsAbove;
  if (m) t->model = translate(*m, options, t->sources, t->diags);
  return t;
}

std::vector<std::string> countNames(const ir::Model& m) {
  std::vector<std::string> out;
  for (const ir::Variable& v : m.variables) {
    if (v.name.rfind("Swarm.holding.", 0) == 0 || v.name.rfind("Swarm.at.", 0) == 0) out.push_back(v.name);
  }
  return out;
}

struct Verdicts {
  std::uint64_t states = 0;
  std::vector<checker::Verdict> safety, liveness;
};

Verdicts verdictsOf(const ir::Model& m, bool symmetry) {
  checker::SearchLimits limits;
  limits.symmetry = symmetry;
  const checker::SearchResult s = checker::checkSafety(m, limits);
  EXPECT_TRUE(s.complete) << s.limitReached;
  Verdicts out;
  out.states = s.states;
  for (const checker::PropertyResult& p : s.properties) out.safety.push_back(p.verdict);
  const checker::LivenessResult l = checker::checkLiveness(m, limits);
  EXPECT_TRUE(l.complete) << l.limitReached;
  for (const checker::PropertyResult& p : l.properties) out.liveness.push_back(p.verdict);
  return out;
}

TEST(TeamCounts, MeanWhatTheRobotByRobotFormMeans) {
  for (const std::string strategy : {"strategy.xml", "strategy_no_sharing.xml"}) {
    auto counted = swarm3(2, strategy), plain = swarm3(8, strategy);
    ASSERT_TRUE(counted->model && plain->model) << strategy;
    EXPECT_TRUE(countNames(*plain->model).empty()) << "three robots: no counts by default";
    const std::vector<std::string> names = countNames(*counted->model);
    EXPECT_NE(std::find(names.begin(), names.end(), "Swarm.at.Move.2"), names.end()) << strategy;  // inside the block
    if (strategy == "strategy.xml") {
      EXPECT_NE(std::find(names.begin(), names.end(), "Swarm.holding.obstacle.1"), names.end());
    }
    for (bool symmetry : {false, true}) {
      const Verdicts a = verdictsOf(*counted->model, symmetry), b = verdictsOf(*plain->model, symmetry);
      EXPECT_EQ(a.states, b.states) << strategy << (symmetry ? " with symmetry" : "");
      EXPECT_EQ(a.safety, b.safety) << strategy;
      EXPECT_EQ(a.liveness, b.liveness) << strategy;
      EXPECT_FALSE(a.liveness.empty());
    }
  }
}

// Recounted from the robots' variables, in every reachable state (no symmetry: every state).
TEST(TeamCounts, AreTheNumberOfLiveRobotsTheyCountInEveryReachableState) {
  auto t = swarm3(2);
  ASSERT_TRUE(t->model.has_value());
  const ir::Model& m = *t->model;
  auto index = [&](const std::string& name) {
    for (std::size_t v = 0; v < m.variables.size(); ++v) {
      if (m.variables[v].name == name) return v;
    }
    ADD_FAILURE() << "no variable " << name;
    return std::size_t{0};
  };
  const std::vector<std::string> robots{"legged_0", "legged_1", "legged_2"};
  struct Count {
    std::size_t var;
    std::vector<std::size_t> of;  // per robot
    std::vector<std::int32_t> values;
  };
  std::vector<Count> counts;
  for (const std::string& name : countNames(m)) {
    Count c{index(name), {}, {}};
    // "Swarm.holding.obstacle.1" counts knows.obstacle == 1; "Swarm.at.Move.2.3" pc.Move in {2, 3}.
    const bool holding = name.rfind("Swarm.holding.obstacle.", 0) == 0;
    std::string rest = name.substr(holding ? std::string("Swarm.holding.obstacle.").size() : std::string("Swarm.at.Move.").size());
    for (std::size_t dot; !rest.empty(); rest = dot == std::string::npos ? "" : rest.substr(dot + 1)) {
      dot = rest.find('.');
      c.values.push_back(std::stoi(rest.substr(0, dot)));
    }
    for (const std::string& r : robots) c.of.push_back(index(r + (holding ? ".knows.obstacle" : ".pc.Move")));
    counts.push_back(std::move(c));
  }
  ASSERT_GE(counts.size(), 2u);
  checker::Stepper stepper(m);
  std::set<checker::Stepper::State> seen{stepper.initial()};
  std::vector<checker::Stepper::State> pending{stepper.initial()};
  std::size_t nonZero = 0;
  while (!pending.empty()) {
    const checker::Stepper::State x = pending.back();
    pending.pop_back();
    for (const Count& c : counts) {
      std::int32_t n = 0;
      for (std::size_t r = 0; r < robots.size(); ++r) {
        const bool alive = x[index(robots[r] + ".alive")] != 0;
        n += alive && std::find(c.values.begin(), c.values.end(), x[c.of[r]]) != c.values.end() ? 1 : 0;
      }
      ASSERT_EQ(x[c.var], n) << m.variables[c.var].name << " in " << stepper.describe(x);
      nonZero += n > 0 ? 1 : 0;
    }
    for (auto& [choice, y] : stepper.successors(x)) {
      if (seen.insert(y).second) pending.push_back(std::move(y));
    }
  }
  EXPECT_GT(seen.size(), 100u);
  EXPECT_GT(nonZero, 100u) << "the counts do count something";
}

// The SMT engine assumes the counts' definitions only once it has proven them (they hold initially
// and together every step keeps them): with them it proves what the explicit search proves; a
// claimed definition that is not inductive is refused, and the verdicts stay sound without it.
TEST(TeamCounts, DefinitionsAreProvenBeforeTheSmtEngineAssumesThem) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const std::string dir = SEMO_SOURCE_DIR "/specs/examples/swarm/";
  auto mission = loadMission({dir + "swarm3.semo", dir + "strategy.xml", std::nullopt}, sources, diags);
  ASSERT_TRUE(mission.has_value());
  TranslationOptions counted;
  counted.countTeamsAbove = 2;
  std::optional<Translation> t = translateMission(*mission, counted, sources, diags);
  ASSERT_TRUE(t.has_value());
  const ir::Model& m = t->model;
  ASSERT_EQ(t->lowering.countDefinitions.size(), countNames(m).size());
  ASSERT_GE(countNames(m).size(), 2u);
  const checker::SearchResult explicitSearch = checker::checkSafety(m, checker::SearchLimits{});
  ASSERT_TRUE(explicitSearch.complete);

  checker::SmtOptions options;
  options.maxDepth = 1;  // the unbounded proofs do the work
  options.lemmas = t->lowering.countDefinitions;
  const checker::SmtResult proven = checker::checkSafetySmt(m, options);
  EXPECT_EQ(proven.lemmasProven, options.lemmas.size());
  ASSERT_EQ(proven.search.properties.size(), explicitSearch.properties.size());
  for (std::size_t j = 0; j < explicitSearch.properties.size(); ++j) {
    EXPECT_EQ(proven.search.properties[j].verdict, explicitSearch.properties[j].verdict) << explicitSearch.properties[j].name;
  }

  // "Nobody is ever inside the block" holds initially but no step keeps it: refused, with the rest.
  ir::VarId atBlock = 0;
  for (std::size_t v = 0; v < m.variables.size(); ++v) {
    if (m.variables[v].name == "Swarm.at.Move.2") atBlock = static_cast<ir::VarId>(v);
  }
  ASSERT_EQ(m.variables[atBlock].init, 0);
  options.lemmas.push_back(ir::Expr::binary(ir::Op::Eq, ir::Expr::var(atBlock), ir::Expr::constant(0)));
  options.ic3 = false;  // k-induction alone: without the definitions IC3 takes minutes on the ranges
  const checker::SmtResult refused = checker::checkSafetySmt(m, options);
  EXPECT_EQ(refused.lemmasProven, 0u);
  for (std::size_t j = 0; j < explicitSearch.properties.size(); ++j) {
    const checker::Verdict v = refused.search.properties[j].verdict;
    EXPECT_TRUE(v == checker::Verdict::Unknown || v == explicitSearch.properties[j].verdict) << explicitSearch.properties[j].name;
  }
}

}  // namespace
}  // namespace semo
