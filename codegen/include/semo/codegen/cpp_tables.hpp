#pragma once
// The runtime's tables as C++ source and back (specs/certificate.md, "Generated tables"): `emit`
// writes each table as one aggregate initializer with designated members (a member at its default
// value is left out; a row of a plan is one line, with its IR rule and mission origin in a comment);
// `certify` reads that initializer back, without a C++ compiler, into the same structs, and compares
// them with the tables projected afresh from the inputs, saying where they first differ.
//
// The syntax read is exactly the syntax written: braces, `.member = value`, integers, `kNone`,
// decimal and exponent numbers, string literals with C escapes, and the qualified enumerator names
// (`GuardRow::Kind::InMode`). Comments are skipped. Nesting is limited (kMaxDepth).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"
#include "semo/runtime/tables.hpp"

namespace semo::codegen::cpp {

// ------------------------------------------------------------------ writing

// The comment after a row's line ("R17 ev3_0: Search ... (scouting.semo:40:5)"); empty: none.
using RowComment = std::function<std::string(const runtime::Row&)>;

// `{ ... }` for the shared tables (MissionTables with each robot's identity only) and for one
// robot's table, starting at column `indent` (the first line is not indented: it follows `= `).
std::string missionInitializer(const runtime::MissionTables& shared, int indent);
std::string robotInitializer(const runtime::RobotTable& robot, const RowComment& comment, int indent);
// One value on one line, as the initializers write it (messages of certify).
std::string rowText(const runtime::Row& row);

// The line (1-based, within the text robotInitializer returned) of each row, per plan: the trace map.
struct RowLine {
  std::size_t plan = 0, row = 0;
  std::uint32_t line = 0;
};
std::vector<RowLine> rowLines(const runtime::RobotTable& robot, std::string_view initializer);

// ------------------------------------------------------------------ reading

inline constexpr int kMaxDepth = 32;

struct Node {
  enum class Kind : std::uint8_t { List, Number, String, Name };
  Kind kind = Kind::List;
  SourceRange at;
  std::string text;            // Number, Name: as written; String: the value, escapes resolved
  std::string member;          // the element's designator (`.member = `), or empty
  std::vector<Node> elements;  // List
};

// The braced initializer that follows `declaration` (e.g. "static const RobotTable table") in
// `file`: nullopt with positioned errors when it is missing or malformed.
std::optional<Node> parseInitializer(const SourceManager& sources, FileId file, std::string_view declaration, DiagnosticEngine& diags);

// The node as a table: false with positioned errors (an unknown member, a member out of order, a
// value of the wrong kind or out of range).
bool readMission(const Node& node, runtime::MissionTables& out, DiagnosticEngine& diags);
bool readRobot(const Node& node, runtime::RobotTable& out, DiagnosticEngine& diags);

// ------------------------------------------------------------------ comparing

struct Difference {
  SourceRange at;         // where in the generated file (the member, or the list it is missing from)
  std::string path;       // "plans[1].rows[4].guards[0].index"
  std::string expected;   // the projection's value, as C++
  std::string actual;     // the file's
  std::uint32_t irRule = 0xffffffffu;  // the row's IR rule when the difference is in or about a row
  std::string what;       // in words, when more than "differs" ("no row for IR rule R17")
};

// The first difference between the projection (`expected`) and the tables read from a file
// (`actual`, read from `node`). Rows are matched by their IR rule first (a bijection: every rule of
// the robot's program has exactly one row), then compared member by member.
std::optional<Difference> compareMission(const runtime::MissionTables& expected, const runtime::MissionTables& actual, const Node& node);
std::optional<Difference> compareRobot(const runtime::RobotTable& expected, const runtime::RobotTable& actual, const Node& node);

}  // namespace semo::codegen::cpp
