// The simulated trace's JSON form (deterministic, parses back, every field present) and its SVG
// picture (well-formed, every kind of mark present, rendered by rsvg-convert when installed).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "semo/runtime/kinematics.hpp"
#include "semo/runtime/sim_trace.hpp"
#include "sim_trace_sample.hpp"

namespace semo::runtime {
namespace {

namespace fs = std::filesystem;

using sample::sampleTrace;

TEST(SimTraceJson, IsDeterministicAndParsesBack) {
  const SimTrace tr = sampleTrace();
  const std::string text = simTraceToJson(tr);
  EXPECT_EQ(text, simTraceToJson(sampleTrace()));
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(text)) << text;
  EXPECT_EQ(j["format"], "semo-simtrace");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["mission"], tr.mission);
  EXPECT_EQ(j["world"], "field.json");
  EXPECT_EQ(j["modelFingerprint"], "3f2a9c");
  EXPECT_EQ(j["seed"], 7);
  EXPECT_EQ(j["duration"], 60.0);
  EXPECT_EQ(j["faults"], tr.faults);
  ASSERT_EQ(j["robots"].size(), 3u);
  EXPECT_EQ(j["robots"][1], (nlohmann::json{{"name", "ev3_1"}, {"type", "Ev3Robot"}, {"team", "SlaveTeam"}}));
  EXPECT_EQ(j["teams"], (nlohmann::json{"MasterTeam", "SlaveTeam"}));

  ASSERT_EQ(j["events"].size(), tr.events.size());
  const nlohmann::json& step = j["events"][3];
  EXPECT_EQ(step["kind"], "step");
  EXPECT_EQ(step["robot"], "ev3_1");
  EXPECT_EQ(step["rule"], "SlaveTeam.search.1,SlaveTeam.search.2");
  EXPECT_EQ(step["origin"], "mission.semo:12:5 move");
  EXPECT_EQ(step["changes"][1], (nlohmann::json{{"var", "at_ev3_1"}, {"from", 0}, {"to", 2}}));
  EXPECT_FALSE(step.contains("label"));  // empty optional members are left out
  EXPECT_FALSE(step.contains("peer"));
  EXPECT_EQ(j["events"][6]["peer"], "*");  // sent to every peer
  EXPECT_EQ(j["events"][8]["kind"], "drop");
  EXPECT_EQ(j["events"][8]["peer"], "ev3_1");
  const nlohmann::json& note = j["events"][19];
  EXPECT_TRUE(note["robot"].is_null());
  EXPECT_EQ(note["label"], "quote \" backslash \\ tab \t and a stray byte \xEF\xBF\xBD");

  ASSERT_EQ(j["poses"].size(), tr.poses.size());
  const nlohmann::json& last = j["poses"].back();
  EXPECT_EQ(last["t"], 60.0);
  ASSERT_EQ(last["robots"].size(), 3u);
  EXPECT_NEAR(last["robots"][2][0].get<double>(), tr.poses.back().poses[2].x, 1e-6);

  const nlohmann::json& s = j["summary"];
  for (const char* key : {"goalStated", "completed", "completedAt", "modeChanges", "leaderChanges", "convergedAt", "messagesSent",
                          "messagesLost", "stepsChecked", "mismatches", "outsideAssumptions", "violations", "dataflow"}) {
    EXPECT_TRUE(s.contains(key)) << key;
  }
  EXPECT_EQ(s["completedAt"], 58.25);
  EXPECT_EQ(s["modeChanges"][1]["change"], "ev3_2: RETURN_MODE");
  EXPECT_TRUE(s["leaderChanges"][0]["from"].is_null());
  EXPECT_TRUE(s["leaderChanges"][0]["sinceCrash"].is_null());
  EXPECT_EQ(s["leaderChanges"][1]["to"], "ev3_2");
  EXPECT_EQ(s["leaderChanges"][1]["sinceCrash"], 6.0);
  EXPECT_TRUE(s["convergedAt"][1]["t"].is_null());
  EXPECT_EQ(s["messagesLost"], 2);
  EXPECT_EQ(s["violations"], (nlohmann::json{"P1"}));
  ASSERT_EQ(s["dataflow"].size(), 3u);
  EXPECT_EQ(s["dataflow"][0], (nlohmann::json{{"robot", "turtle_0"}, {"iterations", 1234}, {"scenariosRun", 2}, {"scenarios", 3},
                                              {"notRun", 0}, {"channelsAtCapacity", 1}, {"channels", 2}, {"stalls", 0}, {"overflows", 0}}));
  EXPECT_EQ(s["dataflow"][1]["overflows"], 1);
  EXPECT_EQ(s["dataflow"][2]["notRun"], 1);
  EXPECT_EQ(s["dataflow"][2]["scenariosRun"], 0);
}

TEST(SimTraceJson, FixedPrecisionAndOneEventPerLine) {
  const std::string text = simTraceToJson(sampleTrace());
  EXPECT_NE(text.find("\n    {\"t\": 25.000000, \"robot\": \"ev3_1\", \"kind\": \"crash\"},\n"), std::string::npos);
  EXPECT_NE(text.find("\n    {\"t\": 0.000000, \"robots\": [[1.000000, 1.000000, 0.000000], [1.000000, 2.000000, 0.500000], "
                      "[1.000000, 3.000000, 0.000000]]},\n"),
            std::string::npos);
  SimTrace tiny;
  tiny.poses.push_back({1e-9, {{-1e-9, 0, -0.0}}});
  EXPECT_NE(simTraceToJson(tiny).find("{\"t\": 0.000000, \"robots\": [[0.000000, 0.000000, 0.000000]]}"), std::string::npos);
  EXPECT_TRUE(nlohmann::json::parse(simTraceToJson(SimTrace{})).is_object());
  EXPECT_NE(text.find("\n      {\"robot\": \"ev3_1\", \"iterations\": 7, \"scenariosRun\": 1, \"scenarios\": 1, \"notRun\": 0, "
                      "\"channelsAtCapacity\": 1, \"channels\": 1, \"stalls\": 0, \"overflows\": 1},\n"),
            std::string::npos);  // one robot's dataflow per line
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// Well-formed enough for any XML reader: every element closed in order, attributes quoted, no bare '&'.
std::string tagBalance(const std::string& svg) {
  std::vector<std::string> open;
  for (std::size_t i = 0; i < svg.size(); ++i) {
    if (svg[i] == '&') {
      static const std::regex entity("^&(amp|lt|gt|quot|apos);");
      if (!std::regex_search(svg.substr(i, 8), entity)) return "bare & at " + std::to_string(i);
      continue;
    }
    if (svg[i] != '<') continue;
    const std::size_t end = svg.find('>', i);
    if (end == std::string::npos) return "unclosed tag at " + std::to_string(i);
    const std::string tag = svg.substr(i + 1, end - i - 1);
    i = end;
    if (tag.front() == '?' || tag.front() == '!') continue;
    if (tag.back() == '/') continue;
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return "</" + tag.substr(1) + "> closes <" + (open.empty() ? "" : open.back()) + ">";
      open.pop_back();
      continue;
    }
    if (count(tag, "\"") % 2 != 0) return "unbalanced quotes in <" + tag + ">";
    open.push_back(tag.substr(0, tag.find(' ')));
  }
  return open.empty() ? "" : "<" + open.back() + "> never closed";
}

TEST(SimTraceSvg, IsWellFormedAndDrawsEveryKindOfMark) {
  const SimTrace tr = sampleTrace();
  const std::string svg = renderSvg(tr);
  EXPECT_EQ(svg, renderSvg(sampleTrace()));
  EXPECT_EQ(tagBalance(svg), "");
  EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\"", 0), 0u);
  EXPECT_EQ(count(svg, "<script"), 0u);
  EXPECT_EQ(count(svg, "href"), 0u);  // self-contained

  EXPECT_EQ(count(svg, "class=\"trajectory\""), 3u);
  EXPECT_EQ(count(svg, "class=\"obstacle\""), 2u);
  EXPECT_EQ(count(svg, "class=\"place\""), 2u);
  EXPECT_EQ(count(svg, "class=\"fact-site\""), 2u);
  EXPECT_EQ(count(svg, "class=\"robot\""), 3u);
  EXPECT_EQ(count(svg, "class=\"crash\""), 1u);
  EXPECT_EQ(count(svg, "class=\"crash-pose\""), 1u);
  // Modes: turtle_0 START, COLLECT; ev3_1 SEARCH (until its crash); ev3_2 SEARCH, RETURN.
  EXPECT_EQ(count(svg, "class=\"mode-band\""), 5u);
  // Roles: ev3_1 leader until its crash; ev3_2 others, then leader until it left the block.
  EXPECT_EQ(count(svg, "class=\"role-band\""), 3u);
  EXPECT_EQ(count(svg, "class=\"msg-sent\""), 3u);
  EXPECT_EQ(count(svg, "class=\"msg-lost\""), 2u);
  EXPECT_EQ(count(svg, "class=\"violation\""), 2u);
  EXPECT_EQ(count(svg, "class=\"fact-found\""), 1u);
  EXPECT_NE(svg.find("rock &lt;big&gt;"), std::string::npos);
  EXPECT_NE(svg.find("search &amp; report"), std::string::npos);
  EXPECT_NE(svg.find(">SEARCH_MODE</text>"), std::string::npos);  // wide enough to be named
}

TEST(SimTraceSvg, EmptyTraceStillDraws) {
  const std::string svg = renderSvg(SimTrace{});
  EXPECT_EQ(tagBalance(svg), "");
  EXPECT_EQ(count(svg, "class=\"trajectory\""), 0u);
}

#ifdef SEMO_RSVG_CONVERT
std::uint32_t bigEndian(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
#endif

TEST(SimTraceSvg, RendersToAPng) {
#ifndef SEMO_RSVG_CONVERT
  GTEST_SKIP() << "rsvg-convert was not found at configure time";
#else
  const fs::path dir = fs::temp_directory_path() / ("semo_svg_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "trace.svg") << renderSvg(sampleTrace());
  const std::string command = std::string(SEMO_RSVG_CONVERT) + " -o '" + (dir / "trace.png").string() + "' '" + (dir / "trace.svg").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream png(dir / "trace.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>());
  fs::remove_all(dir);
  ASSERT_GE(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  EXPECT_GT(bigEndian(data + 16), 100u);  // width
  EXPECT_GT(bigEndian(data + 20), 100u);  // height
#endif
}

}  // namespace
}  // namespace semo::runtime
