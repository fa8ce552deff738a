// End-to-end tests of `semo-verify replay`: the counterexamples `check --json` prints for the seeded
// defects of specs/defects (safety: invariants and deadlocks; liveness: lassos) happen in the
// running team, step for step, with the violation at the same step; the run's trace names the same
// rules; the picture renders; bad input is refused without output.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

namespace {

using namespace semo::e2e;

struct Defect {
  const char* name;  // test name
  const char* mission;
  const char* strategy;
  const char* property;
  const char* shows;  // what replay prints when it reproduces the violation
};

std::ostream& operator<<(std::ostream& o, const Defect& d) { return o << d.name; }

class ReplayDefect : public ::testing::TestWithParam<Defect> {};

// The counterexample of `property` in a `check --json` output.
const nlohmann::json* findCounterexample(const nlohmann::json& root, const std::string& property) {
  for (const nlohmann::json& p : root["properties"]) {
    if (p["name"] == property && p.contains("counterexample")) return &p["counterexample"];
  }
  return nullptr;
}

TEST_P(ReplayDefect, TheViolationHappensAtTheSameStep) {
  const Defect& d = GetParam();
  const fs::path dir = workDir(std::string("replay_") + d.name);
  const std::string checked = (dir / "check.json").string();
  CliRun c = verify(std::string("check ") + d.mission + " -s " + d.strategy + " --json > '" + checked + "'", dir);
  ASSERT_EQ(c.exit, 1) << c.err;
  const nlohmann::json root = nlohmann::json::parse(slurp(checked));
  const nlohmann::json* cex = findCounterexample(root, d.property);
  ASSERT_NE(cex, nullptr) << d.property;
  const std::size_t steps = (*cex)["steps"].size();
  const std::string kind = (*cex)["kind"];

  const fs::path run = dir / "run.json", svg = dir / "run.svg";
  CliRun r = verify("replay '" + checked + "' --property '" + d.property + "' --save-trace '" + run.string() + "' --svg '" + svg.string() + "'", dir);
  ASSERT_EQ(r.exit, 1) << r.out << r.err;
  if (kind == "invariant") {
    EXPECT_NE(r.out.find("violated at step " + std::to_string(steps) + ","), std::string::npos) << r.out;
  }
  if (kind == "deadlock") {
    EXPECT_NE(r.out.find("deadlock at step " + std::to_string(steps) + ","), std::string::npos) << r.out;
  }
  EXPECT_NE(r.out.find(d.shows), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("NOT reproduced"), std::string::npos) << r.out;

  // The running team took the counterexample's rules, in its order (a lasso's loop again and again).
  const nlohmann::json t = nlohmann::json::parse(slurp(run));
  std::vector<std::string> taken;
  for (const nlohmann::json& e : t["events"]) {
    if (e["kind"] == "step" && e.contains("rule") && !e["rule"].get<std::string>().empty()) taken.push_back(e["rule"]);
  }
  ASSERT_GE(taken.size(), steps);
  for (std::size_t k = 0; k < steps; ++k) EXPECT_EQ(taken[k], (*cex)["steps"][k]["rule"]) << "step " << k + 1;
  if (kind == "lasso" && (*cex).contains("loopStart")) {
    const std::size_t loopStart = (*cex)["loopStart"].get<std::size_t>() - 1;  // 1-based in the JSON
    if (loopStart < steps) {
      EXPECT_EQ(taken.size(), steps + 2 * (steps - loopStart));  // the loop taken three times
      for (std::size_t k = steps; k < taken.size(); ++k) EXPECT_EQ(taken[k], taken[k - (steps - loopStart)]);
    }
  }
  // The picture marks the violation.
  const std::string picture = slurp(svg);
  EXPECT_NE(picture.find("class=\"violation\""), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Defects, ReplayDefect,
    ::testing::Values(
        Defect{"leader_timeout", "specs/defects/leader_timeout.semo", "specs/defects/leader_timeout_short.xml", "unique_leader[Relay]",
               "property unique_leader[Relay] is violated"},
        Defect{"double_receive", "specs/defects/double_receive.semo", "specs/defects/strategy.xml", "deadlock_freedom",
               "the team took 0 steps the model sees"},
        Defect{"flood", "specs/defects/flood.semo", "specs/defects/strategy.xml", "buffer_bounds[Rover.mapUpdate]",
               "property buffer_bounds[Rover.mapUpdate] is violated"},
        Defect{"early_clear", "specs/defects/early_clear.semo", "specs/defects/strategy.xml", "one_robot_in_aisle",
               "property one_robot_in_aisle is violated"},
        Defect{"blind_wait", "specs/defects/blind_wait.semo", "specs/defects/strategy.xml", "no_walking_into_blades",
               "property no_walking_into_blades is violated"},
        Defect{"lost_report", "specs/defects/lost_report.semo", "specs/defects/strategy.xml", "deadlock_freedom", "deadlock at step 1,"},
        Defect{"lone_lidar", "specs/defects/lone_lidar.semo", "specs/defects/strategy.xml", "group_formation[Map group (LaserDistanceSensor)]",
               "is violated"},
        Defect{"lost_recall", "specs/defects/liveness/lost_recall.semo", "specs/defects/liveness/strategy.xml", "mode_agreement[Crew]",
               "taken 3 times: after steps 5, 7, 9 the running team is back where the loop starts"},
        Defect{"orphaned_relay", "specs/defects/liveness/orphaned_relay.semo", "specs/defects/liveness/orphaned_relay_formation.xml",
               "leader_reelection[Relay]", "taken 3 times"},
        Defect{"stuck_gossip", "specs/defects/liveness/stuck_gossip.semo", "specs/defects/liveness/strategy.xml",
               "knowledge_convergence[mapField.blocked]", "the run may stay there for ever"}),
    [](const ::testing::TestParamInfo<Defect>& info) { return std::string(info.param.name); });

TEST(Replay, TheSameTraceGivesTheSameRunByteForByte) {
  const fs::path dir = workDir("replay_determinism");
  const std::string checked = (dir / "check.json").string();
  verify("check specs/defects/leader_timeout.semo -s specs/defects/leader_timeout_short.xml --json > '" + checked + "'", dir);
  for (const char* out : {"a", "b"}) {
    CliRun r = verify("replay '" + checked + "' --save-trace '" + (dir / (std::string(out) + ".json")).string() + "' --svg '" +
                          (dir / (std::string(out) + ".svg")).string() + "'",
                      dir);
    ASSERT_EQ(r.exit, 1) << r.out << r.err;
  }
  EXPECT_EQ(slurp(dir / "a.json"), slurp(dir / "b.json"));
  EXPECT_EQ(slurp(dir / "a.svg"), slurp(dir / "b.svg"));
}

TEST(Replay, ThePictureRenders) {
  if (std::string(SEMO_RSVG_CONVERT).empty()) GTEST_SKIP() << "rsvg-convert (librsvg2-bin) is not installed";
  const fs::path dir = workDir("replay_picture");
  const std::string checked = (dir / "check.json").string();
  verify("check specs/defects/liveness/orphaned_relay.semo -s specs/defects/liveness/orphaned_relay_formation.xml --json > '" + checked + "'", dir);
  CliRun r = verify("replay '" + checked + "' --svg '" + (dir / "run.svg").string() + "'", dir);
  ASSERT_EQ(r.exit, 1) << r.out << r.err;
  const std::string svg = slurp(dir / "run.svg");
  EXPECT_NE(svg.find("scout_0"), std::string::npos);
  EXPECT_NE(svg.find("class=\"crash\""), std::string::npos);
  const std::string command = "'" SEMO_RSVG_CONVERT "' '" + (dir / "run.svg").string() + "' -o '" + (dir / "run.png").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_GT(fs::file_size(dir / "run.png"), 5000U);
}

TEST(Replay, BadInputIsRefusedWithoutOutput) {
  const fs::path dir = workDir("replay_bad");
  const std::string out = " --save-trace '" + (dir / "out.json").string() + "' --svg '" + (dir / "out.svg").string() + "'";
  // Not a file.
  CliRun r = verify("replay '" + (dir / "missing.json").string() + "'" + out, dir);
  EXPECT_EQ(r.exit, 2);
  // Not JSON: a positioned error.
  { std::ofstream(dir / "broken.json") << "{\n  \"input\": \"specs/defects/flood.semo\",\n  oops\n}\n"; }
  r = verify("replay '" + (dir / "broken.json").string() + "'" + out, dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_NE(r.err.find("broken.json:3:3: error:"), std::string::npos) << r.err;
  // A counterexample of another model (the other strategy): the fingerprint differs.
  const std::string checked = (dir / "check.json").string();
  verify("check specs/defects/leader_timeout.semo -s specs/defects/leader_timeout_short.xml --json > '" + checked + "'", dir);
  r = verify("replay '" + checked + "' specs/defects/leader_timeout.semo -s specs/defects/leader_timeout_ok.xml" + out, dir);
  EXPECT_EQ(r.exit, 2) << r.out;
  EXPECT_NE(r.err.find("fingerprint"), std::string::npos) << r.err;
  // A single counterexample object does not say which mission it belongs to.
  {
    const nlohmann::json root = nlohmann::json::parse(slurp(checked));
    std::ofstream(dir / "one.json") << (*findCounterexample(root, "unique_leader[Relay]")).dump(2);
  }
  r = verify("replay '" + (dir / "one.json").string() + "'" + out, dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_NE(r.err.find("give MISSION and --strategy"), std::string::npos) << r.err;
  // ... and with them it replays.
  r = verify("replay '" + (dir / "one.json").string() + "' specs/defects/leader_timeout.semo -s specs/defects/leader_timeout_short.xml", dir);
  EXPECT_EQ(r.exit, 1) << r.out << r.err;
  // A property with no counterexample in the file.
  r = verify("replay '" + checked + "' --property no_such_property" + out, dir);
  EXPECT_EQ(r.exit, 2);
  // The picture over the counterexample it replays: refused, the counterexample kept.
  const std::string before = slurp(checked);
  r = verify("replay '" + checked + "' --save-trace '" + (dir / "out.json").string() + "' --svg '" + checked + "'", dir);
  EXPECT_EQ(r.exit, 2) << r.out;
  EXPECT_NE(r.err.find("is an input of this run"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(checked), before);
  EXPECT_FALSE(fs::exists(dir / "out.json"));
  EXPECT_FALSE(fs::exists(dir / "out.svg"));
}

}  // namespace
