// The lowering that comes with the IR (semantics/lowering.hpp): every variable's role and every
// rule's meaning, index for index with the IR, and consistent with what the IR rule itself says.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo {
namespace {

using lowering::RuleMeaning;
using lowering::VariableRole;

struct Loaded {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<model::MissionModel> mission;
  std::optional<Translation> translation;
};

std::unique_ptr<Loaded> load(const std::string& mission, const std::string& strategy) {
  auto l = std::make_unique<Loaded>();
  l->mission = loadMission({SEMO_SOURCE_DIR "/" + mission, SEMO_SOURCE_DIR "/" + strategy, std::nullopt}, l->sources, l->diags);
  if (l->mission) l->translation = translateMission(*l->mission, {}, l->sources, l->diags);
  return l;
}

// The conjuncts of a guard.
void conjuncts(const ir::Expr& e, std::vector<const ir::Expr*>& out) {
  if (e.op == ir::Op::And) {
    for (const ir::Expr& a : e.args) conjuncts(a, out);
  } else {
    out.push_back(&e);
  }
}

bool guardRequires(const ir::Expr& guard, ir::VarId var, std::int32_t value) {
  std::vector<const ir::Expr*> parts;
  conjuncts(guard, parts);
  return std::any_of(parts.begin(), parts.end(), [&](const ir::Expr* p) {
    return p->op == ir::Op::Eq && p->args[0].op == ir::Op::Var && static_cast<ir::VarId>(p->args[0].value) == var &&
           p->args[1].op == ir::Op::Const && p->args[1].value == value;
  });
}

ir::VarId pcVariable(const Translation& t, model::Index robot, std::size_t plan) {
  for (ir::VarId v = 0; v < t.lowering.variables.size(); ++v) {
    const VariableRole& r = t.lowering.variables[v];
    if (r.kind == VariableRole::Kind::Pc && r.robot == robot && r.index == plan) return v;
  }
  ADD_FAILURE() << "no pc variable";
  return 0;
}

class LoweringOfExamples : public testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(LoweringOfExamples, RolesAndMeaningsMatchTheIrIndexForIndex) {
  auto l = load(GetParam().first, GetParam().second);
  ASSERT_TRUE(l->translation.has_value()) << GetParam().first;
  const Translation& t = *l->translation;
  ASSERT_EQ(t.lowering.variables.size(), t.model.variables.size());
  ASSERT_EQ(t.lowering.rules.size(), t.model.rules.size());
  for (ir::VarId v = 0; v < t.model.variables.size(); ++v) {
    const VariableRole& role = t.lowering.variables[v];
    const bool perRobot = role.kind != VariableRole::Kind::Crashed && role.kind != VariableRole::Kind::Channel;
    EXPECT_EQ(t.model.variables[v].robot, perRobot ? static_cast<std::int32_t>(role.robot) : ir::kNoRobot) << t.model.variables[v].name;
  }
  std::size_t steps = 0;
  for (std::size_t i = 0; i < t.model.rules.size(); ++i) {
    const ir::Rule& rule = t.model.rules[i];
    const RuleMeaning& m = t.lowering.rules[i];
    if (m.kind != RuleMeaning::Kind::HeartbeatPeriod) {
      EXPECT_EQ(rule.robot, static_cast<std::int32_t>(m.robot)) << rule.name;
    }
    if (m.kind == RuleMeaning::Kind::ProgramStep) {
      ++steps;
      // The step starts where its meaning says: the guard asks for the robot's pc there.
      EXPECT_TRUE(guardRequires(rule.guard, pcVariable(t, m.robot, m.plan), static_cast<std::int32_t>(m.from))) << rule.name;
      const auto& code = t.lowering.programs[l->mission->robots[m.robot].team][m.plan].code;
      EXPECT_TRUE(code[m.from].controlPoint) << rule.name;
      EXPECT_LT(m.to, code.size()) << rule.name;
      EXPECT_FALSE(rule.origin.construct.empty()) << rule.name;
    }
  }
  EXPECT_GT(steps, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Examples, LoweringOfExamples,
    testing::Values(std::pair{"specs/examples/scouting/scouting.semo", "specs/examples/scouting/strategy.xml"},
                    std::pair{"specs/examples/swarm/swarm3.semo", "specs/examples/swarm/strategy.xml"},
                    std::pair{"specs/examples/chase/chase.semo", "specs/examples/chase/strategy.xml"},
                    std::pair{"specs/examples/deployment/deployment.semo", "specs/examples/deployment/strategy.xml"},
                    std::pair{"specs/examples/patrol/patrol.semo", "specs/examples/patrol/strategy.xml"},
                    std::pair{"specs/defects/flood.semo", "specs/defects/strategy.xml"}));

TEST(Lowering, ScoutingLeaderBlocksHaveElectionsHeartbeatsAndTakeovers) {
  auto l = load("specs/examples/scouting/scouting.semo", "specs/examples/scouting/strategy.xml");
  ASSERT_TRUE(l->translation.has_value());
  const Translation& t = *l->translation;
  const model::Index ev3_0 = l->mission->findRobot("ev3_0"), ev3_1 = l->mission->findRobot("ev3_1");
  const model::Index burger_0 = l->mission->findRobot("burger_0"), burger_1 = l->mission->findRobot("burger_1");
  // Two leader blocks: ReportPapers among the Ev3s (capable of ColorSensor), WatchLight among the
  // Burgers (capable of LightSensor).
  struct Counts {
    std::size_t elected = 0, notElected = 0, heartbeats = 0;
    std::vector<model::Index> takeovers;
  };
  std::map<model::Index, Counts> blocks;
  for (std::size_t i = 0; i < t.lowering.rules.size(); ++i) {
    const RuleMeaning& m = t.lowering.rules[i];
    for (const lowering::Guard& g : m.guards) {
      if (g.kind == lowering::Guard::Kind::Elected) ++blocks[g.index].elected;
      if (g.kind == lowering::Guard::Kind::NotElected) ++blocks[g.index].notElected;
    }
    if (m.kind == RuleMeaning::Kind::HeartbeatPeriod) {
      ++blocks[m.index].heartbeats;
      EXPECT_EQ(t.model.rules[i].kind, ir::RuleKind::Timer);
    }
    if (m.kind == RuleMeaning::Kind::Takeover) blocks[m.index].takeovers.push_back(m.robot);
  }
  ASSERT_EQ(blocks.size(), 2u);
  std::vector<std::vector<model::Index>> candidates;
  for (auto& [index, c] : blocks) {
    // Both candidates of a block form it (Elected) or follow (NotElected). Heartbeats are not lost
    // in this mission (no `loss heartbeats`), so one heartbeat rule per block; one takeover each.
    EXPECT_EQ(c.elected, 2u);
    EXPECT_EQ(c.notElected, 2u);
    EXPECT_EQ(c.heartbeats, 1u);
    std::sort(c.takeovers.begin(), c.takeovers.end());
    candidates.push_back(c.takeovers);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<std::vector<model::Index>> expected = {{ev3_0, ev3_1}, {burger_0, burger_1}};
  for (auto& e : expected) std::sort(e.begin(), e.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(candidates, expected);
}

TEST(Lowering, SwarmGroupServiceSharesKnowledgeAndEndsAtItsGoal) {
  auto l = load("specs/examples/swarm/swarm3.semo", "specs/examples/swarm/strategy.xml");
  ASSERT_TRUE(l->translation.has_value());
  const Translation& t = *l->translation;
  std::size_t learns = 0, discovers = 0, goals = 0;
  for (const RuleMeaning& m : t.lowering.rules) {
    if (m.kind == RuleMeaning::Kind::Learn) {
      ++learns;
      EXPECT_EQ(m.knowledge, "obstacle");
      EXPECT_EQ(m.peer, model::kNone);  // from any live teammate: the rule does not name one
      EXPECT_EQ(m.count, 1);  // one fact: a learner ends up holding it
    }
    if (m.kind == RuleMeaning::Kind::Discover) ++discovers;
    for (const lowering::Guard& g : m.guards) {
      if (g.kind != lowering::Guard::Kind::Goal) continue;
      ++goals;
      EXPECT_EQ(g.knowledge, "obstacle");
      EXPECT_EQ(g.count, 1);
    }
  }
  EXPECT_EQ(learns, 3u);     // each of 3 robots, to 1 fact
  EXPECT_EQ(discovers, 3u);  // one per robot
  EXPECT_EQ(goals, 3u);
}

}  // namespace
}  // namespace semo
