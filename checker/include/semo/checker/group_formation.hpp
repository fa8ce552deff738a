#pragma once
// Group formation for every crash set, decided with Z3: a `[[ ]]` block can be formed from the live
// robots of its team when each arm other than `others` gets robots of its own, as many as its
// minimum size (one, or the largest `min-robots` of the group services it calls; a robot joins at
// most one group; a leader block needs one leader). By Hall's theorem (with a demand per arm) that
// fails exactly when some set of arms has fewer live candidates, together, than the robots those
// arms need. The solver looks for the smallest crash set that makes this happen (minimised count of
// crashed robots), so one query per block gives both the smallest breaking crash set and the
// largest budget tolerated.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/semantics/mission_model.hpp"

namespace semo::checker {

struct FormationVerdict {
  model::Index blockIndex = 0;              // into MissionModel::groupBlocks
  std::string block;                        // "Relay (leader block)" or "Survey (block of 2 groups)"
  std::int64_t budget = 0;                  // crashes assumed in the block's team
  // Every crash set of at most this many robots leaves it formable: -1 when it cannot be formed even
  // with every robot alive, the team's size when no crash set breaks it.
  std::int64_t tolerated = 0;
  std::vector<std::string> breakingSet;     // a smallest crash set that breaks it
  std::vector<std::string> unmetArms;       // the arms that then cannot all get a robot
  [[nodiscard]] bool holds() const { return tolerated >= budget; }
};

// One verdict per block with at least one arm other than `others`, in block order. `crashBudget`
// (per team) replaces the mission's assumption when given (`check --crash N`).
std::vector<FormationVerdict> checkGroupFormation(const model::MissionModel& mission,
                                                  const std::vector<std::int64_t>* crashBudget = nullptr);

}  // namespace semo::checker
