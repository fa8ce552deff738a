#pragma once
// MissionModel + fault assumptions -> IR (specs/semantics.md). One translation serves every mission.
#include <map>
#include <optional>
#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/semantics/ir.hpp"
#include "semo/semantics/lowering.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo {

struct TranslationOptions {
  std::optional<int> crashOverride;         // --crash N: every team may lose up to N robots
  std::optional<std::string> lossOverride;  // --loss none|publish|events|knowledge|heartbeats|all, or a list: events,publish
  std::optional<bool> fairLossOverride;     // --fair-loss / --unfair-loss
  std::map<std::string, int> crashPerTeam;  // --crash N:TEAM: that team may lose up to N robots (before crashOverride)
  // Teams of more robots than this get counts (specs/semantics.md, "Counts of a large team"): a
  // robot's rules read how many teammates hold a number of facts or stand at some program points,
  // not each teammate, so the model grows linearly with the team. Both forms mean the same runs;
  // the option is for tests that compare them.
  std::size_t countTeamsAbove = 8;
};

// The IR of a mission and what its variables and rules mean (lowering.hpp), index for index.
struct Translation {
  ir::Model model;
  lowering::Lowering lowering;
};

// Returns nullopt (with diagnostics) when the mission uses something the translation cannot bound.
// `sources` names the mission files in the rules' origins. The lowering points into `mission`.
std::optional<Translation> translateMission(const model::MissionModel& mission, const TranslationOptions& options,
                                            const SourceManager& sources, DiagnosticEngine& diags);

// The IR alone (what every verification engine reads).
std::optional<ir::Model> translate(const model::MissionModel& mission, const TranslationOptions& options,
                                   const SourceManager& sources, DiagnosticEngine& diags);

}  // namespace semo
