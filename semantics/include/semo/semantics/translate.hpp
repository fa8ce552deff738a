#pragma once
// MissionModel + fault assumptions -> IR (specs/semantics.md). One translation serves every mission.
#include <optional>
#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/semantics/ir.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo {

struct TranslationOptions {
  std::optional<int> crashOverride;         // --crash N: every team may lose up to N robots
  std::optional<std::string> lossOverride;  // --loss none|publish|events|knowledge|heartbeats|all
  std::optional<bool> fairLossOverride;     // --fair-loss / --unfair-loss
};

// Returns nullopt (with diagnostics) when the mission uses something the translation cannot bound.
// `sources` names the mission files in the rules' origins.
std::optional<ir::Model> translate(const model::MissionModel& mission, const TranslationOptions& options,
                                   const SourceManager& sources, DiagnosticEngine& diags);

}  // namespace semo
