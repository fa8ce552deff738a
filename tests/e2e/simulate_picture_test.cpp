// `simulate --svg` read back: the picture says what the trace says. The timeline's leader bars are
// the summary's leader changes (robot, block, from when, to its crash), each robot's role in every
// group block it takes part in is on that block's lane, and no label of the world covers another
// or a mark. The bars are read from the rectangles' positions on the time axis, not from their
// tooltips.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli_run.hpp"

// Named, not anonymous: the unity build compiles this file with the other simulate tests.
namespace semo::e2e::picture {

const std::string kScouting = "specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml";

double attribute(const std::string& element, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(element, m, std::regex(" " + name + "=\"([-0-9.]+)\""))) return NAN;
  return std::stod(m[1].str());
}

struct Bar {
  std::string robot, block, role;
  double from = 0, to = 0;  // seconds, from the rectangle's x and width on the time axis
};

// Every role band of the picture, its times read from where it is drawn.
std::vector<Bar> roleBars(const std::string& svg, double duration) {
  std::smatch axis;
  EXPECT_TRUE(std::regex_search(svg, axis, std::regex("<line class=\"time-axis\"[^>]*>")));
  const double x1 = attribute(axis[0].str(), "x1"), x2 = attribute(axis[0].str(), "x2");
  auto time = [&](double x) { return (x - x1) / (x2 - x1) * duration; };
  std::vector<Bar> bars;
  static const std::regex band("<rect class=\"role-band\"[^>]*><title>([^,<]+), ([^:<]+): ([^<(]+) \\(");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), band); it != std::sregex_iterator(); ++it) {
    const std::string rect = (*it)[0].str();
    const double x = attribute(rect, "x"), w = attribute(rect, "width");
    bars.push_back({(*it)[1].str(), (*it)[2].str(), (*it)[3].str(), time(x), time(x + w)});
  }
  return bars;
}

TEST(SimulatePicture, TheLeaderBarsAreTheSummarysLeaderChanges) {
  const fs::path dir = workDir("picture_leaders");
  CliRun r = verify("simulate " + kScouting + " --crash leader@5s --svg '" + (dir / "run.svg").string() + "' --trace '" +
                        (dir / "run.json").string() + "'",
                    dir);
  ASSERT_EQ(r.exit, 0) << r.err;
  // Which robot `leader@5s` hit is said, and so is every file written.
  EXPECT_TRUE(std::regex_search(r.out, std::regex("faults: crash leader at 5 s \\(ev3_[01], leader of SlaveTeam\\.Report\\.ReportPapers#[0-9]+\\)")))
      << r.out;
  EXPECT_NE(r.err.find("semo-verify simulate: wrote " + (dir / "run.svg").string() + "\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("semo-verify simulate: wrote " + (dir / "run.json").string() + "\n"), std::string::npos) << r.err;

  const nlohmann::json trace = nlohmann::json::parse(slurp(dir / "run.json"));
  const double duration = trace["duration"];
  std::map<std::string, double> crashed;
  for (const auto& e : trace["events"]) {
    if (e["kind"] == "crash") crashed[e["robot"].get<std::string>()] = e["t"];
  }
  ASSERT_EQ(crashed.size(), 1u);
  const std::vector<Bar> bars = roleBars(slurp(dir / "run.svg"), duration);
  std::vector<Bar> leaders;
  for (const Bar& b : bars) {
    if (b.role.rfind("leader of ", 0) == 0) leaders.push_back(b);
  }
  const double pixel = duration / 800;  // a bar's ends are drawn to the hundredth of a pixel
  const auto& changes = trace["summary"]["leaderChanges"];
  ASSERT_GE(changes.size(), 3u) << "two leader blocks elect, and the crashed leader is replaced";
  for (const auto& c : changes) {
    const std::string to = c["to"], block = c["block"];
    const double t = c["t"];
    const auto bar = std::find_if(leaders.begin(), leaders.end(), [&](const Bar& b) {
      return b.robot == to && b.block == block && std::abs(b.from - t) <= 2 * pixel;
    });
    ASSERT_NE(bar, leaders.end()) << "no bar for " << to << " leading " << block << " from " << t << " s";
    // A leader that crashed leads until its crash, and not after.
    if (crashed.count(to) != 0 && crashed[to] > t) {
      EXPECT_NEAR(bar->to, crashed[to], 2 * pixel) << to;
    }
  }
  // Every leader bar is one of the summary's changes: none the summary does not know.
  for (const Bar& b : leaders) {
    const bool known = std::any_of(changes.begin(), changes.end(), [&](const nlohmann::json& c) {
      return c["to"] == b.robot && c["block"] == b.block && std::abs(b.from - c["t"].get<double>()) <= 2 * pixel;
    });
    const bool again = b.from > 0 && std::any_of(leaders.begin(), leaders.end(), [&](const Bar& o) {
      return &o != &b && o.robot == b.robot && o.block == b.block && std::abs(o.to - b.from) <= 2 * pixel;
    });
    EXPECT_TRUE(known || again) << b.robot << " leads " << b.block << " from " << b.from << " s in the picture only";
  }
  // The robot that took over holds a role in three blocks at once, each on its own lane.
  const std::string heir = changes.back()["to"];
  std::set<std::string> blocks;
  for (const Bar& b : bars) {
    if (b.robot == heir && b.from < 10 && b.to > 10) blocks.insert(b.block);
  }
  EXPECT_EQ(blocks.size(), 3u) << heir;
}

struct Box {
  std::string what;
  double x0, y0, x1, y1;
};

// The labels of the world as drawn: text boxes measured as the renderer measures them (0.65 of the
// font size per character), and the marks they must not cover.
std::vector<Box> worldBoxes(const std::string& svg, std::vector<Box>& marks) {
  const std::string world = svg.substr(0, svg.find("<g class=\"timeline\">"));
  std::vector<Box> labels;
  static const std::regex text("<text class=\"(robot-label|place-label|fact-label|obstacle-label)\"[^>]*>([^<]*)</text>");
  for (auto it = std::sregex_iterator(world.begin(), world.end(), text); it != std::sregex_iterator(); ++it) {
    const std::string element = (*it)[0].str();
    const std::string content = std::regex_replace((*it)[2].str(), std::regex("&[a-z]+;"), "?");
    const double x = attribute(element, "x"), y = attribute(element, "y"), size = attribute(element, "font-size");
    labels.push_back({content, x, y - size * 0.8, x + static_cast<double>(content.size()) * size * 0.65, y + size * 0.25});
  }
  static const std::regex cross("<path class=\"crash-pose\" d=\"M([-0-9.]+),([-0-9.]+) L([-0-9.]+),([-0-9.]+)");
  for (auto it = std::sregex_iterator(world.begin(), world.end(), cross); it != std::sregex_iterator(); ++it) {
    marks.push_back({"crash cross", std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4])});
  }
  return labels;
}

bool overlap(const Box& a, const Box& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }

void noLabelCoversAnother(const std::string& mission, const std::string& args, const std::string& name) {
  const fs::path dir = workDir(name);
  CliRun r = verify("simulate " + mission + " " + args + " --svg '" + (dir / "run.svg").string() + "'", dir);
  ASSERT_EQ(r.exit, 0) << r.err;
  std::vector<Box> marks;
  const std::vector<Box> labels = worldBoxes(slurp(dir / "run.svg"), marks);
  ASSERT_GE(labels.size(), 5u);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    for (std::size_t j = i + 1; j < labels.size(); ++j) {
      EXPECT_FALSE(overlap(labels[i], labels[j])) << "'" << labels[i].what << "' and '" << labels[j].what << "'";
    }
    for (const Box& m : marks) EXPECT_FALSE(overlap(labels[i], m)) << "'" << labels[i].what << "' on a " << m.what;
  }
}

// Scouting: three robots end at the base camp, a place is named there, a robot crashes on its way.
TEST(SimulatePicture, NoLabelOfTheScoutingWorldCoversAnother) { noLabelCoversAnother(kScouting, "--crash leader@5s", "picture_labels_scouting"); }
TEST(SimulatePicture, NoLabelOfTheSwarmsWorldCoversAnother) {
  noLabelCoversAnother("specs/examples/swarm/swarm10.semo -s specs/examples/swarm/strategy.xml", "--crash legged_3@2s", "picture_labels_swarm");
}

}  // namespace semo::e2e::picture
