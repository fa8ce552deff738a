#pragma once
// The IR of a shipped mission (specs/defects, specs/examples), for the unit tests of the engines
// and of the stepping API that run on real translations.
#include <gtest/gtest.h>

#include <optional>
#include <ostream>
#include <string>

#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::test {

struct ShippedMission {
  const char* mission;   // relative to the source tree
  const char* strategy;
};
// GoogleTest prints a parameter without PrintTo as its bytes, pointers included: ctest's names
// (gtest_discover_tests) then changed from build to build, and its measured times were lost.
inline void PrintTo(const ShippedMission& m, std::ostream* os) { *os << m.mission; }

// The IR of a mission, or nullopt with a test failure per diagnostic. Paths are relative to the
// source tree; they are given to the loader as SEMO_SOURCE_DIR "/" + path (the rules' origins
// name them so).
inline std::optional<ir::Model> translateShipped(const ShippedMission& m) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<ir::Model> model;
  if (auto mission = loadMission({SEMO_SOURCE_DIR "/" + std::string(m.mission), SEMO_SOURCE_DIR "/" + std::string(m.strategy), std::nullopt},
                                 sources, diags)) {
    model = translate(*mission, {}, sources, diags);
  }
  for (const Diagnostic& d : diags.diagnostics()) {
    if (d.severity == Severity::Error) ADD_FAILURE() << m.mission << ": " << diags.format(d);
  }
  return model;
}

// The safety defects, their twins and the examples.
inline std::vector<ShippedMission> shippedMissions() {
  const char* defects = "specs/defects/strategy.xml";
  return {{"specs/defects/blind_wait.semo", defects},
          {"specs/defects/blind_wait_fixed.semo", defects},
          {"specs/defects/circular_wait.semo", defects},
          {"specs/defects/double_receive.semo", defects},
          {"specs/defects/early_clear.semo", defects},
          {"specs/defects/flood.semo", defects},
          {"specs/defects/flood_fixed.semo", defects},
          {"specs/defects/leader_timeout.semo", "specs/defects/leader_timeout_short.xml"},
          {"specs/defects/lone_lidar.semo", defects},
          {"specs/defects/lost_report.semo", defects},
          {"specs/defects/type_group.semo", defects},
          {"specs/examples/scouting/scouting.semo", "specs/examples/scouting/strategy.xml"},
          {"specs/examples/swarm/swarm3.semo", "specs/examples/swarm/strategy.xml"},
          {"specs/examples/chase/chase.semo", "specs/examples/chase/strategy.xml"},
          {"specs/examples/deployment/deployment.semo", "specs/examples/deployment/strategy.xml"},
          {"specs/examples/patrol/patrol.semo", "specs/examples/patrol/strategy.xml"}};
}

}  // namespace semo::test
