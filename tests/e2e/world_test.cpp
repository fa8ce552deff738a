// End-to-end tests of `semo-verify world`: for every shipped example mission it writes a world that
// `simulate` takes as it is (the reader's and the simulator's checks), with a start per robot, the
// places the mission names, a site per fact of its knowledge, robots apart and everything inside the
// arena; the same inputs give the same bytes; it never writes over an input; a bad mission gives a
// positioned error, exit 2 and no file.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

using namespace semo::e2e;
using nlohmann::json;

struct Example {
  std::string folder, mission;
  std::size_t robots = 0;
  std::set<std::string> places;  // that the mission names
  std::size_t facts = 0;         // of its group services' knowledge
  std::set<std::string> values;  // the sensed values it reads
};

// What each shipped mission needs of a world, from its text and its strategy.
const std::vector<Example>& examples() {
  static const std::vector<Example> all = {
      {"scouting", "scouting", 5, {"Paris palace of congress", "base camp"}, 3,
       {"SlaveTeam.not_arrived", "SlaveTeam.lightness", "SlaveTeam.operator_cmd", "MasterTeam.arrived", "MasterTeam.bumper_pressed",
        "MasterTeam.cliff_detected"}},
      {"chase", "chase", 6, {}, 0, {"BlueTeam.red_distance"}},
      {"deployment", "deployment", 6, {"survey area"}, 4, {}},
      {"patrol", "patrol", 6, {"warehouse"}, 4, {"Guards.target_range", "Guards.bumped"}},
      {"swarm", "swarm3", 3, {"start line"}, 1, {}},
      {"swarm", "swarm10", 10, {"start line"}, 1, {}},
      {"swarm", "swarm1000", 1000, {"start line"}, 1, {}},
  };
  return all;
}

std::string inputs(const Example& e) {
  return "specs/examples/" + e.folder + "/" + e.mission + ".semo --strategy specs/examples/" + e.folder + "/strategy.xml";
}

struct Point {
  double x = 0, y = 0;
};
Point point(const json& p) { return {p.at(0).get<double>(), p.at(1).get<double>()}; }

// The world is what the example needs, and laid out: robots apart, everything within the arena.
void expectLaidOut(const Example& e, const json& w) {
  EXPECT_EQ(w.at("format"), "semo-world");
  EXPECT_EQ(w.at("version"), 1);
  const Point low = point(w.at("arena").at("from")), high = point(w.at("arena").at("to"));
  auto inside = [&](Point p) { return p.x > low.x && p.y > low.y && p.x < high.x && p.y < high.y; };
  std::vector<Point> robots;
  for (const auto& [name, start] : w.at("robots").items()) {
    if (name.front() == '_') continue;
    robots.push_back(point(start.at("at")));
    EXPECT_TRUE(inside(robots.back())) << name;
    EXPECT_TRUE(start.at("heading").is_number()) << name;
  }
  EXPECT_EQ(robots.size(), e.robots);
  // Neighbours in a ring are closest: the smallest distance over all pairs, on a sample for the
  // thousand robots (every pair would be half a million).
  double closest = 1e300;
  const std::size_t stride = robots.size() > 100 ? 7 : 1;
  for (std::size_t i = 0; i < robots.size(); i += stride) {
    for (std::size_t j = 0; j < robots.size(); ++j) {
      if (i != j) closest = std::min(closest, std::hypot(robots[i].x - robots[j].x, robots[i].y - robots[j].y));
    }
  }
  if (robots.size() > 1) {
    EXPECT_GE(closest, 0.3) << "two robots' centres closer than the smallest footprint";
  }
  std::set<std::string> places;
  for (const auto& [name, at] : w.at("places").items()) {
    if (name.front() == '_') continue;
    places.insert(name);
    EXPECT_TRUE(inside(point(at))) << name;
  }
  EXPECT_EQ(places, e.places);
  std::size_t facts = 0;
  for (const json& f : w.at("facts")) {
    ++facts;
    EXPECT_TRUE(inside(point(f.at("at")))) << f.dump();
    // Not under a robot: it is found by going there.
    for (const Point& r : robots) EXPECT_GT(std::hypot(r.x - point(f.at("at")).x, r.y - point(f.at("at")).y), f.at("radius").get<double>());
  }
  EXPECT_EQ(facts, e.facts);
  std::set<std::string> values;
  for (const auto& [name, source] : w.at("values").items()) {
    if (name.front() == '_') continue;
    values.insert(name);
    EXPECT_TRUE(source.contains("constant")) << name;
  }
  EXPECT_EQ(values, e.values);
  EXPECT_TRUE(w.contains("_")) << "the note saying what the file is and what to edit";
}

TEST(World, EveryExampleGetsAWorldThatSimulateRunsAsItIs) {
  const fs::path dir = workDir("examples");
  for (const Example& e : examples()) {
    SCOPED_TRACE(e.mission);
    const fs::path file = dir / (e.mission + ".world.json");
    CliRun written = verify("world " + inputs(e) + " -o '" + file.string() + "'", dir);
    ASSERT_EQ(written.exit, 0) << written.err;
    EXPECT_EQ(written.out, "");
    ASSERT_TRUE(fs::exists(file));
    expectLaidOut(e, json::parse(slurp(file)));
    // A thousand robots run at a fraction of real time, the others for long enough to move.
    const std::string duration = e.robots > 100 ? "1s --no-dataflow" : "10s";
    CliRun run = verify("simulate " + inputs(e) + " --world '" + file.string() + "' --duration " + duration, dir);
    EXPECT_EQ(run.exit, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("simulated "), std::string::npos) << run.out;
    EXPECT_EQ(run.err.find("error"), std::string::npos) << run.err;
  }
}

TEST(World, TheGridLayoutRunsToo) {
  const fs::path dir = workDir("grid");
  for (const Example& e : examples()) {
    if (e.robots > 100) continue;
    SCOPED_TRACE(e.mission);
    CliRun written = verify("world " + inputs(e) + " --layout grid", dir);
    ASSERT_EQ(written.exit, 0) << written.err;
    const json w = json::parse(written.out);
    expectLaidOut(e, w);
    for (const auto& [name, start] : w.at("robots").items()) EXPECT_EQ(start.at("heading"), 0) << name << ": ranks face +x";
    const fs::path file = dir / (e.mission + ".world.json");
    std::ofstream(file) << written.out;
    CliRun run = verify("simulate " + inputs(e) + " --world '" + file.string() + "' --duration 10s", dir);
    EXPECT_EQ(run.exit, 0) << run.out << run.err;
  }
}

// The swarm marches straight ahead: the fact site is on a robot's way, so the knowledge is found and
// shared, and the team turns back.
TEST(World, TheSwarmFindsTheFactOnItsWayAndTurnsBack) {
  const fs::path dir = workDir("swarm");
  const Example& swarm = examples()[5];
  for (const char* layout : {"ring", "grid"}) {
    SCOPED_TRACE(layout);
    const fs::path file = dir / (std::string(layout) + ".world.json");
    ASSERT_EQ(verify("world " + inputs(swarm) + " --layout " + layout + " -o '" + file.string() + "'", dir).exit, 0);
    CliRun run = verify("simulate " + inputs(swarm) + " --world '" + file.string() + "' --duration 20s --no-dataflow", dir);
    EXPECT_EQ(run.exit, 0) << run.err;
    EXPECT_TRUE(std::regex_search(run.out, std::regex("knowledge obstacle: every live robot holds the same facts from"))) << run.out;
    EXPECT_TRUE(std::regex_search(run.out, std::regex("legged_9: RETREAT_MODE at"))) << run.out;
  }
}

TEST(World, TheSameInputsGiveTheSameBytes) {
  const fs::path dir = workDir("determinism");
  for (const Example& e : {examples()[0], examples()[6]}) {
    SCOPED_TRACE(e.mission);
    CliRun a = verify("world " + inputs(e), dir);
    CliRun b = verify("world " + inputs(e), dir);
    ASSERT_EQ(a.exit, 0) << a.err;
    EXPECT_FALSE(a.out.empty());
    EXPECT_EQ(a.out, b.out);
    const fs::path file = dir / "written.json";
    ASSERT_EQ(verify("world " + inputs(e) + " -o '" + file.string() + "'", dir).exit, 0);
    EXPECT_EQ(slurp(file), a.out) << "-o writes what is printed";
    // Through another path to the same mission: the same world (the note names the file, not the path).
    CliRun elsewhere = verify("world ./" + inputs(e), dir);
    EXPECT_EQ(elsewhere.out, a.out);
  }
}

TEST(World, AnOutputOntoAnInputIsRefusedAndTheInputKept) {
  const fs::path dir = workDir("onto_input");
  const fs::path mission = dir / "swarm3.semo";
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/examples/swarm/swarm3.semo", mission);
  const std::string before = slurp(mission);
  for (const fs::path& onto : {mission, dir / "." / "swarm3.semo", dir / ".." / "onto_input" / "swarm3.semo"}) {
    SCOPED_TRACE(onto.string());
    CliRun r = verify("world '" + mission.string() + "' --strategy specs/examples/swarm/strategy.xml -o '" + onto.string() + "'", dir);
    EXPECT_EQ(r.exit, 2);
    EXPECT_NE(r.err.find("is an input of this run"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(slurp(mission), before);
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2) << "nothing but the mission and stderr.txt";
}

TEST(World, ABadMissionGivesAPositionedErrorAndNoFile) {
  const fs::path dir = workDir("bad_mission");
  const fs::path mission = dir / "bad.semo";
  std::ofstream(mission) << "Swarm: QuadrupedRobot legged[3]\n\nSwarm.Move.March {\n  marchInLine( }\n";
  const fs::path out = dir / "bad.world.json";
  CliRun r = verify("world '" + mission.string() + "' --strategy specs/examples/swarm/strategy.xml -o '" + out.string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"((^|\n)[^\n]*bad\.semo:4:\d+: error: )"))) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(r.out, "");
  // A mission calling for a robot type the strategy does not describe: the same, from the elaboration.
  std::ofstream(mission, std::ios::trunc) << "Swarm: NoSuchRobot legged[3]\nSwarm.Move.March { marchInLine() }\n"
                                             "Swarm.MARCH_MODE { set(Move, March) }\nSwarm.main { case (MARCH_MODE): default: mode = MARCH_MODE }\n";
  r = verify("world '" + mission.string() + "' --strategy specs/examples/swarm/strategy.xml", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(bad\.semo:1:\d+: error: )"))) << r.err;
  EXPECT_EQ(r.out, "") << "nothing printed as a world";
}

// A place named "_..." would be a note to the world reader, and "" no place at all: no world file can
// give them, so the command says so at the calls that name them, and writes nothing.
TEST(World, APlaceNoWorldFileCanHoldIsAnErrorAtItsCall) {
  const fs::path dir = workDir("unwritable_place");
  const fs::path mission = dir / "m.semo";
  std::ofstream(mission) << "Master: iRobotCreate irobot\n\nMaster.Go.Drive {\n  move(\"_hidden\")\n  move(\"\") }\n"
                            "Master.GO_MODE { set(Go, Drive) }\nMaster.main { case (GO_MODE): default: mode = GO_MODE }\n";
  const fs::path out = dir / "m.world.json";
  CliRun r = verify("world '" + mission.string() + "' --strategy specs/examples/scouting/strategy.xml -o '" + out.string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(m\.semo:4:3: error: move\("_hidden"\): no world file can hold this place)"))) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(m\.semo:5:3: error: move\(""\): no world file can hold this place)"))) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(World, AnUnknownLayoutIsRefused) {
  const fs::path dir = workDir("layout");
  CliRun r = verify("world " + inputs(examples()[4]) + " --layout hexagon", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_NE(r.err.find("--layout"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

}  // namespace
