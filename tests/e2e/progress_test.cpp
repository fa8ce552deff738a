// Long runs. A long run says what it is doing: the model's size and what the search will try before it starts
// (at once for a large model), then its phases, and a heartbeat while a phase reports nothing
// itself. A quick run stays quiet. The large teams are the swarm example with its team line
// changed, written by the test.
#include <gtest/gtest.h>

#include <vector>

#include "cli_run.hpp"

namespace semo::e2e {
namespace {

// The swarm example with `robots` legged robots, in `dir`.
fs::path swarmOf(int robots, const fs::path& dir) {
  std::string text = slurp(fs::path(SEMO_SOURCE_DIR) / "specs/examples/swarm/swarm10.semo");
  const std::string team = "legged[10]";
  const std::size_t at = text.find(team);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, team.size(), "legged[" + std::to_string(robots) + "]");
  const fs::path out = dir / ("swarm" + std::to_string(robots) + ".semo");
  std::ofstream(out) << text;
  return out;
}

const std::string kStrategy = " -s specs/examples/swarm/strategy.xml";

TEST(Progress, AQuickCheckPrintsNothingOnStderr) {
  const fs::path dir = workDir("progress_quick");
  CliRun r = verify("check specs/examples/swarm/swarm3.semo" + kStrategy, dir);
  EXPECT_EQ(r.exit, 0) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(Progress, ALargeModelSaysItsSizeAndWhatItWillTryBeforeTheSearch) {
  const fs::path dir = workDir("progress_large");
  const fs::path mission = swarmOf(1000, dir);
  CliRun r = verify("check '" + mission.string() + "'" + kStrategy + " --engine explicit --no-symmetry --safety-only --max-states 100", dir);
  EXPECT_EQ(r.exit, 3) << r.err;  // partial: the search stopped at 100 states
  // The first line, before any phase: robots, variables and rules counted, with thousands separated.
  EXPECT_TRUE(std::regex_search(
      r.err, std::regex(R"(^model: 1,000 robots, [0-9]{1,3}(,[0-9]{3})+ variables, [0-9]{1,3}(,[0-9]{3})+ rules; 1 invariant and deadlock freedom, 0 LTL properties\n)")))
      << r.err;
  EXPECT_NE(r.err.find("\n  trying: a breadth-first search of the states (at most 100)\n"), std::string::npos) << r.err;
  // What the plan says matches the options: no symmetry, no LTL.
  EXPECT_EQ(r.err.find("interchangeable"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("LTL property on"), std::string::npos) << r.err;
}

TEST(Progress, APhaseThatReportsNothingIsStillSeenToBeAlive) {
  // Finding which of 5,000 robots are interchangeable (the explicit engine: the default counts them
  // instead) takes over half a minute (each swap compares the rules it touches) and says nothing
  // itself: the heartbeat must. The run is cut after 15 s,
  // 25 s under the sanitizers (there the translation alone takes 5 s, and the phase's first repeat
  // is due ten seconds after it began). (Should that phase ever take less, pick a larger team.)
  const fs::path dir = workDir("progress_heartbeat");
  const fs::path mission = swarmOf(5000, dir), err = dir / "stderr.txt";
  const std::string cut = SEMO_PROGRESS_SANITIZED ? "25" : "15";
  const std::string command = "cd '" SEMO_SOURCE_DIR "' && timeout " + cut + " '" SEMO_VERIFY "' check '" + mission.string() + "'" +
                              kStrategy + " --engine explicit >/dev/null 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 124) << "the check ended within " << cut << " s: this test needs a phase that lasts longer\n"
                                      << slurp(err);
  const std::string text = slurp(err);
  // The model's size before the search's first phase (a slow translation may be said before it).
  const std::size_t model = text.find("model: 5,000 robots, "), symmetry = text.find("] symmetry: ");
  ASSERT_NE(model, std::string::npos) << text;
  EXPECT_LT(model, symmetry) << text;
  // A line within the first seconds, then one at least every ten seconds, the symmetry phase
  // repeated while it lasts.
  const std::regex timed(R"(\[([0-9]+) s\] (.*))");
  std::vector<int> seconds;
  int repeated = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, timed)) continue;
    seconds.push_back(std::stoi(m[1].str()));
    if (m[2].str() == "symmetry: which of the 5000 robots are interchangeable (still working)") ++repeated;
  }
  ASSERT_GE(seconds.size(), 2u) << text;
  EXPECT_LE(seconds.front(), 5) << text;
  for (std::size_t i = 1; i < seconds.size(); ++i) EXPECT_LE(seconds[i] - seconds[i - 1], 11) << text;
  EXPECT_GE(repeated, 1) << text;
}

// Memory running out is a resource limit, said as such (exit 3), not an abort: 100,000 robots
// (400,004 variables, 800,000 rules) under a 2 GB address-space limit.
TEST(Progress, ATeamTooLargeForTheMemoryEndsAsALimitNotASignal) {
  if (SEMO_PROGRESS_SANITIZED) GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
  const fs::path dir = workDir("progress_memory");
  const fs::path mission = swarmOf(100000, dir), err = dir / "stderr.txt";
  const std::string command = "cd '" SEMO_SOURCE_DIR "' && ulimit -v 2000000 && timeout 120 '" SEMO_VERIFY "' check '" + mission.string() + "'" +
                              kStrategy + " >/dev/null 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3) << slurp(err);
  EXPECT_NE(slurp(err).find("semo-verify: error: out of memory: the model is too large for this machine's memory (exit 3)\n"),
            std::string::npos)
      << slurp(err);
}

}  // namespace
}  // namespace semo::e2e
