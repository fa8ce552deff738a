// End-to-end tests of `semo-verify simulate`: the real CLI on the paper's two experiments in
// specs/examples, with conformance checked on every step, and the traces it writes read back.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <fstream>
#include <regex>
#include <string>

#include "cli_run.hpp"

namespace {

using namespace semo::e2e;

const std::string kScouting = "specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml";
const std::string kSwarm3 = "specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml";
const std::string kSwarm10 = "specs/examples/swarm/swarm10.semo -s specs/examples/swarm/strategy.xml";

// The paper's first experiment: the SlaveTeam's leader (an Ev3 in ReportPapers) crashes at 5 s.
TEST(SimulateScouting, LeaderCrashIsRepairedOnEverySeed) {
  const fs::path dir = workDir("scouting_seeds");
  CliRun r = verify("simulate " + kScouting + " --crash leader@5s --loss 0.2 --check-conformance --seeds 1..100", dir);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("mission completed: 100 of 100"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("conformance: 0 runs with a mismatch"), std::string::npos) << r.out;
  // The strategy: heartbeat every 500 ms, timeout 2 s; a new leader within timeout + one period.
  const double worst = number(r.out, "replaced within ([0-9.]+) s at worst");
  ASSERT_GE(worst, 0) << r.out;
  EXPECT_LE(worst, 2.5);
}

TEST(SimulateScouting, ReportsReachTheMasterAfterTheTakeover) {
  const fs::path dir = workDir("scouting_trace");
  CliRun r = verify("simulate " + kScouting + " --crash leader@5s --check-conformance --seed 7 --trace '" + (dir / "t.json").string() + "'", dir);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  const nlohmann::json trace = nlohmann::json::parse(slurp(dir / "t.json"));
  double takeover = -1, crash = -1;
  int reportsAfter = 0;
  for (const auto& e : trace["events"]) {
    const std::string kind = e["kind"], label = e.value("label", "");
    const double t = e["t"];
    if (kind == "crash") crash = t;
    if (kind == "step" && label.find("takes over") != std::string::npos) takeover = t;
    if (kind == "deliver" && e["robot"] == "irobot" && e.value("detail", "") == "SlaveTeam.paperReport" && takeover >= 0) ++reportsAfter;
  }
  EXPECT_DOUBLE_EQ(crash, 5.0);
  ASSERT_GT(takeover, crash);
  EXPECT_LE(takeover - crash, 2.5);
  EXPECT_GE(reportsAfter, 2) << "the new leader's reports reach the master";
  EXPECT_TRUE(trace["summary"]["completed"].get<bool>());
}

// A dark spell from 8 s to 20 s: the Burger leading the light watch sends the team into hiding and
// back, and keeps the watch through both mode changes (on-mode-change="keep" in the strategy). The
// conformance check compares the runtime's `leads` with the model's after every step, so a runtime
// that dropped the leadership at the mode change, as the model no longer does, would fail here.
TEST(SimulateScouting, TheLightWatchStaysWithItsLeaderThroughADarkSpell) {
  const fs::path dir = workDir("scouting_dark_spell");
  nlohmann::json world = nlohmann::json::parse(slurp(fs::path(SEMO_SOURCE_DIR) / "specs/examples/scouting/scouting.world.json"));
  world["values"]["SlaveTeam.lightness"] = {{"schedule", {{0, 650}, {8, 120}, {20, 650}}}};
  std::ofstream(dir / "dark.world.json") << world.dump(1);
  CliRun r = verify("simulate " + kScouting + " --world '" + (dir / "dark.world.json").string() + "' --duration 40s --check-conformance", dir);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("burger_[01]: HIDE_MODE at (8|9)\\.[0-9]+ s"))) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("burger_[01]: SEARCH_MODE at 2[0-9]\\.[0-9]+ s"))) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("leader of SlaveTeam\\.Light\\.WatchLight#[0-9]+: burger_[01] at [0-9.]+ s\n"))) << r.out;
  EXPECT_NE(r.out.find("every one a step the model allows"), std::string::npos) << r.out;
}

// leader:BLOCK chooses the block whose leader crashes; the faults line names the robot it hit.
TEST(SimulateScouting, ACrashOfTheLeaderOfANamedBlock) {
  const fs::path dir = workDir("scouting_named_leader");
  CliRun r = verify("simulate " + kScouting + " --crash leader:WatchLight@5s --check-conformance", dir);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("faults: crash leader:WatchLight at 5 s \\(burger_[01], leader of SlaveTeam\\.Light\\.WatchLight#[0-9]+\\)")))
      << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("leader of SlaveTeam\\.Light\\.WatchLight#[0-9]+: burger_[01] at [0-9.]+ s \\(after burger_[01]\\), [0-9.]+ s after burger_[01] crashed")))
      << r.out;
}

// The paper's second experiment: one robot sees the obstacle; knowledge sharing stops them all.
void swarmStopsBeforeTheDitch(const std::string& mission, const std::string& name) {
  const fs::path dir = workDir(name);
  CliRun r = verify("simulate " + mission + " --loss 0.2 --check-conformance --seeds 1..100", dir);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("mission completed: 100 of 100"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 runs where a robot reached one"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("conformance: 0 runs with a mismatch"), std::string::npos) << r.out;
  // The strategy retransmits each broadcast 3 times, so at 20 % a fact is lost with 0.2^4: rarely.
  // At 80 % many are lost, and the periodic broadcast still carries the sighting to every robot.
  CliRun heavy = verify("simulate " + mission + " --loss 0.8 --check-conformance --seeds 1..100", dir);
  ASSERT_EQ(heavy.exit, 0) << heavy.out << heavy.err;
  EXPECT_NE(heavy.out.find("0 runs where a robot reached one"), std::string::npos) << heavy.out;
  EXPECT_NE(heavy.out.find("conformance: 0 runs with a mismatch"), std::string::npos) << heavy.out;
  std::smatch lost;
  ASSERT_TRUE(std::regex_search(heavy.out, lost, std::regex("messages: [0-9,]+ sent, ([0-9,]+) lost in all"))) << heavy.out;
  EXPECT_NE(lost[1].str(), "0") << "the loss does happen";
  // And on positions, read back from one run's trace: every robot, every sample, west of the ditch.
  CliRun one = verify("simulate " + mission + " --loss 0.2 --check-conformance --seed 3 --trace '" + (dir / "t.json").string() + "'", dir);
  ASSERT_EQ(one.exit, 0) << one.out << one.err;
  const nlohmann::json trace = nlohmann::json::parse(slurp(dir / "t.json"));
  double eastmost = -1e9;
  for (const auto& sample : trace["poses"]) {
    for (const auto& pose : sample["robots"]) eastmost = std::max(eastmost, pose[0].get<double>());
  }
  EXPECT_LT(eastmost, 4.0 - 0.3) << "the ditch starts at x = 4";
  EXPECT_GT(eastmost, 2.5) << "they did march";
}

TEST(SimulateSwarm, ThreeRobotsStopBeforeTheObstacle) { swarmStopsBeforeTheDitch(kSwarm3, "swarm3"); }
TEST(SimulateSwarm, TenRobotsStopBeforeTheObstacle) { swarmStopsBeforeTheDitch(kSwarm10, "swarm10"); }

TEST(SimulateSwarm, WithoutSharingARobotWalksIntoTheObstacle) {
  const fs::path dir = workDir("swarm_no_sharing");
  CliRun r = verify("simulate specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy_no_sharing.xml --check-conformance "
                 "--world specs/examples/swarm/swarm3.world.json --trace '" + (dir / "t.json").string() + "'",
                 dir);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("mission: not completed"), std::string::npos) << r.out;
  const nlohmann::json trace = nlohmann::json::parse(slurp(dir / "t.json"));
  const auto& last = trace["poses"].back()["robots"];
  int atTheDitch = 0;
  for (const auto& pose : last) atTheDitch += pose[0].get<double>() > 4.0 - 0.12 ? 1 : 0;
  EXPECT_GE(atTheDitch, 1) << trace["poses"].back().dump();
}

TEST(SimulateDeterminism, SameSeedSameTraceBytes) {
  const fs::path dir = workDir("determinism");
  const std::string base = "simulate " + kScouting + " --crash leader@5s --loss 0.3 --check-conformance ";
  for (const char* name : {"a", "b"}) {
    CliRun r = verify(base + "--seed 11 --trace '" + (dir / name).string() + ".json' --svg '" + (dir / name).string() + ".svg'", dir);
    ASSERT_EQ(r.exit, 0) << r.out << r.err;
  }
  CliRun c = verify(base + "--seed 12 --trace '" + (dir / "c").string() + ".json'", dir);
  ASSERT_EQ(c.exit, 0);
  EXPECT_EQ(slurp(dir / "a.json"), slurp(dir / "b.json"));
  EXPECT_EQ(slurp(dir / "a.svg"), slurp(dir / "b.svg"));
  EXPECT_NE(slurp(dir / "a.json"), slurp(dir / "c.json")) << "another seed draws other latencies and losses";
}

TEST(SimulatePicture, RendersWithTrajectoriesTimelineAndCrash) {
  const fs::path dir = workDir("picture");
  CliRun r = verify("simulate " + kScouting + " --crash leader@5s --seed 1 --svg '" + (dir / "run.svg").string() + "'", dir);
  ASSERT_EQ(r.exit, 0) << r.err;
  const std::string svg = slurp(dir / "run.svg");
  auto count = [&](const std::string& cls) {
    std::size_t n = 0;
    for (std::size_t at = svg.find("class=\"" + cls + "\""); at != std::string::npos; at = svg.find("class=\"" + cls + "\"", at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("trajectory"), 5u) << "one per robot";
  EXPECT_GE(count("mode-band"), 8u);
  EXPECT_GE(count("crash"), 1u);
  EXPECT_GE(count("fact-site"), 3u);
  if (std::string(SEMO_RSVG_CONVERT).empty()) GTEST_SKIP() << "rsvg-convert is not installed";
  const fs::path png = dir / "run.png";
  const std::string command = "'" SEMO_RSVG_CONVERT "' -w 1000 '" + (dir / "run.svg").string() + "' -o '" + png.string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string bytes = slurp(png);
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(bytes[at])) << 24) | (static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 2])) << 8) | static_cast<unsigned>(static_cast<unsigned char>(bytes[at + 3]));
  };
  EXPECT_EQ(be32(16), 1000u);  // IHDR width
  EXPECT_GT(be32(20), 500u);   // height: the world and the timeline
}

TEST(SimulateBadInput, PositionedErrorsAndNothingWritten) {
  const fs::path dir = workDir("bad_input");
  {
    std::ofstream(dir / "bad.world.json") << "{\n  \"format\": \"semo-world\", \"version\": 1,\n  \"places\": {\"base camp\": [1]}\n}\n";
  }
  CliRun r = verify("simulate " + kScouting + " --world '" + (dir / "bad.world.json").string() + "' --trace '" + (dir / "t.json").string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_TRUE(std::regex_search(r.err, std::regex("bad\\.world\\.json:3:[0-9]+: error: "))) << r.err;
  EXPECT_FALSE(fs::exists(dir / "t.json"));
  CliRun crash = verify("simulate " + kScouting + " --crash nobody@5s --trace '" + (dir / "t.json").string() + "'", dir);
  EXPECT_EQ(crash.exit, 2);
  EXPECT_NE(crash.err.find("--crash 'nobody@5s': the mission has no robot 'nobody' (its robots: irobot, burger_0, burger_1, ev3_0, ev3_1; "
                           "or leader, leader:BLOCK)"),
            std::string::npos)
      << crash.err;
  CliRun block = verify("simulate " + kScouting + " --crash leader:Lamp@5s --trace '" + (dir / "t.json").string() + "'", dir);
  EXPECT_EQ(block.exit, 2);
  EXPECT_NE(block.err.find("no leader block is named like 'Lamp' (its leader blocks: SlaveTeam.Report.ReportPapers#2, SlaveTeam.Light.WatchLight#3)"),
            std::string::npos)
      << block.err;
  EXPECT_FALSE(fs::exists(dir / "t.json"));
  // A world without the places the mission drives to is refused before anything runs.
  {
    std::ofstream(dir / "empty.world.json") << "{\"format\": \"semo-world\", \"version\": 1}\n";
  }
  CliRun empty = verify("simulate " + kScouting + " --world '" + (dir / "empty.world.json").string() + "'", dir);
  EXPECT_EQ(empty.exit, 2);
  EXPECT_NE(empty.err.find("names a place the world does not have"), std::string::npos) << empty.err;
  EXPECT_NE(empty.err.find("no start pose for robot ev3_0"), std::string::npos) << empty.err;
  // The strategy reads the operator's command from one source for the team (source="team"): a
  // world that gives it by region would run what the checker did not assume.
  {
    std::string world = slurp(fs::path(SEMO_SOURCE_DIR) / "specs/examples/scouting/scouting.world.json");
    const std::string constant = "\"SlaveTeam.operator_cmd\": {\n      \"constant\": \"auto\"\n    }";
    ASSERT_NE(world.find(constant), std::string::npos);
    world.replace(world.find(constant), constant.size(),
                  "\"SlaveTeam.operator_cmd\": {\"regions\": [{\"circle\": {\"at\": [1, 1], \"radius\": 0.5}, \"value\": \"manual\"}], "
                  "\"otherwise\": \"auto\"}");
    std::ofstream(dir / "regions.world.json") << world;
  }
  CliRun regions = verify("simulate " + kScouting + " --world '" + (dir / "regions.world.json").string() + "' --trace '" + (dir / "t.json").string() + "'", dir);
  EXPECT_EQ(regions.exit, 2);
  EXPECT_NE(regions.err.find("SlaveTeam.operator_cmd is one source for the whole team (strategy: source=\"team\"), but the world gives it by region"),
            std::string::npos) << regions.err;
  EXPECT_FALSE(fs::exists(dir / "t.json"));
}

// No output replaces an input: not the mission, nor a URDF it reads, nor the world; the inputs are
// untouched and nothing is written.
TEST(SimulateBadInput, NeverWritesOverAnInput) {
  const fs::path dir = workDir("over_input");
  const fs::path mission = dir / "swarm3.semo", world = dir / "swarm3.world.json";
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/examples/swarm/swarm3.semo", mission, fs::copy_options::overwrite_existing);
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/examples/swarm/swarm3.world.json", world, fs::copy_options::overwrite_existing);
  const std::string missionText = slurp(mission), worldText = slurp(world);
  const std::string base = "simulate '" + mission.string() + "' -s specs/examples/swarm/strategy.xml --no-dataflow ";
  for (const std::string& target : {mission.string(), world.string(), (fs::path(SEMO_SOURCE_DIR) / "specs/robots/quadruped.urdf").string()}) {
    CliRun r = verify(base + "--trace '" + dir.string() + "/t.json' --svg '" + target + "'", dir);
    EXPECT_EQ(r.exit, 2) << target;
    EXPECT_NE(r.err.find("is an input of this run"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "t.json")) << "nothing written, not even the other output";
  }
  EXPECT_EQ(slurp(mission), missionText);
  EXPECT_EQ(slurp(world), worldText);
}

// --seeds writes one trace per run where {seed} says; without {seed} it is refused before running.
TEST(SimulateSeeds, OneTracePerSeedAndEachIsThatSeedsRun) {
  const fs::path dir = workDir("per_seed");
  const std::string base = "simulate specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --no-dataflow --loss 0.2 ";
  CliRun none = verify(base + "--seeds 1..3 --trace '" + (dir / "t.json").string() + "'", dir);
  EXPECT_EQ(none.exit, 2);
  EXPECT_NE(none.err.find("put {seed} in the name"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(dir / "t.json"));
  CliRun many = verify(base + "--seeds 4..6 --trace '" + (dir / "run{seed}.json").string() + "'", dir);
  ASSERT_EQ(many.exit, 0) << many.out << many.err;
  EXPECT_FALSE(fs::exists(dir / "run3.json"));
  EXPECT_FALSE(fs::exists(dir / "run7.json"));
  CliRun one = verify(base + "--seed 5 --trace '" + (dir / "single.json").string() + "'", dir);
  ASSERT_EQ(one.exit, 0) << one.out << one.err;
  EXPECT_EQ(slurp(dir / "run5.json"), slurp(dir / "single.json")) << "seed 5 of many is seed 5 alone";
  EXPECT_NE(slurp(dir / "run4.json"), slurp(dir / "run5.json"));
  EXPECT_TRUE(fs::exists(dir / "run6.json"));
}

}  // namespace
