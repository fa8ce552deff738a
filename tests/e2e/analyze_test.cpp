// `analyze --svg`: the chart of P(within t) (tools/semo-verify/probability_chart.cpp) says what the
// numbers say, renders, is the same bytes on every run, and never replaces an input.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace semo::e2e
