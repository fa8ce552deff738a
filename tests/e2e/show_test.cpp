// `check --trace-out` keeps the verdicts and counterexamples; `show` prints a counterexample again,
// exactly as check printed it, or narrowed to one robot, or with the whole state after each step.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

namespace semo::e2e {
namespace {

const std::string kDoubleReceive = "specs/defects/double_receive.semo -s specs/defects/strategy.xml";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Show, PrintsTheCounterexampleCheckPrinted) {
  const fs::path dir = workDir("show_same");
  const std::string saved = (dir / "cex.json").string();
  CliRun check = verify("check " + kDoubleReceive + " --trace-out '" + saved + "'", dir);
  ASSERT_EQ(check.exit, 1) << check.err;
  const nlohmann::json root = nlohmann::json::parse(slurp(saved));
  EXPECT_EQ(root.at("schemaVersion"), 1);
  EXPECT_EQ(root.at("exitCode"), 1);
  EXPECT_EQ(root.at("tool").get<std::string>().rfind("semo-verify ", 0), 0u);
  // The initial state with value names too, as the changes show them.
  const nlohmann::json& cex = root.at("properties").at(1).at("counterexample");
  EXPECT_EQ(cex.at("initialText").at("base.mode"), "COLLECT_MODE");
  EXPECT_EQ(cex.at("initial").at("base.mode"), 0);
  CliRun show = verify("show '" + saved + "'", dir);
  ASSERT_EQ(show.exit, 0) << show.err;
  ASSERT_NE(show.out.find("counterexample for deadlock_freedom (deadlock): 11 steps"), std::string::npos) << show.out;
  EXPECT_NE(check.out.find(show.out), std::string::npos) << "show prints the very text of check:\n" << show.out;
}

// A mission with a lint warning: check says it once, show (of what check kept) does not again.
TEST(Show, DoesNotRepeatTheMissionsWarnings) {
  const fs::path dir = workDir("show_no_warnings");
  const std::string saved = (dir / "cex.json").string();
  CliRun check = verify("check specs/defects/lone_lidar.semo -s specs/defects/strategy.xml --trace-out '" + saved + "'", dir);
  ASSERT_EQ(check.exit, 1) << check.err;
  ASSERT_NE(check.err.find("lone_lidar.semo:12:6: warning: "), std::string::npos) << check.err;
  EXPECT_NE(check.err.find("semo-verify check: wrote " + saved + "\n"), std::string::npos) << check.err;
  CliRun show = verify("show '" + saved + "'", dir);
  ASSERT_EQ(show.exit, 0) << show.err;
  EXPECT_EQ(show.err, "");
  EXPECT_NE(show.out.find("[mapper] crashes"), std::string::npos) << show.out;
}

TEST(Show, OneRobotsStepsWithTheOthersCounted) {
  const fs::path dir = workDir("show_robot");
  const std::string saved = (dir / "cex.json").string();
  ASSERT_EQ(verify("check " + kDoubleReceive + " --trace-out '" + saved + "'", dir).exit, 1);
  CliRun base = verify("show '" + saved + "' --robot base", dir);
  ASSERT_EQ(base.exit, 0) << base.err;
  EXPECT_EQ(count(base.out, "[base]"), 1u) << base.out;
  EXPECT_EQ(count(base.out, "[scout]") + count(base.out, "[mapper]"), 0u) << base.out;
  EXPECT_NE(base.out.find("  ... 2 steps of other robots or the network\n  3. [base] receives report"), std::string::npos) << base.out;
  EXPECT_NE(base.out.find("  ... 8 steps of other robots or the network\n  then no rule is enabled"), std::string::npos) << base.out;
  CliRun full = verify("show '" + saved + "' --full-state", dir);
  ASSERT_EQ(full.exit, 0) << full.err;
  EXPECT_EQ(count(full.out, "       state: "), 11u) << "the whole state after each of the 11 steps";
  EXPECT_EQ(count(full.out, "  initial state: base.mode=COLLECT_MODE"), 1u) << full.out;
  CliRun nobody = verify("show '" + saved + "' --robot nobody", dir);
  EXPECT_EQ(nobody.exit, 2);
  EXPECT_NE(nobody.err.find("its robots: base, scout, mapper"), std::string::npos) << nobody.err;
}

// A check of some properties (--prop) keeps the whole model's fingerprint: its trace reads back.
TEST(Show, ATraceFoundWithAPropertySelectionReadsBack) {
  const fs::path dir = workDir("show_selection");
  const std::string saved = (dir / "cex.json").string();
  ASSERT_EQ(verify("check " + kDoubleReceive + " --prop deadlock_freedom --trace-out '" + saved + "'", dir).exit, 1);
  CliRun show = verify("show '" + saved + "'", dir);
  EXPECT_EQ(show.exit, 0) << show.err;
  EXPECT_NE(show.out.find("counterexample for deadlock_freedom (deadlock): 11 steps"), std::string::npos) << show.out;
}

TEST(Show, TheTraceFileNeverReplacesAnInput) {
  const fs::path dir = workDir("show_no_overwrite");
  const fs::path mission = dir / "double_receive.semo";
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/defects/double_receive.semo", mission);
  const std::string before = slurp(mission);
  CliRun r = verify("check '" + mission.string() + "' -s specs/defects/strategy.xml --trace-out '" + mission.string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_EQ(slurp(mission), before);
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(Show, ATraceOfAnotherModelIsRefused) {
  const fs::path dir = workDir("show_other_model");
  const std::string saved = (dir / "cex.json").string();
  ASSERT_EQ(verify("check " + kDoubleReceive + " --trace-out '" + saved + "'", dir).exit, 1);
  CliRun r = verify("show '" + saved + "' specs/defects/double_receive_fixed.semo", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_NE(r.err.find("fingerprint"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// The message sequence chart: a lifeline per robot, a row per step, an arrow from the send to the
// receive, a lost message dashed and crossed, a crash crossed, mode changes boxed, a lasso's loop
// framed, knowledge facts named; check --msc and show --msc draw the same bytes; the pictures render.
TEST(Show, TheSequenceChartDrawsWhatTheTraceSays) {
  const fs::path dir = workDir("show_msc");
  const std::string saved = (dir / "cex.json").string(), chart = (dir / "dr.svg").string(), again = (dir / "again.svg").string();
  ASSERT_EQ(verify("check " + kDoubleReceive + " --trace-out '" + saved + "' --msc '" + chart + "'", dir).exit, 1);
  ASSERT_EQ(verify("show '" + saved + "' --msc '" + again + "'", dir).exit, 0);
  const std::string svg = slurp(chart);
  EXPECT_EQ(svg, slurp(again));
  EXPECT_EQ(count(svg, "class=\"lifeline\""), 3u) << "base, scout, mapper (no network lane: every step is a robot's)";
  EXPECT_EQ(count(svg, "class=\"step\""), 11u);
  EXPECT_EQ(count(svg, "class=\"message\""), 1u) << "scout's report to base";
  EXPECT_NE(svg.find("<title>ch.Scouts.report</title>"), std::string::npos);
  EXPECT_EQ(count(svg, ">HOME_MODE</text>"), 2u);
  EXPECT_NE(svg.find("3. [base] receives report  :24"), std::string::npos);
  EXPECT_EQ(svg.find("class=\"loop\""), std::string::npos);
  EXPECT_NE(svg.find("then no rule is enabled: a deadlock"), std::string::npos);

  const std::string lasso = (dir / "lasso.svg").string();
  ASSERT_EQ(verify("check tests/e2e/ir/retry_delivery_weak.ir --msc '" + lasso + "'", dir).exit, 1);
  const std::string loop = slurp(lasso);
  EXPECT_EQ(count(loop, "class=\"message lost\""), 1u) << "sent, then lost by the receiver";
  EXPECT_EQ(count(loop, "class=\"loop\""), 1u);
  EXPECT_NE(loop.find("loop: steps 1 to 2 repeat for ever"), std::string::npos);

  const std::string crash = (dir / "crash.svg").string();
  ASSERT_EQ(verify("check specs/defects/lone_lidar.semo -s specs/defects/strategy.xml --msc '" + crash + "'", dir).exit, 1);
  EXPECT_EQ(count(slurp(crash), "class=\"crash\""), 1u);

  // Knowledge facts named (one assignment that fits the counts), in blue boxes on the finder's lifeline.
  const std::string facts = (dir / "facts.svg").string();
  ASSERT_EQ(verify("check specs/defects/liveness/stuck_gossip.semo -s specs/defects/liveness/strategy.xml --msc '" + facts + "'", dir).exit, 1);
  const std::string gossip = slurp(facts);
  EXPECT_EQ(count(gossip, "class=\"facts\""), 2u);
  EXPECT_NE(gossip.find(">north</text>"), std::string::npos);
  EXPECT_NE(gossip.find(">north, south</text>"), std::string::npos);
  EXPECT_NE(gossip.find("<title>mapper_0.knows.blocked holds north, south</title>"), std::string::npos);

  CliRun none = verify("check specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --msc '" + (dir / "none.svg").string() + "'", dir);
  EXPECT_EQ(none.exit, 0);
  EXPECT_FALSE(fs::exists(dir / "none.svg"));
  EXPECT_NE(none.err.find("no counterexample to draw"), std::string::npos) << none.err;

  if (std::string(SEMO_RSVG_CONVERT).empty()) GTEST_SKIP() << "rsvg-convert (librsvg2-bin) is not installed";
  const std::string command = "'" SEMO_RSVG_CONVERT "' '" + chart + "' -o '" + (dir / "dr.png").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_GT(fs::file_size(dir / "dr.png"), 10000U);
  const std::string factsCommand = "'" SEMO_RSVG_CONVERT "' '" + facts + "' -o '" + (dir / "facts.png").string() + "'";
  ASSERT_EQ(std::system(factsCommand.c_str()), 0);
  EXPECT_GT(fs::file_size(dir / "facts.png"), 5000U);
}

}  // namespace
}  // namespace semo::e2e
