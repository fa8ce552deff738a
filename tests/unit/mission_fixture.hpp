#pragma once
// A shipped mission loaded, translated and projected, for the unit tests of what runs (projection,
// simulation, dataflow, replay). Paths are relative to specs/, unless absolute.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "semo/codegen/project.hpp"
#include "semo/runtime/world.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::test {

struct LoadedMission {
  SourceManager sources;
  std::optional<model::MissionModel> mission;
  std::optional<Translation> translation;
  runtime::MissionTables tables;
  std::optional<runtime::World> world;  // when a world file was given and reads
};

// Null when the mission does not load or translate.
inline std::unique_ptr<LoadedMission> loadSpec(const std::string& mission, const std::string& strategy, const std::string& world = {}) {
  auto l = std::make_unique<LoadedMission>();
  DiagnosticEngine diags(l->sources);
  const std::string specs = std::string(SEMO_SOURCE_DIR) + "/specs/";
  auto at = [&](const std::string& path) { return !path.empty() && path.front() == '/' ? path : specs + path; };
  l->mission = loadMission({at(mission), at(strategy), std::nullopt}, l->sources, diags);
  if (!l->mission) return nullptr;
  l->translation = translateMission(*l->mission, {}, l->sources, diags);
  if (!l->translation) return nullptr;
  l->tables = codegen::project(*l->mission, *l->translation, l->sources);
  if (!world.empty()) {
    std::vector<runtime::WorldError> errors;
    l->world = runtime::readWorld(at(world), errors);
  }
  return l;
}

// specs/examples/DIR/STEM.semo with STRATEGY of that folder and STEM.world.json.
inline std::unique_ptr<LoadedMission> loadExample(const std::string& dir, const std::string& stem, const std::string& strategy = "strategy.xml") {
  const std::string base = "examples/" + dir + "/";
  return loadSpec(base + stem + ".semo", base + strategy, base + stem + ".world.json");
}

}  // namespace semo::test
