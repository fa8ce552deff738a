#pragma once
#include "semo/frontend/ast.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo {

// Resolves every name of the mission against itself, the strategy and the robot catalog, and builds
// the MissionModel. Errors and warnings go to `diags`; when diags.hasErrors() the model is
// incomplete and must not be used for verification.
model::MissionModel elaborate(const ast::Mission& mission, strategy::Strategy strategy, RobotCatalog catalog,
                              DiagnosticEngine& diags);

}  // namespace semo
