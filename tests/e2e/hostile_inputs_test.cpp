// Hostile inputs, end to end: every reader of semo-verify (missions, strategies, URDF files, IR, task
// graphs, SDF3 graphs, counterexample traces, worlds) fed what an attacker or a broken tool would give
// it, generated here at run time (nothing large is stored): nesting far past every documented limit,
// a hundred thousand items on one line, files of megabytes, empty files, binary garbage, invalid
// UTF-8, missing files and folders given as files (and, in hostile_outputs_test.cpp, every output
// option pointed onto an input, into a missing folder and onto a folder). The project's rule: bad
// input never crashes and never half-writes; it gets `file:line:col: error: ...` with a caret where
// a position exists, exit code 2 and no output files; no output ever replaces an input; readers
// limit nesting; cost stays near-linear in the input's size. Each case checks all of it: the exit code, the diagnostic, that
// the process was not killed by a signal, that it finished within the bound, and that no file of the
// run's folder changed, appeared or disappeared.
#include "hostile_support.hpp"

namespace {

using namespace hostile;
namespace fs = std::filesystem;

// ---- missions (.semo) ---------------------------------------------------------------------------

const std::string kTeam = "Survey: TurtlebotBurger mapper, Ev3Robot tracker[2]\n";

// `lint` on a mission written to in/hostile.semo (against the seeded defects' strategy).
void missionRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.semo");
  writeFile(path, text);
  refused(w, {"lint", path, "--strategy", w.strategy()}, diagnostic, where, "hostile.semo");
}

TEST(HostileMission, NestingFarPastTheLimit) {
  Work w("mission_depth");
  const std::string service = "Survey.Explore.Map { ";
  missionRefused(w, kTeam + service + "if (" + repeat("(", kHuge) + "Survey.x == 1" + repeat(")", kHuge) + ") scanArea() }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + service + repeat("if (Survey.x == 1) { ", kHuge) + "scanArea()" + repeat(" }", kHuge) + " }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + service + "if (" + repeat("not ", kHuge) + "Survey.x == 1) scanArea() }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + service + repeat("[[ group (capable of LaserDistanceSensor) { ", kHuge) + "scanArea()" + repeat(" } ]]", kHuge) + " }\n",
                 "hostile\\.semo:2:[0-9]+: error: group blocks '\\[\\[ \\]\\]' cannot be nested");
  missionRefused(w, kTeam + "verify { property p: always " + repeat("(", kHuge) + "mapper.alive" + repeat(")", kHuge) + " }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + "verify { property p: " + repeat("always eventually ", kHuge) + "mapper.alive }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  // Unclosed: a hundred thousand braces opened and never closed.
  missionRefused(w, kTeam + service + repeat("{", kHuge) + "\n", "hostile\\.semo:2:[0-9]+: error: ");
}

TEST(HostileMission, AHundredThousandItemsOnOneLine) {
  Work w("mission_width");
  // A condition of 100,000 terms, the last undefined: the error is placed at its column.
  std::string terms;
  for (std::size_t i = 0; i < kHuge; ++i) terms += "mapper.alive and ";
  missionRefused(w, kTeam + "Survey.Explore.Map { if (" + terms + "nosuch.alive) scanArea() }\n",
                 "hostile\\.semo:2:1700026: error: [^\n]*nosuch");
  // 100,000 arguments.
  missionRefused(w, kTeam + "Survey.Explore.Map { navigate(" + repeat("\"a\", ", kHuge) + "\"a\") }\n", "hostile\\.semo:2:[0-9]+: error: ");
  // 100,000 statements on one line, each an error: every diagnostic shows a window of the line, not
  // the whole of it (a megabyte under each of 100,000 errors would be 100 GB).
  const std::string path = w.at("hostile.semo");
  writeFile(path, kTeam + "Survey.Explore.Map { " + repeat("nosuch() ", kHuge) + "}\n");
  const Outcome o = refused(w, {"lint", path, "--strategy", w.strategy()}, "hostile\\.semo:2:22: error: undefined service 'nosuch'",
                            Where::Caret, "hostile.semo");
  EXPECT_LT(o.err.size(), kHuge * 1000) << "each error's line is a window, not the whole line";
}

TEST(HostileMission, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("mission_size");
  missionRefused(w, megabytes("# ", "", 40000, kTeam + "Survey.Explore.Map { scanArea( }\n"), "hostile\\.semo:40002:[0-9]+: error: ");
  missionRefused(w, "", "hostile\\.semo:1:1: error: the mission is empty", Where::Position);
  missionRefused(w, garbage(1 << 20), "hostile\\.semo:1:1: error: ");
  missionRefused(w, "Survey: Turtlebot" + kBadUtf8 + "Burger mapper\n", "hostile\\.semo:1:18: error: unexpected character byte 0x80");
  missionRefused(w, "Survey: TurtlebotBurger mapper\n# a comment " + kBadUtf8 + "\nSurvey.Explore.Map { scan" + kBadUtf8 + "Area() }\n",
                 "hostile\\.semo:3:26: error: unexpected character byte 0x80");
  missionRefused(w, kTeam + "Survey.Explore.Map {" + '\0' + " scanArea() }\n", "hostile\\.semo:2:21: error: unexpected character byte 0x00");
  // Not UTF-8 in a string: `parse --json` once died of it (nlohmann::json refuses to write it).
  const std::string path = w.at("hostile.semo");
  writeFile(path, kTeam + "Survey.Explore.Map { navigate(\"fr" + kBadUtf8 + "ontier\") }\n");
  for (const std::vector<std::string>& args : {std::vector<std::string>{"parse", path, "--json"}, std::vector<std::string>{"lint", path, "-s", w.strategy()},
                                               std::vector<std::string>{"check", path, "-s", w.strategy(), "--json"}}) {
    refused(w, args, "hostile\\.semo:2:34: error: a string must be UTF-8 text: byte 0x80 is not", Where::Caret, "hostile.semo");
  }
}

TEST(HostileMission, MissingFileAndAFolder) {
  Work w("mission_path");
  refused(w, {"lint", w.at("no_such.semo"), "--strategy", w.strategy()}, "error: cannot open '[^']*no_such\\.semo'", Where::NoPosition);
  refused(w, {"parse", w.at("no_such.semo")}, "error: cannot open '[^']*no_such\\.semo'", Where::NoPosition);
  fs::create_directories(w.at("folder.semo"));
  refused(w, {"lint", w.at("folder.semo"), "--strategy", w.strategy()}, "error: cannot read '[^']*folder\\.semo': it is a folder, not a file",
          Where::NoPosition);
  refused(w, {"check", w.at("folder.semo"), "--strategy", w.strategy()}, "error: cannot read '[^']*folder\\.semo': it is a folder",
          Where::NoPosition);
  refused(w, {"simulate", w.at("missions"), "--strategy", w.swarmStrategy(), "--world", w.world()}, "error: cannot read '[^']*missions': it is a folder",
          Where::NoPosition);
}

// ---- strategies (--strategy, XML) ---------------------------------------------------------------

const std::string kXmlHead = "<?xml version=\"1.0\"?>\n";

void strategyRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("missions/hostile.xml");
  writeFile(path, text);
  refused(w, {"lint", w.mission(), "--strategy", path}, diagnostic, where, "hostile.xml");
}

TEST(HostileStrategy, NestingFarPastTheLimit) {
  Work w("strategy_depth");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">" + repeat("<a>", kHuge) + repeat("</a>", kHuge) + "</strategy>\n",
                  "hostile\\.xml:2:1: error: malformed XML: elements are nested too deeply");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n" + repeat("<service name=\"s\">\n", kHuge),
                  "hostile\\.xml:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
}

TEST(HostileStrategy, AHundredThousandItemsOnOneLine) {
  Work w("strategy_width");
  const std::string robots = "  <robot urdf=\"../robots/turtlebot3_burger.urdf\" type=\"TurtlebotBurger\"/>\n"
                             "  <robot urdf=\"../robots/ev3_robot.urdf\" type=\"Ev3Robot\"/>\n";
  // 100,000 unknown elements on one line: an error each, each with a window of the line.
  const Outcome o = [&] {
    const std::string path = w.at("missions/hostile.xml");
    writeFile(path, kXmlHead + "<strategy version=\"1\">\n" + robots + repeat("<nosuch/>", kHuge) + "\n</strategy>\n");
    return refused(w, {"lint", w.mission(), "--strategy", path}, "hostile\\.xml:5:1: error: [^\n]*nosuch", Where::Caret, "hostile.xml");
  }();
  EXPECT_LT(o.err.size(), kHuge * 1000);
  // 100,000 attributes on one element (tinyxml2 compares each with those before it: refused first).
  std::string attributes;
  for (std::size_t i = 0; i < kHuge; ++i) attributes += " a" + std::to_string(i) + "=\"1\"";
  strategyRefused(w, kXmlHead + "<strategy version=\"1\"" + attributes + ">\n</strategy>\n",
                  "hostile\\.xml:2:1: error: element <strategy> has more than 1000 attributes");
}

TEST(HostileStrategy, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("strategy_size");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n" + megabytes("<!-- ", " -->", 40000, "<broken\n"),
                  "hostile\\.xml:40003:1: error: malformed XML");
  strategyRefused(w, "", "hostile\\.xml:1:1: error: malformed XML: the document is empty", Where::Position);
  strategyRefused(w, garbage(1 << 20), "hostile\\.xml:1:2: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  // Not UTF-8: refused where the first bad byte is (names and values are written out again, in JSON
  // among others: `lint --json` once died of one).
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n  <robot urdf=\"" + kBadUtf8 + ".urdf\" type=\"T\"/>\n</strategy>\n",
                  "hostile\\.xml:3:16: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n  <" + kBadUtf8 + "/>\n</strategy>\n", "hostile\\.xml:3:4: error: malformed XML: not UTF-8");
  std::string strategy = slurp(w.strategy());
  strategy.replace(strategy.find("type=\"Ev3Robot\""), 15, "type=\"Ev3" + kBadUtf8 + "Robot\"");
  writeFile(w.at("missions/hostile.xml"), strategy);
  refused(w, {"lint", w.mission(), "--strategy", w.at("missions/hostile.xml")}, "hostile\\.xml:10:[0-9]+: error: malformed XML: not UTF-8", Where::Caret,
          "hostile.xml");
  // With --json the diagnostics are JSON on stdout, with their positions.
  const Snapshot before = snapshot(w.in);
  const Outcome o = run({"lint", w.mission(), "--strategy", w.at("missions/hostile.xml"), "--json"}, w.log);
  EXPECT_EQ(o.signal, 0) << o.err;
  EXPECT_EQ(o.exit, 2) << o.err;
  const nlohmann::json lint = nlohmann::json::parse(o.out, nullptr, false);
  ASSERT_TRUE(lint.is_object()) << o.out;
  ASSERT_FALSE(lint["diagnostics"].empty()) << o.out;
  EXPECT_EQ(lint["diagnostics"][0].value("line", 0), 10) << o.out;
  EXPECT_NE(lint["diagnostics"][0].value("message", "").find("not UTF-8"), std::string::npos) << o.out;
  EXPECT_EQ(differences(before, snapshot(w.in)), "");
  // An entity bomb: tinyxml2 expands no entity of a DTD; the document is refused, quickly.
  strategyRefused(w,
                  kXmlHead + "<!DOCTYPE s [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\">"
                             "<!ENTITY c \"&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;\"><!ENTITY d \"&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;\">]>\n"
                             "<strategy version=\"1\">&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;</strategy>\n",
                  "error: ", Where::NoPosition);
}

TEST(HostileStrategy, MissingFileAndAFolder) {
  Work w("strategy_path");
  refused(w, {"lint", w.mission(), "--strategy", w.at("no_such.xml")}, "error: cannot open '[^']*no_such\\.xml'", Where::NoPosition);
  refused(w, {"lint", w.mission(), "--strategy", w.at("missions")}, "error: cannot read '[^']*missions': it is a folder, not a file",
          Where::NoPosition);
}

// ---- URDF files (--robots DIR) ------------------------------------------------------------------

// The strategy names ../robots/turtlebot3_burger.urdf, which --robots DIR resolves against DIR:
// DIR/../robots/turtlebot3_burger.urdf, here the hostile one (DIR is a folder named robots).
fs::path robotsLike(Work& w, const std::string& name) {
  const fs::path dir = w.in / name / "robots";
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(w.in / "robots")) fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
  return dir;
}

void urdfRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const fs::path dir = robotsLike(w, "hostile");
  writeFile(dir / "turtlebot3_burger.urdf", text);
  refused(w, {"lint", w.mission(), "--strategy", w.strategy(), "--robots", dir.string()}, diagnostic, where, "turtlebot3_burger.urdf");
}

const std::string kRobotOpen = kXmlHead + "<robot name=\"TurtlebotBurger\">\n";

TEST(HostileUrdf, NestingFarPastTheLimit) {
  Work w("urdf_depth");
  urdfRefused(w, kRobotOpen + repeat("<link name=\"l\">", kHuge) + repeat("</link>", kHuge) + "\n</robot>\n",
              "turtlebot3_burger\\.urdf:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
  // A kinematic chain of 100,000 links whose last joint closes a cycle: the tree check is linear.
  std::string chain = kRobotOpen;
  for (std::size_t i = 0; i <= kHuge; ++i) chain += "<link name=\"l" + std::to_string(i) + "\"/>\n";
  for (std::size_t i = 0; i < kHuge; ++i) {
    chain += "<joint name=\"j" + std::to_string(i) + "\" type=\"fixed\"><parent link=\"l" + std::to_string(i) + "\"/><child link=\"l" +
             std::to_string(i + 1) + "\"/></joint>\n";
  }
  chain += "<joint name=\"back\" type=\"fixed\"><parent link=\"l" + std::to_string(kHuge) + "\"/><child link=\"l0\"/></joint>\n</robot>\n";
  urdfRefused(w, chain, "turtlebot3_burger\\.urdf:[0-9]+:1: error: invalid URDF: joints form a cycle through link 'l0'");
}

TEST(HostileUrdf, AHundredThousandItemsOnOneLine) {
  Work w("urdf_width");
  // 100,000 links on one line, two of them with the same name.
  std::string links;
  for (std::size_t i = 0; i < kHuge; ++i) links += "<link name=\"l" + std::to_string(i) + "\"/>";
  urdfRefused(w, kRobotOpen + links + "<link name=\"l7\"/>\n</robot>\n", "turtlebot3_burger\\.urdf:[0-9]+:[0-9]+: error: ");
  std::string attributes;
  for (std::size_t i = 0; i < kHuge; ++i) attributes += " a" + std::to_string(i) + "=\"1\"";
  urdfRefused(w, kXmlHead + "<robot name=\"TurtlebotBurger\"" + attributes + ">\n</robot>\n",
              "turtlebot3_burger\\.urdf:2:1: error: element <robot> has more than 1000 attributes");
}

TEST(HostileUrdf, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("urdf_size");
  urdfRefused(w, kRobotOpen + megabytes("<!-- ", " -->", 40000, "<link\n"), "turtlebot3_burger\\.urdf:40003:1: error: malformed XML");
  urdfRefused(w, "", "turtlebot3_burger\\.urdf:1:1: error: malformed XML: the document is empty", Where::Position);
  urdfRefused(w, garbage(1 << 20), "turtlebot3_burger\\.urdf:1:2: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  urdfRefused(w, kXmlHead + "<robot name=\"Turtlebot" + kBadUtf8 + "\">\n<link name=\"base\"/>\n</robot>\n",
              "turtlebot3_burger\\.urdf:2:23: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
}

TEST(HostileUrdf, MissingFileMissingFolderAndAFolder) {
  Work w("urdf_path");
  refused(w, {"lint", w.mission(), "--strategy", w.strategy(), "--robots", w.at("no_such_folder")},
          "strategy\\.xml:[0-9]+:[0-9]+: error: cannot read robot description: --robots '[^']*no_such_folder' has no 'turtlebot3_burger\\.urdf'",
          Where::Caret, "strategy.xml");
  const fs::path dir = robotsLike(w, "folder_case");
  fs::remove(dir / "turtlebot3_burger.urdf");
  fs::create_directories(dir / "turtlebot3_burger.urdf");
  refused(w, {"lint", w.mission(), "--strategy", w.strategy(), "--robots", dir.string()},
          "strategy\\.xml:[0-9]+:[0-9]+: error: cannot read robot description: cannot read '[^']*turtlebot3_burger\\.urdf': it is a folder",
          Where::Caret, "strategy.xml");
  fs::remove(w.urdf());
  refused(w, {"lint", w.mission(), "--strategy", w.strategy()},
          "strategy\\.xml:[0-9]+:[0-9]+: error: cannot read robot description: no file '[^']*turtlebot3_burger\\.urdf'", Where::Caret, "strategy.xml");
}

// ---- IR files (.ir, read by check) --------------------------------------------------------------

const std::string kIrHead = "semo-ir 1;\nvar x : 0..1 = 0;\n";

void irRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.ir");
  writeFile(path, text);
  refused(w, {"check", path}, diagnostic, where, "hostile.ir");
}

TEST(HostileIr, NestingFarPastTheLimit) {
  Work w("ir_depth");
  irRefused(w, kIrHead + "rule r : " + repeat("(", kHuge) + "x == 0" + repeat(")", kHuge) + " -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  irRefused(w, kIrHead + "rule r : " + repeat("!", kHuge) + "(x == 0) -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  irRefused(w, kIrHead + "rule r : " + repeat("x == 0 => ", kHuge) + "x == 0 -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  irRefused(w, kIrHead + "rule r : " + repeat("x == 0 ? 1 : ", kHuge) + "0 == 1 -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  // A chain of a non-associative operator nests one level per operator.
  irRefused(w, kIrHead + "rule r : x" + repeat(" - 1", kHuge) + " == 0 -> x' = 1;\n", "hostile\\.ir:3:[0-9]+: error: expression nested too deeply");
  // Ten times as long (4 MB): the tree was once built before its depth was measured, and its
  // recursive destructor overflowed the stack (a crash in the release build too).
  irRefused(w, kIrHead + "rule r : x" + repeat(" - 1", 10 * kHuge) + " == 0 -> x' = 1;\n", "hostile\\.ir:3:[0-9]+: error: expression nested too deeply");
  irRefused(w, kIrHead + "rule r : x == 0 -> x' = 1;\nproperty p : " + repeat("always ", kHuge) + "{x == 0};\n",
            "hostile\\.ir:4:[0-9]+: error: formula nested too deeply");
  irRefused(w, kIrHead + "rule r : x == 0 -> x' = 1;\nproperty p : " + repeat("(", kHuge) + "{x == 0}" + repeat(")", kHuge) + ";\n",
            "hostile\\.ir:4:[0-9]+: error: formula nested too deeply");
}

TEST(HostileIr, AHundredThousandItemsOnOneLine) {
  Work w("ir_width");
  // A guard of 100,000 conjuncts (read into a balanced tree), the last naming no variable.
  std::string terms;
  for (std::size_t i = 0; i < kHuge; ++i) terms += "x == 0 && ";
  irRefused(w, kIrHead + "rule r : " + terms + "nosuch == 0 -> x' = 1;\n", "hostile\\.ir:3:1000010: error: undeclared variable 'nosuch'");
  // 100,000 variables declared on one line, then a stray word.
  std::string vars;
  for (std::size_t i = 0; i < kHuge; ++i) vars += "var v" + std::to_string(i) + " : bool = false; ";
  irRefused(w, "semo-ir 1;\n" + vars + "nosuch\n", "hostile\\.ir:2:[0-9]+: error: expected 'var', 'rule'[^\n]*found 'nosuch'");
  // 100,000 robots named.
  std::string robots;
  for (std::size_t i = 0; i < kHuge; ++i) robots += " r" + std::to_string(i);
  irRefused(w, "semo-ir 1;\nrobots" + robots + " r7;\n" + "var x : 0..1 = 0;\n", "hostile\\.ir:2:[0-9]+: error: ");
  // An array of a billion elements.
  irRefused(w, "semo-ir 1;\nvar a[1000000000] : bool = false;\n", "hostile\\.ir:2:[0-9]+: error: an array has at most");
}

TEST(HostileIr, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("ir_size");
  irRefused(w, "semo-ir 1;\n" + megabytes("# ", "", 40000, "var x : 0..1 = 0;\nbroken\n"), "hostile\\.ir:40003:1: error: ");
  irRefused(w, "", "hostile\\.ir:1:1: error: expected 'semo-ir'", Where::Position);
  irRefused(w, garbage(1 << 20), "hostile\\.ir:1:1: error: ");
  irRefused(w, "semo-ir 1;\nvar " + kBadUtf8 + " : bool = false;\n", "hostile\\.ir:2:5: error: unexpected character");
  // Not UTF-8 in a label: `check` (without --json) once died of it, writing the counterexample.
  const std::string path = w.at("hostile.ir");
  writeFile(path, slurp(w.ir()) + "rule r2 @robot(r0) @label(\"go" + kBadUtf8 + "\") : false -> busy' = true;\n");
  for (const char* json : {"--safety-only", "--json"}) {
    refused(w, {"check", path, json}, "hostile\\.ir:[0-9]+:30: error: a string must be UTF-8 text: byte 0x80 is not", Where::Caret, "hostile.ir");
  }
  irRefused(w, std::string("semo-ir 1;\nvar x") + '\0' + " : bool = false;\n", "hostile\\.ir:2:6: error: ");
}

TEST(HostileIr, MissingFileAndAFolder) {
  Work w("ir_path");
  refused(w, {"check", w.at("no_such.ir")}, "error: cannot open '[^']*no_such\\.ir'", Where::NoPosition);
  refused(w, {"analyze", w.at("no_such.ir")}, "error: cannot open '[^']*no_such\\.ir'", Where::NoPosition);
  fs::create_directories(w.at("folder.ir"));
  refused(w, {"check", w.at("folder.ir")}, "error: cannot read '[^']*folder\\.ir': it is a folder, not a file", Where::NoPosition);
  refused(w, {"export", "--ir", w.at("folder.ir")}, "error: cannot read '[^']*folder\\.ir': it is a folder", Where::NoPosition);
}

// ---- task graphs (sdf --graph, JSON) -------------------------------------------------------------

void taskGraphRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.json");
  writeFile(path, text);
  refused(w, {"sdf", "--graph", path}, diagnostic, where, "hostile.json");
}

TEST(HostileTaskGraph, NestingFarPastTheLimit) {
  Work w("taskgraph_depth");
  taskGraphRefused(w, repeat("[", kHuge) + repeat("]", kHuge), "hostile\\.json:1:257: error: nested too deeply \\(limit 256\\)");
  taskGraphRefused(w, repeat("{\"a\":", kHuge) + "1" + repeat("}", kHuge), "hostile\\.json:1:1281: error: nested too deeply \\(limit 256\\)");
  taskGraphRefused(w, repeat("[", kHuge), "hostile\\.json:1:257: error: nested too deeply");
  // Inside a real task graph, under a member the reader ignores.
  std::string graph = slurp(w.taskGraph());
  graph.insert(graph.find('{') + 1, "\"_deep\": " + repeat("[", kHuge) + repeat("]", kHuge) + ",");
  taskGraphRefused(w, graph, "hostile\\.json:[0-9]+:[0-9]+: error: nested too deeply \\(limit 256\\)");
}

TEST(HostileTaskGraph, AHundredThousandItemsOnOneLine) {
  Work w("taskgraph_width");
  nlohmann::json g = nlohmann::json::parse(slurp(w.taskGraph()));
  for (std::size_t i = 0; i < kHuge; ++i) g["tasks"].push_back({{"name", "t" + std::to_string(i)}, {"kind", "service"}, {"execMicros", 1}, {"ports", nlohmann::json::array()}});
  g["channels"].push_back({{"name", "bad"}, {"from", "nosuch.x"}, {"to", "planner.goal"}, {"initialTokens", 0}});
  taskGraphRefused(w, g.dump(), "hostile\\.json:1:[0-9]+: error: no task named 'nosuch'");
}

TEST(HostileTaskGraph, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("taskgraph_size");
  taskGraphRefused(w, "{\"pad\": \"" + std::string(4 << 20, 'z') + "\", \"x\": ]}", "hostile\\.json:1:" + std::to_string((4 << 20) + 18) + ": error: not valid JSON");
  taskGraphRefused(w, "", "hostile\\.json:1:1: error: not valid JSON", Where::Position);
  taskGraphRefused(w, garbage(1 << 20), "hostile\\.json:1:4: error: not valid JSON: a NUL byte");
  taskGraphRefused(w, "{\"format\": \"semo-taskgraph\", \"robot\": \"" + kBadUtf8 + "\"}", "hostile\\.json:1:40: error: not valid JSON");
}

TEST(HostileTaskGraph, MissingFileAndAFolder) {
  Work w("taskgraph_path");
  refused(w, {"sdf", "--graph", w.at("no_such.json")}, "error: cannot open '[^']*no_such\\.json'", Where::NoPosition);
  refused(w, {"sdf", "--graph", w.at("robots")}, "error: cannot read '[^']*robots': it is a folder, not a file", Where::NoPosition);
}

// ---- SDF3 graphs (sdf --sdf3, XML) ---------------------------------------------------------------

void sdf3Refused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.xml");
  writeFile(path, text);
  refused(w, {"sdf", "--sdf3", path}, diagnostic, where, "hostile.xml");
}

const std::string kSdf3Open = kXmlHead + "<sdf3 type=\"sdf\" version=\"1.0\">\n<applicationGraph name=\"g\">\n<sdf name=\"g\" type=\"G\">\n";
const std::string kSdf3Close = "</sdf>\n</applicationGraph>\n</sdf3>\n";

TEST(HostileSdf3, NestingFarPastTheLimit) {
  Work w("sdf3_depth");
  sdf3Refused(w, kSdf3Open + repeat("<actor name=\"a\" type=\"A\">", kHuge) + repeat("</actor>", kHuge) + kSdf3Close,
              "hostile\\.xml:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
  sdf3Refused(w, kSdf3Open + repeat("<x>", kHuge), "hostile\\.xml:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
}

TEST(HostileSdf3, AHundredThousandItemsOnOneLine) {
  Work w("sdf3_width");
  // A ring of 100,000 actors on one line, and a channel from an actor that does not exist.
  std::string actors, channels;
  for (std::size_t i = 0; i < kHuge; ++i) {
    const std::string a = "a" + std::to_string(i);
    actors += "<actor name=\"" + a + "\" type=\"A\"><port name=\"i\" type=\"in\" rate=\"1\"/><port name=\"o\" type=\"out\" rate=\"1\"/></actor>";
    channels += "<channel name=\"c" + std::to_string(i) + "\" srcActor=\"" + a + "\" srcPort=\"o\" dstActor=\"a" + std::to_string((i + 1) % kHuge) +
                "\" dstPort=\"i\"" + (i + 1 == kHuge ? " initialTokens=\"1\"" : "") + "/>";
  }
  sdf3Refused(w, kSdf3Open + actors + channels + "<channel name=\"bad\" srcActor=\"nosuch\" srcPort=\"o\" dstActor=\"a0\" dstPort=\"i\"/>\n" + kSdf3Close,
              "hostile\\.xml:5:[0-9]+: error: no actor named 'nosuch'");
  std::string attributes;
  for (std::size_t i = 0; i < kHuge; ++i) attributes += " a" + std::to_string(i) + "=\"1\"";
  sdf3Refused(w, kXmlHead + "<sdf3 type=\"sdf\" version=\"1.0\"" + attributes + ">\n</sdf3>\n",
              "hostile\\.xml:2:1: error: element <sdf3> has more than 1000 attributes");
}

TEST(HostileSdf3, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("sdf3_size");
  sdf3Refused(w, kSdf3Open + megabytes("<!-- ", " -->", 40000, "<actor\n"), "hostile\\.xml:40005:1: error: malformed XML");
  sdf3Refused(w, "", "hostile\\.xml:1:1: error: malformed XML: the document is empty", Where::Position);
  sdf3Refused(w, garbage(1 << 20), "hostile\\.xml:1:2: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  // An actor's name not UTF-8: `sdf --sdf3 --json` once died of it (nlohmann::json refuses to write it).
  const std::string path = w.at("hostile.xml");
  writeFile(path, kSdf3Open + "<actor name=\"" + kBadUtf8 + "\" type=\"A\"/>\n" + kSdf3Close);
  for (const char* json : {"--verbose", "--json"}) {
    refused(w, {"sdf", "--sdf3", path, json}, "hostile\\.xml:5:14: error: malformed XML: not UTF-8 text \\(byte 0x80\\)", Where::Caret, "hostile.xml");
  }
}

TEST(HostileSdf3, MissingFileAndAFolder) {
  Work w("sdf3_path");
  refused(w, {"sdf", "--sdf3", w.at("no_such.xml")}, "error: cannot open '[^']*no_such\\.xml'", Where::NoPosition);
  refused(w, {"sdf", "--sdf3", w.at("robots")}, "error: cannot read '[^']*robots': it is a folder, not a file", Where::NoPosition);
}

// ---- counterexample traces (show, replay; JSON) ---------------------------------------------------

void traceRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.json");
  writeFile(path, text);
  for (const char* command : {"show", "replay"}) refused(w, {command, path}, diagnostic, where, "hostile.json");
}

TEST(HostileTrace, NestingFarPastTheLimit) {
  Work w("trace_depth");
  const std::string trace = slurp(w.trace());
  traceRefused(w, "{\"pad\": " + repeat("[", kHuge) + repeat("]", kHuge) + ", " + trace.substr(trace.find('{') + 1),
               "hostile\\.json:1:[0-9]+: error: nested (too deeply|more than 64 levels)");
  traceRefused(w, repeat("{\"a\":", kHuge), "hostile\\.json:1:[0-9]+: error: nested (too deeply|more than 64 levels)");
  // Deeper than a trace ever is (64) but within the JSON limit: the trace reader refuses it.
  traceRefused(w, "{\"pad\": " + repeat("[", 100) + repeat("]", 100) + ", " + trace.substr(trace.find('{') + 1),
               "hostile\\.json:[0-9]+:[0-9]+: error: nested more than 64 levels deep: not a trace");
}

TEST(HostileTrace, AHundredThousandItemsOnOneLine) {
  Work w("trace_width");
  nlohmann::json t = nlohmann::json::parse(slurp(w.trace()));
  nlohmann::json properties = nlohmann::json::array();
  for (std::size_t i = 0; i < kHuge; ++i) properties.push_back({{"name", "p" + std::to_string(i)}, {"verdict", "proven"}, {"type", "safety"}});
  for (nlohmann::json& p : t["properties"]) {
    if (p.contains("counterexample")) p["counterexample"]["steps"][0]["rule"] = "nosuch.rule";
    properties.push_back(p);
  }
  t["properties"] = properties;
  traceRefused(w, t.dump(), "hostile\\.json:1:[0-9]+: error: step 1: unknown rule 'nosuch\\.rule'");
}

TEST(HostileTrace, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("trace_size");
  traceRefused(w, "{\"pad\": \"" + std::string(4 << 20, 'z') + "\", \"x\": ]}", "hostile\\.json:1:" + std::to_string((4 << 20) + 18) + ": error: not valid JSON");
  traceRefused(w, "", "hostile\\.json:1:1: error: not valid JSON", Where::Position);
  traceRefused(w, garbage(1 << 20), "hostile\\.json:1:4: error: not valid JSON: a NUL byte");
  std::string trace = slurp(w.trace());
  trace.insert(trace.find('{') + 1, "\"bad\": \"" + kBadUtf8 + "\",");
  traceRefused(w, trace, "hostile\\.json:1:[0-9]+: error: not valid JSON[^\n]*UTF-8");
}

TEST(HostileTrace, MissingFileAndAFolder) {
  Work w("trace_path");
  for (const char* command : {"show", "replay"}) {
    refused(w, {command, w.at("no_such.json")}, "error: cannot open '[^']*no_such\\.json'", Where::NoPosition);
    refused(w, {command, w.at("robots")}, "error: cannot read '[^']*robots': it is a folder, not a file", Where::NoPosition);
  }
}

// ---- worlds (simulate --world, JSON) --------------------------------------------------------------

void worldRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("missions/hostile.world.json");
  writeFile(path, text);
  refused(w, {"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--world", path, "--no-dataflow"}, diagnostic, where, "hostile.world.json");
}

TEST(HostileWorld, NestingFarPastTheLimit) {
  Work w("world_depth");
  worldRefused(w, repeat("[", kHuge) + repeat("]", kHuge), "hostile\\.world\\.json:1:65: error: nesting deeper than 64 levels");
  worldRefused(w, repeat("{\"a\":", kHuge), "hostile\\.world\\.json:1:[0-9]+: error: nesting deeper than 64 levels");
  std::string world = slurp(w.world());
  world.insert(world.find('{') + 1, "\"_deep\": " + repeat("[", kHuge) + repeat("]", kHuge) + ",");
  worldRefused(w, world, "hostile\\.world\\.json:[0-9]+:[0-9]+: error: nesting deeper than 64 levels");
}

TEST(HostileWorld, AHundredThousandItemsOnOneLine) {
  Work w("world_width");
  nlohmann::json world = nlohmann::json::parse(slurp(w.world()));
  for (std::size_t i = 0; i < kHuge; ++i) world["obstacles"].push_back({{"name", "o" + std::to_string(i)}, {"circle", {{"at", {i, 100}}, {"radius", 0.1}}}});
  world["obstacles"].push_back({{"name", "bad"}, {"circle", {{"at", {1, 1}}, {"radius", -1}}}});
  worldRefused(w, world.dump(), "hostile\\.world\\.json:1:[0-9]+: error: a radius must be greater than 0");
  // 100,000 members given twice on one line: an error each, each with a window of the line.
  std::string text = slurp(w.world());
  text.insert(text.find('{') + 1, repeat("\"places\": {}, ", kHuge));
  const std::string path = w.at("missions/hostile.world.json");
  writeFile(path, text);
  const Outcome o = refused(w, {"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--world", path, "--no-dataflow"},
                            "hostile\\.world\\.json:1:[0-9]+: error: member 'places' given twice", Where::Caret, "hostile.world.json");
  EXPECT_LT(o.err.size(), kHuge * 1000);
}

TEST(HostileWorld, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("world_size");
  worldRefused(w, "{\"pad\": \"" + std::string(4 << 20, 'z') + "\", \"x\": ]}", "hostile\\.world\\.json:1:" + std::to_string((4 << 20) + 18) + ": error: not valid JSON");
  worldRefused(w, "", "hostile\\.world\\.json:1:1: error: not valid JSON", Where::Position);
  worldRefused(w, garbage(1 << 20), "hostile\\.world\\.json:1:4: error: not valid JSON: a NUL byte");
  std::string world = slurp(w.world());
  world.insert(world.find('{') + 1, "\"_bad\": \"" + kBadUtf8 + "\",");
  worldRefused(w, world, "hostile\\.world\\.json:1:[0-9]+: error: not valid JSON[^\n]*UTF-8");
}

TEST(HostileWorld, MissingFileAndAFolder) {
  Work w("world_path");
  const std::vector<std::string> base{"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--no-dataflow", "--world"};
  auto with = [&](const std::string& world) {
    std::vector<std::string> args = base;
    args.push_back(world);
    return args;
  };
  refused(w, with(w.at("no_such.world.json")), "no_such\\.world\\.json: error: cannot read the world file", Where::NoPosition);
  refused(w, with(w.at("robots")), "robots: error: cannot read the world file", Where::NoPosition);
  // No --world, and no MISSION.world.json beside the mission.
  fs::remove(w.world());
  refused(w, {"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--no-dataflow"}, "error: no world given and no [^\n]*swarm3\\.world\\.json",
          Where::NoPosition);
}

// ---- a small mission that asks for a huge model -------------------------------------------------

// One line of a mission declares a team of 100,000 robots (the language's limit, which lint accepts
// in a tenth of a second). The commands that build the model or the task graphs must end in time,
// with an error or a limit (exit 2 or 3), not by running out of memory.
TEST(HostileMission, AHundredThousandRobotsInOneTeam) {
  GTEST_SKIP() << "defect: with legged[100000] the translation is linear (export --ir writes 387 MB in 26 s, exit 0, where "
                  "this test wants a budget: exit 3), and check --engine auto proves the mission by counting its robots, but the "
                  "default check (the explicit engine, finding the interchangeable robots), sdf, analyze and simulate run past 60 s "
                  "(memory running out is exit 3, e2e.Progress.ATeamTooLargeForTheMemoryEndsAsALimitNotASignal)";
  Work w("mission_many_robots");
  std::string mission = slurp(w.swarm());
  mission.replace(mission.find("legged[3]"), 9, "legged[100000]");
  writeFile(w.swarm(), mission);
  const std::vector<std::string> model{w.swarm(), "-s", w.swarmStrategy()};
  auto with = [&](std::vector<std::string> head, std::vector<std::string> tail = {}) {
    head.insert(head.end(), model.begin(), model.end());
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
  };
  for (const std::vector<std::string>& args :
       {with({"check"}, {"--max-states", "1000", "--safety-only"}), with({"export", "--ir"}, {"-o", w.at("model.ir")}), with({"sdf"}),
        with({"analyze"}, {"--loss-prob", "0.2"}), with({"simulate"}, {"--no-dataflow"})}) {
    const Snapshot before = snapshot(w.in);
    const Outcome o = run(args, w.log);
    EXPECT_EQ(o.signal, 0) << args[0] << ": " << o.err.substr(0, 2000);
    EXPECT_FALSE(o.timedOut) << args[0];
    EXPECT_TRUE(o.exit == 2 || o.exit == 3) << args[0] << ": exit " << o.exit;
    EXPECT_EQ(differences(before, snapshot(w.in)), "") << args[0];
  }
}

// ---- paths that are not UTF-8 -------------------------------------------------------------------

// A file name may hold any byte but '/' and NUL. JSON written about it (check --json, --trace-out)
// once died of one (nlohmann::json refuses to write bytes that are not UTF-8); it is written with
// U+FFFD in their place.
TEST(HostilePaths, FileNamesThatAreNotUtf8) {
  Work w("paths_not_utf8");
  const std::string model = w.at("mutex" + kBadUtf8 + ".ir");
  fs::copy_file(w.ir(), model);
  const std::string out = w.at("out" + kBadUtf8 + ".json");
  for (const std::vector<std::string>& args : {std::vector<std::string>{"check", model, "--json"}, std::vector<std::string>{"check", model, "--trace-out", out},
                                               std::vector<std::string>{"export", "--ir", model, "-o", out + ".ir"}}) {
    const Outcome o = run(args, w.log);
    EXPECT_EQ(o.signal, 0) << args[1] << " " << args[2] << ": " << o.err;
    EXPECT_EQ(o.exit, args[0] == "export" ? 0 : 1) << o.err;
  }
  EXPECT_TRUE(nlohmann::json::parse(slurp(out), nullptr, false).is_object()) << "the trace was written, as JSON";
  const Outcome o = run({"check", model, "--json"}, w.log);
  EXPECT_TRUE(nlohmann::json::parse(o.out, nullptr, false).is_object()) << o.out.substr(0, 500);
  // And the reading side: show reads the trace back, its "input" as written.
  const Outcome shown = run({"show", out, model}, w.log);
  EXPECT_EQ(shown.signal, 0) << shown.err;
  EXPECT_EQ(shown.exit, 0) << shown.err;
}

// ---- certificates (certify DIR reads DIR/certificate.json) --------------------------------------

TEST(HostileCertificate, DeepEmptyAndGarbage) {
  Work w("certificate");
  const fs::path dir = w.in / "emitted";
  auto certificate = [&](const std::string& text, const std::string& diagnostic, Where where) {
    writeFile(dir / "certificate.json", text);
    refused(w, {"certify", dir.string()}, diagnostic, where, "certificate.json");
  };
  certificate(repeat("[", kHuge), "certificate\\.json:1:257: error: nested too deeply", Where::Caret);
  certificate("", "certificate\\.json:1:1: error: not valid JSON", Where::Position);
  certificate(garbage(1 << 20), "certificate\\.json:1:4: error: not valid JSON: a NUL byte", Where::Caret);
  fs::remove_all(dir);
  refused(w, {"certify", dir.string()}, "error: cannot read [^\n]*certificate\\.json", Where::NoPosition);
}

}  // namespace
