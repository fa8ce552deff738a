// The generated tables' C++ (codegen/cpp_tables.hpp): every shipped mission's projection written as
// initializers, read back without a compiler, equal to what was written (the structs' own
// operator==, which knows every member, so a member the schema forgot shows); and the reader's and
// the comparison's messages on edited text.
#include <gtest/gtest.h>

#include "mission_fixture.hpp"

#include "semo/codegen/cpp_tables.hpp"
#include "semo/codegen/project_dataflow.hpp"

namespace semo {
namespace {

using codegen::cpp::Node;

struct Parsed {
  SourceManager sources;
  std::optional<Node> node;
  std::string errors;
};

std::unique_ptr<Parsed> parse(const std::string& text, const std::string& declaration) {
  auto p = std::make_unique<Parsed>();
  DiagnosticEngine diags(p->sources);
  const FileId file = p->sources.add("tables.cpp", text);
  p->node = codegen::cpp::parseInitializer(p->sources, file, declaration, diags);
  for (const Diagnostic& d : diags.diagnostics()) p->errors += diags.format(d);
  return p;
}

// The robot table in `text` (nullopt when it does not parse or read); the parse tree, which the
// comparisons point into, stays in `parsed`.
std::optional<runtime::RobotTable> readRobotText(const std::string& text, std::unique_ptr<Parsed>& parsed) {
  parsed = parse(text, "static const RobotTable table");
  if (!parsed->node) return std::nullopt;
  runtime::RobotTable r;
  DiagnosticEngine d(parsed->sources);
  if (codegen::cpp::readRobot(*parsed->node, r, d)) return r;
  for (const Diagnostic& diag : d.diagnostics()) parsed->errors += d.format(diag);
  return std::nullopt;
}

runtime::MissionTables projected(const std::string& dir, const std::string& stem) {
  auto l = test::loadExample(dir, stem);
  EXPECT_TRUE(l);
  DiagnosticEngine diags(l->sources);
  EXPECT_TRUE(codegen::projectDataflow(*l->mission, l->tables, diags));
  return l->tables;
}

class RoundTrip : public ::testing::TestWithParam<std::pair<const char*, const char*>> {};

TEST_P(RoundTrip, EveryTableReadsBackEqual) {
  const runtime::MissionTables tables = projected(GetParam().first, GetParam().second);
  ASSERT_FALSE(tables.robots.empty());
  // The shared tables (robots by identity only).
  runtime::MissionTables shared = tables;
  for (runtime::RobotTable& r : shared.robots) {
    runtime::RobotTable id;
    id.name = r.name, id.type = r.type, id.team = r.team, id.indexInTeam = r.indexInTeam, id.geometry = r.geometry;
    r = id;
  }
  const std::string missionText = "static const MissionTables tables" + codegen::cpp::missionInitializer(shared, 2) + ";\n";
  auto m = parse(missionText, "static const MissionTables tables");
  ASSERT_TRUE(m->node) << m->errors;
  runtime::MissionTables back;
  DiagnosticEngine diags(m->sources);
  ASSERT_TRUE(codegen::cpp::readMission(*m->node, back, diags));
  EXPECT_TRUE(back == shared);
  EXPECT_FALSE(codegen::cpp::compareMission(shared, back, *m->node));

  for (const runtime::RobotTable& robot : tables.robots) {
    SCOPED_TRACE(robot.name);
    const std::string text = "static const RobotTable table" + codegen::cpp::robotInitializer(robot, {}, 2) + ";\n";
    std::unique_ptr<Parsed> p;
    const std::optional<runtime::RobotTable> r = readRobotText(text, p);
    ASSERT_TRUE(r) << p->errors;
    EXPECT_TRUE(*r == robot);
    EXPECT_FALSE(codegen::cpp::compareRobot(robot, *r, *p->node));
    // Every row is one line of its own.
    std::size_t rows = 0;
    for (const runtime::PlanTable& plan : robot.plans) rows += plan.rows.size();
    EXPECT_EQ(codegen::cpp::rowLines(robot, text).size(), rows);
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, RoundTrip,
                         ::testing::Values(std::pair{"scouting", "scouting"}, std::pair{"swarm", "swarm3"}, std::pair{"chase", "chase"},
                                           std::pair{"deployment", "deployment"}, std::pair{"patrol", "patrol"}));

// A robot table with one row, as text, to edit.
struct OneRobot {
  runtime::RobotTable robot;
  std::string text;
};

OneRobot scoutingRobot() {
  const runtime::MissionTables tables = projected("scouting", "scouting");
  OneRobot out;
  out.robot = tables.robots.at(1);
  out.text = "static const RobotTable table" + codegen::cpp::robotInitializer(out.robot, {}, 2) + ";\n";
  return out;
}

TEST(CppTables, AnEditedRowIsTheFirstDifferenceWithItsRuleAndLine) {
  OneRobot o = scoutingRobot();
  // Change the first row's target program counter: `.to = N` -> `.to = N+1` on its line.
  const runtime::Row& row = o.robot.plans.front().rows.empty() ? o.robot.plans.back().rows.front() : o.robot.plans.front().rows.front();
  const std::string line = codegen::cpp::rowText(row);
  const std::size_t at = o.text.find(line);
  ASSERT_NE(at, std::string::npos);
  std::string edited = o.text;
  const std::string to = ".to = " + std::to_string(row.to);
  const std::size_t toAt = edited.find(to, at);
  ASSERT_NE(toAt, std::string::npos);
  edited.replace(toAt, to.size(), ".to = " + std::to_string(row.to + 1));
  std::unique_ptr<Parsed> p;
  const std::optional<runtime::RobotTable> r = readRobotText(edited, p);
  ASSERT_TRUE(r) << p->errors;
  const auto diff = codegen::cpp::compareRobot(o.robot, *r, *p->node);
  ASSERT_TRUE(diff);
  EXPECT_NE(diff->path.find(".rows["), std::string::npos) << diff->path;
  EXPECT_TRUE(diff->path.ends_with(".to")) << diff->path;
  EXPECT_EQ(diff->irRule, row.irRule) << "a difference inside a row names the row's rule";
  EXPECT_EQ(diff->expected, std::to_string(row.to));
  EXPECT_EQ(diff->actual, std::to_string(row.to + 1));
  const auto lineNo = static_cast<std::uint32_t>(std::count(edited.begin(), edited.begin() + static_cast<std::ptrdiff_t>(toAt), '\n') + 1);
  EXPECT_EQ(diff->at.begin.line, lineNo);
}

TEST(CppTables, ARemovedRowIsARuleWithoutARow) {
  OneRobot o = scoutingRobot();
  const runtime::PlanTable* plan = nullptr;
  for (const runtime::PlanTable& p : o.robot.plans) {
    if (!p.rows.empty() && p.rows.front().irRule != runtime::kNone) plan = &p;
  }
  ASSERT_NE(plan, nullptr);
  const runtime::Row& row = plan->rows.front();
  const std::string line = codegen::cpp::rowText(row) + ",";
  std::string edited = o.text;
  const std::size_t at = edited.find(line);
  ASSERT_NE(at, std::string::npos);
  edited.erase(at, line.size());
  std::unique_ptr<Parsed> p;
  const std::optional<runtime::RobotTable> r = readRobotText(edited, p);
  ASSERT_TRUE(r) << p->errors;
  const auto diff = codegen::cpp::compareRobot(o.robot, *r, *p->node);
  ASSERT_TRUE(diff);
  EXPECT_EQ(diff->irRule, row.irRule);
  EXPECT_NE(diff->what.find("has no row for this IR rule"), std::string::npos) << diff->what;
}

TEST(CppTables, MalformedTextGetsPositionedErrors) {
  struct Case {
    const char* text;
    const char* message;
  };
  for (const Case& c : {Case{"static const RobotTable table{.name = \"a\", .nme = \"b\"};", "'.nme' is not a member here"},
                        Case{"static const RobotTable table{.name = 3};", "expected a string literal"},
                        Case{"static const RobotTable table{.team = -1};", "expected an integer in range"},
                        Case{"static const RobotTable table{.team = 1,", "a '}' is missing"},
                        Case{"static const RobotTable table{.type = \"x\", .name = \"a\"};", "out of order"},
                        Case{"static const RobotTable table{.name = \"unterminated};", "unterminated string"},
                        Case{"static const RobotTable table{.geometry = {.wheeled = maybe}};", "expected true or false"},
                        Case{"static const RobotTable table{.plans = {{.rows = {{.guards = {{.kind = GuardRow::Kind::Nope}}}}}}};",
                             "expected one of GuardRow::Kind::"},
                        Case{"static const OtherTable table{};", "no 'static const RobotTable table' in this file"}}) {
    SCOPED_TRACE(c.text);
    auto p = parse(c.text, "static const RobotTable table");
    runtime::RobotTable r;
    DiagnosticEngine d(p->sources);
    const bool read = p->node && codegen::cpp::readRobot(*p->node, r, d);
    EXPECT_FALSE(read);
    for (const Diagnostic& diag : d.diagnostics()) p->errors += d.format(diag);
    EXPECT_NE(p->errors.find(c.message), std::string::npos) << p->errors;
    EXPECT_NE(p->errors.find("tables.cpp:"), std::string::npos) << p->errors;
  }
  // Nesting beyond the limit is refused, not recursed into.
  std::string deep = "static const RobotTable table";
  for (int i = 0; i < 10000; ++i) deep += "{";
  auto p = parse(deep, "static const RobotTable table");
  EXPECT_FALSE(p->node);
  EXPECT_NE(p->errors.find("nested deeper than"), std::string::npos) << p->errors;
}

}  // namespace
}  // namespace semo
