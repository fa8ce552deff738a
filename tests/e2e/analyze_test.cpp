// `analyze --svg`: the chart of P(within t) (tools/semo-verify/probability_chart.cpp) says what the
// numbers say, renders, is the same bytes on every run, and never replaces an input.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

namespace semo::e2e {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Analyze, TheChartShowsTheMinimumAndMaximumAndRenders) {
  const fs::path dir = workDir("analyze_chart");
  const std::string svg = (dir / "goal.svg").string();
  CliRun r = verify("analyze specs/examples/quantitative/gamble.ir --rounds 4 --svg '" + svg + "'", dir);
  ASSERT_EQ(r.exit, 0) << r.err;
  const std::string text = slurp(svg);
  EXPECT_EQ(count(text, "<polyline class=\"series\""), 2u);
  EXPECT_NE(text.find(">goal (min)</text>"), std::string::npos);
  EXPECT_NE(text.find(">goal (max)</text>"), std::string::npos);
  EXPECT_EQ(count(text, "stroke-dasharray"), 2u) << "the minimum's line and its legend are dashed";
  // The maximum reaches 0.5, 0.75, 0.875, 0.9375: its last point is high on the chart (y of 1 is 40,
  // of 0 is 370), the minimum's stays on the axis.
  EXPECT_NE(text.find("points=\"70.0,370.0 182.5,370.0 295.0,370.0 407.5,370.0 520.0,370.0\""), std::string::npos) << text;
  EXPECT_NE(text.find("points=\"70.0,370.0 182.5,205.0 295.0,122.5 407.5,81.2 520.0,60.6\""), std::string::npos) << text;
  if (std::string(SEMO_RSVG_CONVERT).empty()) GTEST_SKIP() << "rsvg-convert (librsvg2-bin) is not installed";
  const std::string command = "'" SEMO_RSVG_CONVERT "' '" + svg + "' -o '" + (dir / "goal.png").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_GT(fs::file_size(dir / "goal.png"), 5000U);
}

TEST(Analyze, TheSameModelGivesTheSameBytes) {
  const fs::path dir = workDir("analyze_determinism");
  for (const char* run : {"a", "b"}) {
    const std::string base = (dir / run).string();
    CliRun r = verify("analyze specs/examples/quantitative/leader_sync_4_4.ir --reward pick --json --svg '" + base + ".svg' > '" + base + ".json'", dir);
    ASSERT_EQ(r.exit, 0) << r.err;
  }
  EXPECT_EQ(slurp(dir / "a.json"), slurp(dir / "b.json"));
  EXPECT_EQ(slurp(dir / "a.svg"), slurp(dir / "b.svg"));
  EXPECT_NE(slurp(dir / "a.json").find("\"schemaVersion\": 1"), std::string::npos);
}

TEST(Analyze, TheChartNeverReplacesTheModel) {
  const fs::path dir = workDir("analyze_no_overwrite");
  const fs::path model = dir / "broadcast.ir";
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/examples/quantitative/broadcast.ir", model);
  const std::string before = slurp(model);
  CliRun r = verify("analyze '" + model.string() + "' --svg '" + model.string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_EQ(slurp(model), before);
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// swarm10's round model has 46,592 states per finder: with --max-states 1000 it is estimated from
// simulated runs instead, labelled so, and each P(within t) lies within its band of the exact one;
// the same seed gives the same bytes, and --runs 0 gives up with exit 3 instead.
TEST(Analyze, BeyondTheStateLimitTheSpreadIsEstimatedWithinItsBand) {
  const fs::path dir = workDir("analyze_sampled");
  const std::string mission = "specs/examples/swarm/swarm10.semo --strategy specs/examples/swarm/strategy.xml --loss-prob 0.6 --rounds 4";
  CliRun exact = verify("analyze " + mission + " --json", dir);
  ASSERT_EQ(exact.exit, 0) << exact.err;
  CliRun sampled = verify("analyze " + mission + " --json --max-states 1000 --runs 3000 --seed 5", dir);
  ASSERT_EQ(sampled.exit, 0) << sampled.err;
  EXPECT_NE(sampled.err.find("estimating from 3000 simulated runs per finder"), std::string::npos) << sampled.err;
  const nlohmann::json e = nlohmann::json::parse(exact.out).at("knowledge").at(0), s = nlohmann::json::parse(sampled.out).at("knowledge").at(0);
  EXPECT_FALSE(e.contains("statistical"));
  ASSERT_TRUE(s.contains("statistical")) << s.dump();
  const double band = s["statistical"]["withinBand"];
  EXPECT_NEAR(band, std::sqrt(std::log(40.0) / 6000.0), 1e-12);
  EXPECT_NE(s["method"].get<std::string>().find("not exact"), std::string::npos);
  double furthest = 0;
  for (const char* side : {"min", "max"}) {
    for (std::size_t t = 0; t <= 4; ++t) {
      const double d = std::fabs(s["withinRounds"][side][t].get<double>() - e["withinRounds"][side][t].get<double>());
      EXPECT_LE(d, band) << side << " t = " << t;
      furthest = std::max(furthest, d);
    }
  }
  EXPECT_GT(furthest, 0.0) << "estimated, not the exact figures";
  CliRun again = verify("analyze " + mission + " --json --max-states 1000 --runs 3000 --seed 5", dir);
  EXPECT_EQ(again.out, sampled.out);
  CliRun text = verify("analyze " + mission + " --max-states 1000 --runs 3000", dir);
  EXPECT_NE(text.out.find("ESTIMATED from 3000 simulated runs per finder"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("each +-0.0"), std::string::npos) << text.out;
  CliRun refused = verify("analyze " + mission + " --max-states 1000 --runs 0", dir);
  EXPECT_EQ(refused.exit, 3);
  EXPECT_NE(refused.err.find("--max-states raises the limit"), std::string::npos) << refused.err;
}

TEST(Analyze, ExportToPrismWritesTheModelAndItsQuestions) {
  const fs::path dir = workDir("export_prism");
  const std::string pm = (dir / "leader.pm").string(), props = (dir / "leader.props").string();
  CliRun r = verify("export specs/examples/quantitative/leader_sync_4_4.ir --prism -o '" + pm + "' --props '" + props + "'", dir);
  ASSERT_EQ(r.exit, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  const std::string model = slurp(pm), questions = slurp(props);
  EXPECT_NE(model.find("\ndtmc\n"), std::string::npos) << "812 states, one rule enabled in each";
  EXPECT_EQ(count(model, "\n  [] "), 5u) << "pick, read, done, retry, loop";
  EXPECT_NE(model.find("1/256 : (s1' = 1)"), std::string::npos) << "the fractions kept exact";
  // A conjunction is held as a balanced tree (specs/ir.md, "Limits of the reader"), bracketed as such.
  EXPECT_NE(model.find("label \"elected\" = (((s1 = 3) & (s2 = 3)) & ((s3 = 3) & (s4 = 3)));"), std::string::npos) << model;
  EXPECT_NE(questions.find("R{\"steps\"}=? [ F \"elected\" ];"), std::string::npos) << questions;
  // --props is for --prism only; neither output may replace the model.
  r = verify("export specs/examples/quantitative/gamble.ir --ir --props '" + props + "'", dir);
  EXPECT_EQ(r.exit, 2);
  const fs::path copy = dir / "gamble.ir";
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/examples/quantitative/gamble.ir", copy);
  const std::string before = slurp(copy);
  r = verify("export '" + copy.string() + "' --prism -o '" + pm + "' --props '" + copy.string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_EQ(slurp(copy), before);
}

// The computed distribution of the swarm's knowledge spread against the simulator's: 1,000 seeded
// runs of swarm3 with each copy of a message lost with probability 0.8 (three extra copies: a
// message is lost with 0.8^4 = 0.41), the rounds from the first gossip round after the obstacle is
// found to the last robot's learning, read from each run's trace. The empirical distribution must
// lie within the Dvoretzky-Kiefer-Wolfowitz band of the computed one (95 %: 0.043 for 1,000 runs),
// and a wrong model (loss 0.5) must fall outside it.
std::vector<double> computedSpread(const fs::path& dir, const std::string& loss, const std::string& finder) {
  const fs::path json = dir / ("analyze_" + loss + ".json");
  CliRun r = verify("analyze specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --loss-prob " + loss +
                        " --rounds 12 --json > '" + json.string() + "'",
                    dir);
  EXPECT_EQ(r.exit, 0) << r.err;
  const nlohmann::json out = nlohmann::json::parse(slurp(json));
  for (const nlohmann::json& f : out.at("knowledge").at(0).at("byFinder")) {
    if (f.at("robot") == finder) return f.at("withinRounds").get<std::vector<double>>();
  }
  ADD_FAILURE() << "no finder " << finder;
  return {};
}

TEST(Analyze, TheSwarmsSpreadAgreesWithTheSimulatorWithinTheDkwBand) {
  const fs::path dir = workDir("analyze_dkw");
  constexpr int kRuns = 1000;
  CliRun sim = verify("simulate specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --loss 0.8 --seeds 1.." +
                          std::to_string(kRuns) + " --no-dataflow --trace '" + (dir / "t_{seed}.json").string() + "'",
                      dir);
  ASSERT_EQ(sim.exit, 0) << sim.err;
  std::map<std::string, int> finders;
  std::vector<int> rounds;
  int foundTwice = 0;
  for (int seed = 1; seed <= kRuns; ++seed) {
    const fs::path trace = dir / ("t_" + std::to_string(seed) + ".json");
    const nlohmann::json events = nlohmann::json::parse(slurp(trace)).at("events");
    fs::remove(trace);
    std::string finder;
    double found = -1, firstRound = -1, last = -1;
    std::map<std::string, double> knows;
    for (const nlohmann::json& e : events) {
      auto text = [&e](const char* key) { return e.contains(key) && e[key].is_string() ? e[key].get<std::string>() : std::string(); };
      const std::string kind = text("kind"), label = text("label"), robot = text("robot");
      const double t = e.at("t");
      const bool finds = kind == "fact" && label.rfind("finds obstacle", 0) == 0;
      const bool learns = kind == "fact" && label.rfind("learns obstacle", 0) == 0;
      const bool dropped = kind == "drop" && label.find("obstacle gossip lost") != std::string::npos;
      if (finds && finder.empty()) finder = robot, found = t, knows[robot] = t;
      else if (finds && knows.count(robot) == 0) ++foundTwice, knows[robot] = t;
      if ((learns || dropped) && found >= 0 && t > found && firstRound < 0) firstRound = t;
      if (learns && knows.count(robot) == 0) knows[robot] = t, last = t;
    }
    ASSERT_FALSE(finder.empty()) << "seed " << seed << ": nobody found the obstacle";
    ASSERT_EQ(knows.size(), 3u) << "seed " << seed << ": not every robot learnt of it";
    ++finders[finder];
    rounds.push_back(static_cast<int>(std::lround((last - firstRound) / 0.2)) + 1);  // gossip every 200 ms
  }
  ASSERT_EQ(finders.size(), 1u) << "the same robot finds the obstacle in every run";
  EXPECT_EQ(foundTwice, 0) << "a robot found it itself before it was told";
  const double band = std::sqrt(std::log(2 / 0.05) / (2.0 * kRuns));
  auto distance = [&](const std::vector<double>& cdf) {
    double worst = 0;
    for (std::size_t t = 1; t < cdf.size(); ++t) {
      const double measured = static_cast<double>(std::count_if(rounds.begin(), rounds.end(), [t](int r) { return r <= static_cast<int>(t); })) / kRuns;
      worst = std::max(worst, std::fabs(measured - cdf[t]));
    }
    return worst;
  };
  const std::string robot = finders.begin()->first;
  const double right = distance(computedSpread(dir, "0.8", robot));
  EXPECT_LT(right, band) << "the simulator's spread is not the computed one";
  const double wrong = distance(computedSpread(dir, "0.5", robot));
  EXPECT_GT(wrong, band) << "the comparison cannot tell loss 0.8 from 0.5";
  std::cout << "DKW band " << band << ": loss 0.8 at " << right << ", loss 0.5 at " << wrong << "\n";
}

}  // namespace
}  // namespace semo::e2e
