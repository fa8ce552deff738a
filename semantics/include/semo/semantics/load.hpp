#pragma once
// The whole front half in one call: read mission, strategy and robots, elaborate. Used by every
// subcommand of semo-verify and by the diagnostic tests, so that they see exactly the same thing.
#include <optional>
#include <string>

#include "semo/semantics/mission_model.hpp"

namespace semo {

struct MissionInputs {
  std::string mission;
  std::string strategy;
  std::optional<std::string> robotsDir;
};

// Returns the model, or nullopt if any error was reported (all of them are in `diags`). Elaboration
// is skipped when the mission does not parse or the strategy or a robot cannot be read, since its
// diagnostics would only repeat those errors.
std::optional<model::MissionModel> loadMission(const MissionInputs& inputs, SourceManager& sources, DiagnosticEngine& diags);

}  // namespace semo
