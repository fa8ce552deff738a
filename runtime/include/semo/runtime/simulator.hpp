#pragma once
// The simulator (specs/runtime.md, "The simulator"): the whole team in one process, in simulated
// time, with crashes and message loss injected, each robot running its step tables. Discrete
// events in time order (ties in the order they were scheduled), every random choice drawn from
// streams derived from one seed: the same tables, world, options and seed give the same trace, byte
// for byte.
//
// Conformance: after every step the simulator maps the team's state onto the IR's variables (the
// abstraction function, MissionTables::abstraction) and hands both states and the IR rules the step
// claims to an observer, which may stop the run. The checker's conformance monitor is one; the
// runtime itself never links the checker.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/runtime/loss.hpp"
#include "semo/runtime/sim_trace.hpp"
#include "semo/runtime/tables.hpp"
#include "semo/runtime/tasklib.hpp"
#include "semo/runtime/world.hpp"

namespace semo::runtime {

struct CrashPlan {
  std::string robot;  // a robot's name, or "leader" (whoever leads a leader block then), or "leader:BLOCK"
  double at = 0;      // seconds
};

struct SimulationOptions {
  double duration = 60;  // seconds
  std::uint64_t seed = 1;
  std::vector<CrashPlan> crashes;
  double loss = 0;       // probability that one message is lost (of the kinds the model lets be lost)
  LossModel lossModel;   // how losses are spread (default: independent)
  double controlPeriod = 0.05;  // seconds between two steps of the running behaviours
  double poseSampling = 0.1;    // seconds between two pose samples in the trace
  bool stopAtGoal = true;       // end the run once the world's goal is reached (after a last pose sample)
};

// One step of the team, as the observer sees it.
struct StepReport {
  double t = 0;
  std::uint32_t robot = kNoRobot;
  std::vector<Id> rules;  // the IR rules the step is, in order (empty: a stutter, nothing the model sees changes)
  const std::vector<std::int32_t>* before = nullptr;  // the IR state before (abstraction function)
  const std::vector<std::int32_t>* after = nullptr;   // and after
  std::string what;       // in words
};

class StepObserver {
 public:
  virtual ~StepObserver() = default;
  // Returns false to stop the run (the simulator records a Violation event with `why()`).
  virtual bool onStep(const StepReport& step) = 0;
  [[nodiscard]] virtual std::string why() const = 0;
};

// Checks that the world gives the mission what it needs (every place a call names, a start pose
// per robot, a source per sensed value the mission reads); returns the problems, in words.
std::vector<std::string> checkWorld(const MissionTables& tables, const World& world);

// Runs the team. `observer` may be null (no conformance check).
SimTrace simulate(const MissionTables& tables, const World& world, const TaskLibrary& library, const SimulationOptions& options,
                  StepObserver* observer = nullptr);

// The IR state of the team at its start (every variable's initial value).
std::vector<std::int32_t> initialAbstractState(const MissionTables& tables);

}  // namespace semo::runtime
