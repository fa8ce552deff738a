// Group formation for every crash set (Z3) on the seeded defects of specs/defects: the smallest
// crash set that breaks a block, and the budget a corrected block tolerates.
#include <gtest/gtest.h>

#include "semo/checker/group_formation.hpp"
#include "semo/semantics/load.hpp"

namespace semo::checker {
namespace {

std::vector<FormationVerdict> formation(const std::string& mission) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  const std::string dir = SEMO_SOURCE_DIR "/specs/defects/";
  std::optional<model::MissionModel> m = loadMission({dir + mission, dir + "strategy.xml", std::nullopt}, sources, diags);
  EXPECT_TRUE(m.has_value());
  if (!m) return {};
  return checkGroupFormation(*m);
}

TEST(GroupFormation, OneCrashBreaksABlockWithASingleCandidate) {
  // lone_lidar: only mapper carries a LaserDistanceSensor; crash <= 1 in Survey.
  std::vector<FormationVerdict> v = formation("lone_lidar.semo");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].budget, 1);
  EXPECT_FALSE(v[0].holds());
  EXPECT_EQ(v[0].tolerated, 0);
  EXPECT_EQ(v[0].breakingSet, std::vector<std::string>{"mapper"});
  ASSERT_EQ(v[0].unmetArms.size(), 1u);
  EXPECT_NE(v[0].unmetArms[0].find("LaserDistanceSensor"), std::string::npos);
}

TEST(GroupFormation, TheCorrectedBlockToleratesItsBudget) {
  std::vector<FormationVerdict> v = formation("lone_lidar_fixed.semo");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_TRUE(v[0].holds()) << v[0].tolerated;
  EXPECT_GE(v[0].tolerated, 1);
  EXPECT_EQ(v[0].breakingSet.size(), static_cast<std::size_t>(v[0].tolerated + 1));
}

TEST(GroupFormation, ARobotJoinsOneGroupOnly) {
  // Two groups that both want the one robot r0 (r1 fits neither): each group alone has a
  // candidate, but not both at once, so the block fails with every robot alive.
  model::MissionModel m;
  m.teams.push_back({});
  m.teams[0].name = "T";
  m.teams[0].robots = {0, 1};
  m.robots = {{"r0", 0, "A", 0, {}}, {"r1", 0, "B", 1, {}}};
  m.services.push_back({});
  m.services[0].name = "S";
  m.assumptions.crashBudget = {0};
  model::GroupBlock block;
  block.team = 0;
  block.service = 0;
  for (int k = 0; k < 2; ++k) {
    model::GroupArm arm;
    arm.names = {"A"};
    arm.candidates = {0};
    block.arms.push_back(std::move(arm));
  }
  m.groupBlocks.push_back(std::move(block));
  std::vector<FormationVerdict> v = checkGroupFormation(m);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].tolerated, -1);
  EXPECT_TRUE(v[0].breakingSet.empty());
  EXPECT_EQ(v[0].unmetArms.size(), 2u);
  EXPECT_FALSE(v[0].holds());
  // With r1 a candidate of the second group, both groups are staffed; one crash breaks it.
  m.groupBlocks[0].arms[1].candidates = {0, 1};
  v = checkGroupFormation(m);
  EXPECT_EQ(v[0].tolerated, 0);
  EXPECT_EQ(v[0].breakingSet.size(), 1u);
}

TEST(GroupFormation, AGroupNeedsTheMinimumSizeOfTheGroupServicesItRuns) {
  // One group of four candidates whose body runs a group service with min-robots = 3 (inside an
  // `if`): it tolerates one crash, not two; with the default of one robot it would tolerate three.
  model::MissionModel m;
  m.teams.push_back({});
  m.teams[0].name = "T";
  m.teams[0].robots = {0, 1, 2, 3};
  for (int r = 0; r < 4; ++r) m.robots.push_back({"r" + std::to_string(r), 0, "A", static_cast<model::Index>(r), {}});
  m.services.push_back({});
  m.services[0].name = "S";
  m.assumptions.crashBudget = {2};
  strategy::Service search;
  search.name = "search";
  search.kind = strategy::Service::Kind::Group;
  search.minRobots = 3;
  m.strategy.services.push_back(search);
  model::GroupBlock block;
  block.team = 0;
  block.service = 0;
  model::GroupArm arm;
  arm.names = {"A"};
  arm.candidates = {0, 1, 2, 3};
  model::Stmt branch;
  branch.kind = model::Stmt::Kind::If;
  branch.thenBody.emplace_back();
  branch.thenBody.back().kind = model::Stmt::Kind::CallGroupService;
  branch.thenBody.back().service = "search";
  branch.thenBody.back().strategyService = 0;  // as elaboration resolves it
  arm.body.push_back(std::move(branch));
  block.arms.push_back(std::move(arm));
  m.groupBlocks.push_back(std::move(block));
  std::vector<FormationVerdict> v = checkGroupFormation(m);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].tolerated, 1);
  EXPECT_FALSE(v[0].holds());
  EXPECT_EQ(v[0].breakingSet.size(), 2u);
  m.strategy.services[0].minRobots = 1;
  v = checkGroupFormation(m);
  // No crash set breaks it: a crash of all four leaves nobody to run the block, which holds
  // vacuously (specs/language.md), so every budget up to the team's size is tolerated.
  EXPECT_EQ(v[0].tolerated, 4);
  EXPECT_TRUE(v[0].holds());
  EXPECT_FALSE(v[0].vacuousAtBudget());
}

}  // namespace
}  // namespace semo::checker
