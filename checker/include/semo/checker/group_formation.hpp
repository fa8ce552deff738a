#pragma once
// Group formation for every crash set, decided with Z3: a `[[ ]]` block can be formed from the live
// robots of its team when each arm other than `others` gets robots of its own, as many as its
// minimum size (MissionModel::armDemand: one, or the largest `min-robots` of the group services it
// calls; a robot joins at most one group; a leader block needs one leader). A crash set that leaves
// no robot of the team alive leaves nobody to form the block: it breaks nothing (the translation's
// invariants say the same, so every engine gives one verdict). By Hall's theorem (with a demand per arm) that
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
  std::int64_t teamSize = 0;                // robots of the block's team
  // Every crash set of at most this many robots leaves it formable: -1 when it cannot be formed even
  // with every robot alive, the team's size when no crash set breaks it.
  std::int64_t tolerated = 0;
  std::vector<std::string> breakingSet;     // a smallest crash set that breaks it
  std::vector<std::string> unmetArms;       // the arms that then cannot all get a robot
  [[nodiscard]] bool holds() const { return tolerated >= budget; }
  // The budget lets the whole team crash: then nobody is left to form the block, and it holds for
  // that crash set only vacuously.
  [[nodiscard]] bool vacuousAtBudget() const { return budget >= teamSize; }
};

// What a verdict that holds covers, in words: "every crash set of up to 2 robots leaves it formable;
// it tolerates 2", and when the budget lets the whole team crash, that it then holds vacuously.
std::string formationCoverage(const FormationVerdict& v);

// One verdict per block with at least one arm other than `others`, in block order. `crashBudget`
// (per team) replaces the mission's assumption when given (`check --crash N`).
std::vector<FormationVerdict> checkGroupFormation(const model::MissionModel& mission,
                                                  const std::vector<std::int64_t>* crashBudget = nullptr);

}  // namespace semo::checker
