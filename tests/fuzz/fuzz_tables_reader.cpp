// Fuzzes the reader of generated tables (codegen/cpp_tables.hpp) that `certify` trusts nothing to:
// any text either reads into a table, which then writes out and reads back equal, or gets positioned
// errors; the comparison with an empty table never fails to say where.
#include <cstddef>
#include <cstdint>
#include <string>

#include "semo/codegen/cpp_tables.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool robot : {true, false}) {
    semo::SourceManager sources;
    semo::DiagnosticEngine diags(sources);
    const semo::FileId file = sources.add("tables.cpp", text);
    const char* declaration = robot ? "static const RobotTable table" : "static const MissionTables tables";
    std::optional<semo::codegen::cpp::Node> node = semo::codegen::cpp::parseInitializer(sources, file, declaration, diags);
    for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
    if (!node) continue;
    if (robot) {
      semo::runtime::RobotTable t;
      if (!semo::codegen::cpp::readRobot(*node, t, diags)) continue;
      (void)semo::codegen::cpp::compareRobot(semo::runtime::RobotTable{}, t, *node);
      // What reads writes out and reads back to the same table.
      const std::string again = std::string(declaration) + semo::codegen::cpp::robotInitializer(t, {}, 2) + ";\n";
      semo::SourceManager s2;
      semo::DiagnosticEngine d2(s2);
      const semo::FileId f2 = s2.add("again.cpp", again);
      std::optional<semo::codegen::cpp::Node> n2 = semo::codegen::cpp::parseInitializer(s2, f2, declaration, d2);
      semo::runtime::RobotTable back;
      if (!n2 || !semo::codegen::cpp::readRobot(*n2, back, d2) || !(back == t)) __builtin_trap();
    } else {
      semo::runtime::MissionTables t;
      if (semo::codegen::cpp::readMission(*node, t, diags)) (void)semo::codegen::cpp::compareMission(semo::runtime::MissionTables{}, t, *node);
    }
  }
  return 0;
}
