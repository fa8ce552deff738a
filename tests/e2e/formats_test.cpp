// Formats for tools: check --junit and --sarif, lint --json and --sarif, read back as a CI system or a
// code-scanning tool would (tinyxml2, nlohmann).
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

namespace semo::e2e {
namespace {

TEST(Formats, JunitHasATestCasePerPropertyWithTheCounterexampleInTheFailure) {
  const fs::path dir = workDir("formats_junit");
  const std::string xml = (dir / "check.xml").string();
  CliRun r = verify("check specs/defects/double_receive.semo -s specs/defects/strategy.xml --junit '" + xml + "'", dir);
  ASSERT_EQ(r.exit, 1) << r.err;
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile(xml.c_str()), tinyxml2::XML_SUCCESS);
  const tinyxml2::XMLElement* suites = doc.FirstChildElement("testsuites");
  ASSERT_NE(suites, nullptr);
  const tinyxml2::XMLElement* suite = suites->FirstChildElement("testsuite");
  ASSERT_NE(suite, nullptr);
  int cases = 0, failures = 0;
  std::string failureText;
  for (const tinyxml2::XMLElement* c = suite->FirstChildElement("testcase"); c != nullptr; c = c->NextSiblingElement("testcase")) {
    ++cases;
    if (const tinyxml2::XMLElement* f = c->FirstChildElement("failure")) {
      ++failures;
      EXPECT_STREQ(c->Attribute("name"), "deadlock_freedom");
      failureText = f->GetText() != nullptr ? f->GetText() : "";
    }
  }
  EXPECT_EQ(cases, suite->IntAttribute("tests"));
  EXPECT_GE(cases, 2);
  EXPECT_EQ(failures, 1);
  EXPECT_EQ(suites->IntAttribute("failures"), 1);
  EXPECT_NE(failureText.find("counterexample for deadlock_freedom (deadlock): 11 steps"), std::string::npos) << failureText;
  EXPECT_NE(r.out.find(failureText), std::string::npos) << "the failure carries the text check printed";
}

TEST(Formats, JunitSkipsTheUnknown) {
  const fs::path dir = workDir("formats_junit_unknown");
  const std::string xml = (dir / "check.xml").string();
  CliRun r = verify("check specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --safety-only --junit '" + xml + "'", dir);
  ASSERT_EQ(r.exit, 3) << r.err;
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile(xml.c_str()), tinyxml2::XML_SUCCESS);
  const tinyxml2::XMLElement* suites = doc.FirstChildElement("testsuites");
  ASSERT_NE(suites, nullptr);
  EXPECT_EQ(suites->IntAttribute("skipped"), 3) << "the three LTL properties, not checked with --safety-only";
  EXPECT_EQ(suites->IntAttribute("failures"), 0);
}

TEST(Formats, SarifPlacesTheViolationAndItsStepsInTheMission) {
  const fs::path dir = workDir("formats_sarif");
  const std::string sarif = (dir / "check.sarif").string();
  CliRun r = verify("check specs/defects/double_receive.semo -s specs/defects/strategy.xml --sarif '" + sarif + "'", dir);
  ASSERT_EQ(r.exit, 1) << r.err;
  const nlohmann::json log = nlohmann::json::parse(slurp(sarif));
  EXPECT_EQ(log.at("version"), "2.1.0");
  const nlohmann::json& run = log.at("runs").at(0);
  EXPECT_EQ(run.at("tool").at("driver").at("name"), "semo-verify");
  ASSERT_EQ(run.at("results").size(), 1u);
  const nlohmann::json& result = run.at("results").at(0);
  EXPECT_EQ(result.at("level"), "error");
  EXPECT_NE(result.at("message").at("text").get<std::string>().find("deadlock_freedom is violated"), std::string::npos);
  const nlohmann::json& steps = result.at("codeFlows").at(0).at("threadFlows").at(0).at("locations");
  EXPECT_EQ(steps.size(), 11u);
  const nlohmann::json& third = steps.at(2).at("location");
  EXPECT_EQ(third.at("physicalLocation").at("artifactLocation").at("uri"), "specs/defects/double_receive.semo");
  EXPECT_EQ(third.at("physicalLocation").at("region").at("startLine"), 24);
  EXPECT_EQ(third.at("message").at("text"), "[base] receives report");
}

TEST(Formats, LintJsonAndSarifCarryTheDiagnosticsAtTheirPositions) {
  const fs::path dir = workDir("formats_lint");
  const std::string sarif = (dir / "lint.sarif").string();
  CliRun r = verify("lint tests/e2e/inputs/undefined_mode.semo -s specs/examples/scouting/strategy.xml --json --sarif '" + sarif + "'", dir);
  ASSERT_EQ(r.exit, 2) << r.err;
  EXPECT_TRUE(r.err.empty()) << "with --json the diagnostics are in the JSON: " << r.err;
  const nlohmann::json out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out.at("schemaVersion"), 1);
  EXPECT_EQ(out.at("exitCode"), 2);
  ASSERT_GE(out.at("diagnostics").size(), 1u);
  const nlohmann::json& first = out.at("diagnostics").at(0);
  std::size_t errors = 0;
  for (const nlohmann::json& d : out.at("diagnostics")) errors += d.at("severity") == "error" ? 1 : 0;
  EXPECT_GE(errors, 1u);
  EXPECT_EQ(out.at("errors"), errors);
  EXPECT_EQ(first.at("file"), "tests/e2e/inputs/undefined_mode.semo");
  EXPECT_GT(first.at("line").get<int>(), 0);
  const nlohmann::json log = nlohmann::json::parse(slurp(sarif));
  const nlohmann::json& results = log.at("runs").at(0).at("results");
  ASSERT_EQ(results.size(), out.at("diagnostics").size());
  EXPECT_EQ(results.at(0).at("message").at("text"), first.at("message"));
  EXPECT_EQ(results.at(0).at("locations").at(0).at("physicalLocation").at("region").at("startLine"), first.at("line"));
}

TEST(Formats, NoneOfThemReplacesAnInput) {
  const fs::path dir = workDir("formats_no_overwrite");
  const fs::path strategy = dir / "strategy.xml";
  fs::copy_file(fs::path(SEMO_SOURCE_DIR) / "specs/examples/swarm/strategy.xml", strategy);
  const std::string before = slurp(strategy);
  for (const char* option : {"--junit", "--sarif"}) {
    CliRun r = verify("check specs/examples/swarm/swarm3.semo -s '" + strategy.string() + "' " + option + " '" + strategy.string() + "'", dir);
    EXPECT_EQ(r.exit, 2) << option;
    EXPECT_EQ(slurp(strategy), before) << option;
  }
  CliRun r = verify("lint specs/examples/swarm/swarm3.semo -s '" + strategy.string() + "' --sarif '" + strategy.string() + "'", dir);
  EXPECT_EQ(r.exit, 2);
  EXPECT_EQ(slurp(strategy), before);
}

// `graph`: the dot text says what the mission says, and Graphviz renders it.
std::string rendered(const fs::path& dot, const fs::path& dir) {
  if (std::string(SEMO_DOT).empty()) return {};
  const fs::path svg = dir / (dot.stem().string() + ".svg");
  const std::string command = "'" SEMO_DOT "' -Tsvg '" + dot.string() + "' -o '" + svg.string() + "'";
  if (std::system(command.c_str()) != 0) return "dot failed";
  return slurp(svg);
}

TEST(Formats, GraphDrawsTheModesTheGroupsAndTheTaskGraphs) {
  const fs::path dir = workDir("formats_graph");
  const std::string scouting = "specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml";
  ASSERT_EQ(verify("graph " + scouting + " --modes -o '" + (dir / "modes.dot").string() + "'", dir).exit, 0);
  const std::string modes = slurp(dir / "modes.dot");
  EXPECT_NE(modes.find("label=\"SlaveTeam\""), std::string::npos);
  EXPECT_NE(modes.find("label=\"catch danger\""), std::string::npos);
  EXPECT_NE(modes.find("SEARCH_MODE\\nListen: CommOperator\\nAction: Search"), std::string::npos) << modes;
  EXPECT_NE(modes.find("[label=\"default\", style=dashed]"), std::string::npos);
  ASSERT_EQ(verify("graph " + scouting + " --groups -o '" + (dir / "groups.dot").string() + "'", dir).exit, 0);
  const std::string groups = slurp(dir / "groups.dot");
  EXPECT_NE(groups.find("leader (capable of ColorSensor)"), std::string::npos);
  EXPECT_NE(groups.find("heartbeat 500 ms, takeover after 2000 ms"), std::string::npos);
  EXPECT_NE(groups.find("ev3_0\\nEv3Robot"), std::string::npos);
  ASSERT_EQ(verify("graph " + scouting + " --tasks --robot ev3_0 -o '" + (dir / "tasks.dot").string() + "'", dir).exit, 0);
  const std::string tasks = slurp(dir / "tasks.dot");
  EXPECT_NE(tasks.find("scenario SEARCH_MODE (proven; period 5000 us)"), std::string::npos);
  EXPECT_NE(tasks.find("[label=\"1:4\\ncap 5\"]"), std::string::npos) << "color_reader to paper_detector: rates and proven capacity";
  EXPECT_EQ(tasks.find("burger_0"), std::string::npos);
  CliRun none = verify("graph specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --modes --groups", dir);
  EXPECT_EQ(none.exit, 2) << "one drawing at a time";
  if (std::string(SEMO_DOT).empty()) GTEST_SKIP() << "Graphviz is not installed";
  for (const char* name : {"modes.dot", "groups.dot", "tasks.dot"}) {
    const std::string svg = rendered(dir / name, dir);
    EXPECT_NE(svg.find("<svg"), std::string::npos) << name;
  }
  EXPECT_NE(slurp(dir / "modes.svg").find(">catch find_color_paper</text>"), std::string::npos);
}

}  // namespace
}  // namespace semo::e2e
