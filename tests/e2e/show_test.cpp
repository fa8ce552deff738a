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
  CliRun show = verify("show '" + saved + "'", dir);
  ASSERT_EQ(show.exit, 0) << show.err;
  ASSERT_NE(show.out.find("counterexample for deadlock_freedom (deadlock): 11 steps"), std::string::npos) << show.out;
  EXPECT_NE(check.out.find(show.out), std::string::npos) << "show prints the very text of check:\n" << show.out;
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

}  // namespace
}  // namespace semo::e2e
