// The world file reader: every kind of entry read back, comments ignored, each mistake reported at
// its line and column, and no input (a depth bomb, random bytes) crashes it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "semo/runtime/world.hpp"

namespace semo::runtime {
namespace {

const char* kFullWorld = R"({
  "_comment": "every kind of entry once",
  "format": "semo-world", "version": 1,
  "arena": {"from": [0, 0], "to": [10, 6]},
  "places": {"base camp": [1, 1], "Paris palace of congress": [4, 2.5], "_note": "ignored"},
  "robots": {"ev3_0": {"at": [0.5, 0.5], "heading": 90, "_why": "faces north"}, "ev3_1": {"at": [1.5, 0.5]}},
  "obstacles": [{"name": "ditch", "polygon": [[3,-1],[3.5,-1],[3.5,5],[3,5]]},
                {"name": "rock", "circle": {"at": [2,2], "radius": 0.3}}],
  "facts": [{"knowledge": "papers", "fact": "red", "at": [2, 3], "radius": 0.5},
            {"knowledge": "papers", "fact": "blue", "at": [6, 3]}],
  "values": {
     "SlaveTeam.light": {"constant": "high"},
     "SlaveTeam.ready": {"constant": true},
     "Team.battery": {"schedule": [[0, 80], [30, 15.5]]},
     "Team.zone": {"regions": [{"polygon": [[0,0],[2,0],[2,2],[0,2]], "value": "inside"},
                               {"circle": {"at": [1,1], "radius": 2}, "value": "near"}], "otherwise": "far"},
     "Team.obstacle": {"sensor": "obstacle_ahead", "range": 0.7},
     "Team.arrived": {"sensor": "at_destination"}
  },
  "goal": [{"team": "SlaveTeam", "mode": "RETURN_MODE", "done": ["Action"]}, {"team": "MasterTeam", "mode": "END"}]
}
)";

std::vector<WorldError> errorsOf(std::string_view text) {
  std::vector<WorldError> errors;
  EXPECT_FALSE(parseWorld(text, "w.json", errors).has_value()) << "a world with errors must not be returned";
  return errors;
}

// The first error's "line:col: message".
std::string firstError(std::string_view text) {
  std::vector<WorldError> errors = errorsOf(text);
  if (errors.empty()) return "(no error)";
  return std::to_string(errors[0].line) + ":" + std::to_string(errors[0].column) + ": " + errors[0].message;
}

TEST(WorldReader, ReadsEveryKindOfEntry) {
  std::vector<WorldError> errors;
  std::optional<World> w = parseWorld(kFullWorld, "full.json", errors);
  for (const WorldError& e : errors) ADD_FAILURE() << formatWorldError(e);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->path, "full.json");
  ASSERT_TRUE(w->arena.has_value());
  EXPECT_EQ(w->arena->second.x, 10);
  EXPECT_EQ(w->arena->second.y, 6);

  ASSERT_EQ(w->places.size(), 2u);
  EXPECT_EQ(w->places[0].name, "base camp");  // file order, not key order
  EXPECT_EQ(w->values[0].name, "SlaveTeam.light");
  EXPECT_EQ(w->values[5].name, "Team.arrived");
  const Place* paris = w->place("Paris palace of congress");
  ASSERT_NE(paris, nullptr);
  EXPECT_EQ(paris->at.y, 2.5);
  EXPECT_EQ(paris->written.line, 5u);
  EXPECT_EQ(w->place("_note"), nullptr);

  ASSERT_EQ(w->starts.size(), 2u);
  const StartPose* ev3 = w->start("ev3_0");
  ASSERT_NE(ev3, nullptr);
  EXPECT_NEAR(ev3->heading, std::numbers::pi / 2, 1e-15);
  EXPECT_EQ(w->start("ev3_1")->heading, 0);

  ASSERT_EQ(w->obstacles.size(), 2u);
  EXPECT_EQ(w->obstacles[0].shape.kind, Shape::Kind::Polygon);
  EXPECT_EQ(w->obstacles[0].shape.points.size(), 4u);
  EXPECT_EQ(w->obstacles[1].shape.kind, Shape::Kind::Circle);
  EXPECT_EQ(w->obstacles[1].shape.radius, 0.3);

  ASSERT_EQ(w->facts.size(), 2u);
  EXPECT_EQ(w->facts[0].radius, 0.5);
  EXPECT_EQ(w->facts[1].radius, 0.3);  // the default
  EXPECT_EQ(w->facts[1].fact, "blue");

  ASSERT_EQ(w->values.size(), 6u);
  const ValueSource* light = w->value("SlaveTeam.light");
  ASSERT_NE(light, nullptr);
  EXPECT_EQ(light->kind, ValueSource::Kind::Constant);
  ASSERT_EQ(light->schedule.size(), 1u);
  EXPECT_FALSE(light->schedule[0].second.isNumber);
  EXPECT_EQ(light->schedule[0].second.symbol, "high");
  EXPECT_EQ(w->value("SlaveTeam.ready")->schedule[0].second.symbol, "true");
  const ValueSource* battery = w->value("Team.battery");
  ASSERT_EQ(battery->kind, ValueSource::Kind::Schedule);
  ASSERT_EQ(battery->schedule.size(), 2u);
  EXPECT_EQ(battery->schedule[1].first, 30);
  EXPECT_TRUE(battery->schedule[1].second.isNumber);
  EXPECT_EQ(battery->schedule[1].second.number, 15.5);
  const ValueSource* zone = w->value("Team.zone");
  ASSERT_EQ(zone->kind, ValueSource::Kind::Regions);
  ASSERT_EQ(zone->regions.size(), 2u);
  EXPECT_EQ(zone->regions[1].value.symbol, "near");
  EXPECT_EQ(zone->otherwise.symbol, "far");
  const ValueSource* obstacle = w->value("Team.obstacle");
  EXPECT_EQ(obstacle->kind, ValueSource::Kind::Sensor);
  EXPECT_EQ(obstacle->sensor, "obstacle_ahead");
  EXPECT_EQ(obstacle->range, 0.7);
  EXPECT_EQ(w->value("Team.arrived")->range, 0.5);  // the default

  ASSERT_EQ(w->goal.size(), 2u);
  EXPECT_EQ(w->goal[0].team, "SlaveTeam");
  EXPECT_EQ(w->goal[0].mode, "RETURN_MODE");
  ASSERT_EQ(w->goal[0].plansDone.size(), 1u);
  EXPECT_EQ(w->goal[0].plansDone[0], "Action");
  EXPECT_TRUE(w->goal[1].plansDone.empty());
}

TEST(WorldReader, OnlyFormatAndVersionAreRequired) {
  std::vector<WorldError> errors;
  std::optional<World> w = parseWorld(R"({"format": "semo-world", "version": 1})", "min.json", errors);
  ASSERT_TRUE(w.has_value());
  EXPECT_FALSE(w->arena.has_value());
  EXPECT_TRUE(w->places.empty() && w->starts.empty() && w->goal.empty());
}

TEST(WorldReader, ReadsAFile) {
  const auto path = std::filesystem::temp_directory_path() / "semo_world_reader_test.json";
  std::ofstream(path) << kFullWorld;
  std::vector<WorldError> errors;
  std::optional<World> w = readWorld(path.string(), errors);
  std::filesystem::remove(path);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->path, path.string());

  EXPECT_FALSE(readWorld("/nonexistent/world.json", errors).has_value());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].line, 0u);
  EXPECT_EQ(formatWorldError(errors[0]), "/nonexistent/world.json: error: cannot read the world file\n");
  errors.clear();
  EXPECT_FALSE(readWorld(std::filesystem::temp_directory_path().string(), errors).has_value());
  EXPECT_EQ(errors.at(0).line, 0u);
}

TEST(WorldReader, EachMistakeIsReportedWhereItIs) {
  const std::string head = "{\"format\": \"semo-world\", \"version\": 1,\n";
  struct Case {
    std::string body;  // line 2 of the file
    std::string expected;
  };
  const Case cases[] = {
      {"\"places\": {\"a\": [1, \"x\"]}}", "2:21: a coordinate must be a number"},
      {"\"places\": {\"a\": [1]}}", "2:17: a point is [x, y]"},
      {"\"places\": {\"\": [1, 1]}}", "2:12: a place needs a non-empty name"},
      {"\"places\": {\"a\": [1, 1], \"a\": [2, 2]}}", "2:25: member 'a' given twice"},
      {"\"obstacles\": [{\"name\": \"r\", \"circle\": {\"at\": [0, 0], \"radius\": 0}}]}", "2:64: a radius must be greater than 0"},
      {"\"obstacles\": [{\"name\": \"p\", \"polygon\": [[0, 0], [1, 1]]}]}", "2:40: a polygon needs at least 3 points, not 2"},
      {"\"obstacles\": [{\"name\": \"p\", \"circle\": {\"at\": [0, 0], \"radius\": 1}}, {\"name\": \"p\", \"circle\": {\"at\": [0, 0], \"radius\": 1}}]}",
       "2:78: obstacle 'p' declared twice"},
      {"\"obstacles\": [{\"name\": \"\", \"circle\": {\"at\": [0, 0], \"radius\": 1}}]}", "2:24: \"name\" must be a non-empty string"},
      {"\"values\": {\"T.b\": {\"schedule\": [[0, 1], [5, 2], [5, 3]]}}}", "2:50: schedule times must increase (5.0 after 5.0)"},
      {"\"values\": {\"T.b\": {\"schedule\": [[1, 1]]}}}", "2:34: a schedule starts at time 0"},
      {"\"values\": {\"T.b\": {\"sensor\": \"sonar\"}}}", "2:30: unknown sensor \"sonar\""},
      {"\"values\": {\"T.b\": {\"constant\": 1, \"sensor\": \"at_destination\"}}}", "2:19: a value source needs exactly one of"},
      {"\"values\": {\"light\": {\"constant\": 1}}}", "2:12: a sensed value is named 'Team.variable'"},
      {"\"values\": {\"T.b\": {\"constant\": null}}}", "2:32: a sensed value is a number, a non-empty string, true or false"},
      {"\"values\": {\"T.z\": {\"regions\": [{\"circle\": {\"at\": [0, 0], \"radius\": 1}, \"value\": 1}]}}}", "2:19: a value by regions needs \"otherwise\""},
      {"\"robots\": {\"r\": {\"at\": [0, 0], \"heading\": \"north\"}}}", "2:43: a heading (degrees) must be a number"},
      {"\"robots\": {\"r\": {\"at\": [0, 0], \"speed\": 1}}}", "2:32: unknown member 'speed' in a robot's start"},
      {"\"arena\": {\"from\": [0, 0], \"to\": [0, 5]}}", "2:33: the arena's \"to\" corner must be above and right"},
      {"\"goal\": [{\"team\": \"T\"}]}", "2:10: a goal needs \"mode\""},
      {"\"facts\": [{\"knowledge\": \"k\", \"fact\": \"f\", \"at\": [1e400, 0]}]}", "2:50: number 1e400 is out of range"},
      {"\"places\": {\"a\": [1, 1],}}", "2:24: not valid JSON: syntax error"},
      {"\"colour\": \"red\"}", "2:1: unknown member 'colour' in the world"},
  };
  for (const Case& c : cases) {
    const std::string got = firstError(head + c.body + "\n");
    EXPECT_EQ(got.substr(0, c.expected.size()), c.expected) << c.body;
  }
}

TEST(WorldReader, WrongFormatOrVersion) {
  EXPECT_EQ(firstError("{\"format\": \"semo-taskgraph\", \"version\": 1}"), "1:12: \"format\" must be \"semo-world\"");
  EXPECT_EQ(firstError("{\"format\": \"semo-world\", \"version\": 2}"), "1:37: unsupported world version (this semo reads \"version\": 1)");
  EXPECT_EQ(firstError("[1, 2]"), "1:1: a world file is a JSON object");
  EXPECT_EQ(firstError(""), "1:1: not valid JSON: syntax error while parsing value - unexpected end of input; expected '[', '{', or a literal");
}

TEST(WorldReader, ReportsEveryMistakeNotJustTheFirst) {
  std::vector<WorldError> errors = errorsOf(R"({"format": "semo-world", "version": 1,
"places": {"a": [1, 1], "a": [2, 2]},
"robots": {"r": {"at": [0]}},
"obstacles": [{"name": "o", "circle": {"at": [0, 0], "radius": -1}}],
"values": {"T.v": {"sensor": "radar"}}
})");
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors[0].line, 2u);
  EXPECT_EQ(errors[1].line, 3u);
  EXPECT_EQ(errors[2].line, 4u);
  EXPECT_EQ(errors[3].line, 5u);
}

TEST(WorldReader, CommentsAreIgnoredEverywhere) {
  std::vector<WorldError> errors;
  std::optional<World> w = parseWorld(R"({"_a": 1, "format": "semo-world", "version": 1, "_b": {"anything": [1, 2]},
    "arena": {"from": [0, 0], "to": [1, 1], "_c": null},
    "obstacles": [{"_d": 0, "name": "o", "circle": {"_e": 1, "at": [0, 0], "radius": 1}}],
    "facts": [{"_f": 2, "knowledge": "k", "fact": "f", "at": [0, 0]}],
    "values": {"_g": 3, "T.v": {"_h": 4, "regions": [{"_i": 5, "circle": {"at": [0, 0], "radius": 1}, "value": 1}], "otherwise": 0}},
    "goal": [{"_j": 6, "team": "T", "mode": "M"}]})", "c.json", errors);
  for (const WorldError& e : errors) ADD_FAILURE() << formatWorldError(e);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->values.size(), 1u);
}

TEST(WorldReader, FormatsAnErrorWithACaret) {
  std::vector<WorldError> errors = errorsOf("{\"format\": \"semo-world\", \"version\": 1,\n\t\"places\": {\"a\": [1]}}");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(formatWorldError(errors[0]), "w.json:2:18: error: a point is [x, y] (two numbers, metres)\n"
                                         "\t\"places\": {\"a\": [1]}}\n"
                                         "\t                ^\n");
}

TEST(WorldReader, RejectsADepthBombBeforeParsing) {
  std::string bomb = "{\"format\": \"semo-world\", \"version\": 1, \"_x\": ";
  bomb += std::string(100000, '[') + std::string(100000, ']') + "}";
  std::vector<WorldError> errors = errorsOf(bomb);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].message, "nesting deeper than 64 levels");
  EXPECT_EQ(errors[0].column, std::string_view("{\"format\": \"semo-world\", \"version\": 1, \"_x\": ").size() + 64);  // the 65th level

  // 64 levels are fine.
  std::string deep = "{\"format\": \"semo-world\", \"version\": 1, \"_x\": " + std::string(63, '[') + std::string(63, ']') + "}";
  std::vector<WorldError> none;
  EXPECT_TRUE(parseWorld(deep, "deep.json", none).has_value());
}

TEST(WorldReader, NeverCrashesOnGarbage) {
  std::mt19937 random(20240611);
  const std::string pieces[] = {"{", "}", "[", "]", ",", ":", "\"", "\"format\"", "\"semo-world\"", "\"version\"", "1", "-0.5e3", "1e999",
                                "\"places\"", "\"values\"", "\"regions\"", "\"circle\"", "\"polygon\"", "\"at\"", "\"radius\"", "true", "null",
                                "\"schedule\"", "\"sensor\"", "\\", "\xff", "\n", " ", "\"_\"", std::string(1, '\0')};
  for (int round = 0; round < 3000; ++round) {
    std::string text;
    if (round % 2 == 0) {
      // Mutations of a valid world reach deep into the checks.
      text = kFullWorld;
      for (int k = 0; k < 1 + round % 5; ++k) {
        const std::size_t at = random() % text.size();
        const std::string& piece = pieces[random() % std::size(pieces)];
        if (random() % 2 == 0) text.replace(at, std::min<std::size_t>(random() % 4, text.size() - at), piece);
        else text.insert(at, piece);
      }
    } else {
      for (int k = 0; k < 40; ++k) text += pieces[random() % std::size(pieces)];
    }
    std::vector<WorldError> errors;
    std::optional<World> w = parseWorld(text, "fuzz.json", errors);
    EXPECT_TRUE(w.has_value() != !errors.empty()) << "a world comes with no error, an error with no world";
    for (const WorldError& e : errors) {
      EXPECT_FALSE(formatWorldError(e).empty());
      EXPECT_GE(e.line, 1u);
    }
  }
}

// The example of the format's documentation is a valid world.
TEST(WorldReader, DocumentationExampleIsValid) {
  std::ifstream in(std::string(SEMO_SOURCE_DIR) + "/runtime/WORLD.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t start = doc.find("```json\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + 8);
  std::vector<WorldError> errors;
  std::optional<World> w = parseWorld(doc.substr(start + 8, end - start - 8), "WORLD.md", errors);
  for (const WorldError& e : errors) ADD_FAILURE() << formatWorldError(e);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->values.size(), 5u);
  EXPECT_EQ(w->goal.size(), 1u);
}

}  // namespace
}  // namespace semo::runtime
