#pragma once
// Replay (specs/runtime.md, "Replay"): the running team takes exactly the steps of a counterexample
// the checker found, one IR rule after another, with the choices the counterexample made (which
// robot moves, what the environment answers, which message is lost, who crashes) forced. Each rule
// is taken where the runtime takes it (the inverse of the projection's indices: ruleSites), by the
// same code that takes it in a free run; nothing is decided a second time.
//
// After the script, the team may run freely for a while (`settle`) with no loss and no crash:
// a deadlock shows as a team that takes no further step the model sees.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/runtime/sim_trace.hpp"
#include "semo/runtime/simulator.hpp"
#include "semo/runtime/tables.hpp"

namespace semo::runtime {

// Where the runtime takes one IR rule.
struct RuleSite {
  enum class Kind : std::uint8_t {
    None,             // no step of the runtime is this rule (a projection bug: reported, never guessed)
    Row,              // row `index` of plan `plan` of `robot`
    Crash,            // `robot` crashes
    EventDelivery,    // event `index` of robot's team reaches `robot`
    EventLoss,        // ... is lost on its way to `robot`
    MessageDelivery,  // the message slot of topic `index` reaches `robot`'s view
    MessageLoss,      // ... is lost
    ModeDefault,      // `robot` takes its mode `index`'s default (every plan done)
    Takeover,         // `robot` takes over leader block slot `index` (RobotTable::leaderBlocks)
    Discover,         // `robot` finds a fact: discover rule `index` (RobotTable::discoverRules)
    Learn,            // `robot` learns knowledge slot `index` from a live teammate, to `count` facts
    Heartbeat,        // a heartbeat period of leader block `index`; bit i of `extra`: the heartbeat to candidate i is lost
  };
  Kind kind = Kind::None;
  Id robot = kNone, plan = kNone, index = kNone;
  std::uint64_t extra = 0;
  std::int64_t count = 0;
};

// Per IR rule (MissionTables::rules), its site.
std::vector<RuleSite> ruleSites(const MissionTables& tables);

struct ReplayOptions {
  double pace = 0.5;    // seconds of simulated time between two steps of the script
  double settle = 0;    // seconds of free run after the script (0: none)
};

// Runs the script. The trace's summary gets a violation ("step K (RULE): the running team cannot
// take it: WHY") when the team cannot take a step, and the run stops there; the observer sees every
// step, as in simulate(), and may stop the run too. `options` gives the seed, the control period and
// the pose sampling; its loss and crash plans apply to the free run only (a replay passes none).
SimTrace replay(const MissionTables& tables, const World& world, const TaskLibrary& library, const std::vector<Id>& rules,
                const SimulationOptions& options, const ReplayOptions& replayOptions, StepObserver* observer = nullptr);

}  // namespace semo::runtime
