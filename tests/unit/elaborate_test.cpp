// Elaboration of the shipped examples into a MissionModel.
#include <gtest/gtest.h>

#include <algorithm>

#include "semo/semantics/load.hpp"

namespace semo {
namespace {

struct ElaboratedMission {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<model::MissionModel> model;
};

std::unique_ptr<ElaboratedMission> elaborateSpec(const std::string& mission, const std::string& strategy) {
  auto l = std::make_unique<ElaboratedMission>();
  l->model = loadMission({SEMO_SOURCE_DIR "/" + mission, SEMO_SOURCE_DIR "/" + strategy, std::nullopt}, l->sources, l->diags);
  return l;
}

std::vector<std::string> robotNames(const model::MissionModel& m, const std::vector<model::Index>& robots) {
  std::vector<std::string> out;
  for (model::Index r : robots) out.push_back(m.robots[r].name);
  return out;
}

class Scouting : public ::testing::Test {
 protected:
  void SetUp() override {
    loaded_ = elaborateSpec("specs/examples/scouting/scouting.semo", "specs/examples/scouting/strategy.xml");
    ASSERT_TRUE(loaded_->model.has_value());
  }
  const model::MissionModel& m() const { return *loaded_->model; }
  std::unique_ptr<ElaboratedMission> loaded_;
};

TEST_F(Scouting, ExpandsRobotArrays) {
  ASSERT_EQ(m().teams.size(), 2u);
  const model::Team& slave = m().teams[m().findTeam("SlaveTeam")];
  EXPECT_EQ(robotNames(m(), slave.robots), (std::vector<std::string>{"burger_0", "burger_1", "ev3_0", "ev3_1"}));
  EXPECT_EQ(m().robots[m().findRobot("ev3_1")].type, "Ev3Robot");
  EXPECT_EQ(m().robots[m().findRobot("ev3_1")].indexInTeam, 3u);
  EXPECT_EQ(m().robots[m().findRobot("irobot")].team, m().findTeam("MasterTeam"));
}

TEST_F(Scouting, ResolvesGroupCandidates) {
  model::Index slave = m().findTeam("SlaveTeam");
  model::Index search = m().findService(slave, "Search");
  auto block = std::find_if(m().groupBlocks.begin(), m().groupBlocks.end(),
                            [&](const model::GroupBlock& b) { return b.service == search; });
  ASSERT_NE(block, m().groupBlocks.end());
  EXPECT_FALSE(block->isLeaderBlock);
  ASSERT_EQ(block->arms.size(), 2u);
  EXPECT_EQ(robotNames(m(), block->arms[0].candidates), (std::vector<std::string>{"burger_0", "burger_1"}));
  EXPECT_EQ(block->arms[1].kind, model::GroupArm::Kind::Others);
  EXPECT_EQ(robotNames(m(), block->arms[1].candidates), (std::vector<std::string>{"ev3_0", "ev3_1"}));
}

TEST_F(Scouting, LeaderBlockTakesItsSelectionFromTheStrategy) {
  model::Index report = m().findService(m().findTeam("SlaveTeam"), "ReportPapers");
  auto block = std::find_if(m().groupBlocks.begin(), m().groupBlocks.end(),
                            [&](const model::GroupBlock& b) { return b.service == report; });
  ASSERT_NE(block, m().groupBlocks.end());
  EXPECT_TRUE(block->isLeaderBlock);
  EXPECT_TRUE(block->leader.fromStrategy);
  EXPECT_EQ(block->leader.algorithm, strategy::LeaderSelection::Algorithm::Bully);
  EXPECT_LT(block->leader.heartbeatMillis, block->leader.timeoutMillis);
  EXPECT_EQ(robotNames(m(), block->arms[0].candidates), (std::vector<std::string>{"ev3_0", "ev3_1"}));
  // Followers are every robot of the team: any of them may not be the leader.
  EXPECT_EQ(block->arms[1].candidates.size(), 4u);
}

TEST_F(Scouting, ModesTransitionsAndEvents) {
  const model::Team& slave = m().teams[m().findTeam("SlaveTeam")];
  EXPECT_EQ(m().modes[slave.initialMode].name, "AUTODRIVE_MODE");
  for (model::Index md : slave.modes) EXPECT_TRUE(m().modes[md].reachable) << m().modes[md].name;
  const model::Mode& autodrive = m().modes[m().findMode(m().findTeam("SlaveTeam"), "AUTODRIVE_MODE")];
  ASSERT_EQ(autodrive.settings.size(), 2u);
  ASSERT_EQ(autodrive.transitions.size(), 2u);
  const model::Event& e = slave.events[autodrive.transitions[0].event];
  EXPECT_EQ(e.name, "find_color_paper");
  EXPECT_FALSE(e.thrownAt.empty());
  EXPECT_FALSE(e.caughtAt.empty());
  EXPECT_EQ(m().modes[autodrive.transitions[0].target].name, "SEARCH_MODE");
  for (const model::CompositeService& s : m().services) EXPECT_TRUE(s.used) << s.name;
}

TEST_F(Scouting, StatementsAreResolved) {
  const model::CompositeService& approach = m().services[m().findService(m().findTeam("SlaveTeam"), "ApproachDestination")];
  ASSERT_EQ(approach.body.size(), 2u);
  EXPECT_EQ(approach.body[0].kind, model::Stmt::Kind::CallPrimitive);
  EXPECT_EQ(approach.body[0].args[0].text, "Paris palace of congress");
  EXPECT_EQ(approach.body[1].kind, model::Stmt::Kind::Throw);
  ASSERT_TRUE(approach.repeat.has_value());
  EXPECT_EQ(approach.repeat->cond->lhs.valueKind, model::ValueKind::Sensed);
  model::Index message = m().findTopic(m().findTeam("SlaveTeam"), "Message");
  ASSERT_NE(message, model::kNone);
  EXPECT_FALSE(m().topics[message].reliable);
  EXPECT_TRUE(m().topics[message].written && m().topics[message].read);
  EXPECT_EQ(m().topics[message].buffer, 2);
  model::Index report = m().findTopic(m().findTeam("SlaveTeam"), "paperReport");
  ASSERT_NE(report, model::kNone);
  EXPECT_FALSE(m().topics[report].reliable) << "published to the master, not sent";
  EXPECT_TRUE(m().topics[report].written && m().topics[report].read);
}

TEST_F(Scouting, AssumptionsAndProperties) {
  const model::Assumptions& a = m().assumptions;
  EXPECT_EQ(a.crashBudget[m().findTeam("SlaveTeam")], 1);
  EXPECT_EQ(a.crashBudget[m().findTeam("MasterTeam")], 0);
  EXPECT_TRUE(a.losePublish);
  EXPECT_TRUE(a.loseEvents);
  EXPECT_FALSE(a.loseKnowledge);
  EXPECT_TRUE(a.fairLoss);
  EXPECT_EQ(a.checks.size(), 7u);
  ASSERT_EQ(m().properties.size(), 1u);
  const model::Ltl& f = *m().properties[0].formula;
  EXPECT_EQ(f.kind, model::Ltl::Kind::Always);
}

TEST(Elaborate, SwarmOfTenHasTenRobotsInItsGroup) {
  auto l = elaborateSpec("specs/examples/swarm/swarm10.semo", "specs/examples/swarm/strategy.xml");
  ASSERT_TRUE(l->model.has_value());
  EXPECT_EQ(l->model->robots.size(), 10u);
  ASSERT_FALSE(l->model->groupBlocks.empty());
  EXPECT_EQ(l->model->groupBlocks[0].arms[0].candidates.size(), 10u);
}

TEST(Elaborate, IncompleteFig2IsRejectedWithPositions) {
  auto l = elaborateSpec("specs/fig2.semo", "specs/examples/scouting/strategy.xml");
  EXPECT_FALSE(l->model.has_value());
  std::vector<std::string> errors;
  for (const Diagnostic& d : l->diags.diagnostics()) {
    if (d.severity == Severity::Error) {
      errors.push_back(std::to_string(d.range.begin.line) + ":" + std::to_string(d.range.begin.column) + " " + d.message);
    }
  }
  EXPECT_NE(std::find(errors.begin(), errors.end(), "18:15 undefined service 'CommOperator' in team 'SlaveTeam'"), errors.end());
  EXPECT_NE(std::find(errors.begin(), errors.end(), "23:35 undefined mode 'RC_MODE' of team 'SlaveTeam'"), errors.end());
  EXPECT_NE(std::find(errors.begin(), errors.end(), "24:9 main case for undefined mode 'SEARCH_MODE' of team 'SlaveTeam'"),
            errors.end());
}

}  // namespace
}  // namespace semo
