#pragma once
// What the IR's variables and rules stand for in the mission: the other half of the translation
// (translate.hpp). The IR alone is enough to verify; running the mission needs to know which robot
// owns a variable and what it means (its role), and what each rule does in terms of the mission
// (a program step of one plan with its calls, sensed tests, guards and effects; an event delivered;
// a heartbeat period). The runtime's step tables are projected from this, row by row, and the
// simulator's conformance check maps the running team back onto the IR through the roles
// (specs/runtime.md, "The abstraction function").
//
// Pointers into the MissionModel (statements, conditions) stay valid while that model lives.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"
#include "semo/semantics/mission_model.hpp"
#include "semo/semantics/robot_program.hpp"

namespace semo::lowering {

// What one IR variable holds. `robot` for the per-robot roles, `team` for Crashed.
struct VariableRole {
  enum class Kind : std::uint8_t {
    Alive,           // robot is alive
    Crashed,         // robots of `team` crashed so far
    Mode,            // robot's mode, as an index into its team's modes
    Pc,              // robot's program counter in plan `index` (an instruction of programs[team][plan])
    Event,           // event `index` of the robot's team is on its way to the robot
    View,            // the robot's latest received value of topic `index` (0 none, else symbol + 1)
    Message,         // a value of topic `index` on its way to the robot (0 none)
    Channel,         // values queued on the reliable channel of topic `index`
    Leads,           // the robot believes it leads group block `index`
    Silence,         // heartbeat periods the robot heard nothing in block `index`
    LostHeartbeats,  // heartbeats to the robot lost in a row in block `index` (the network's count)
    Knows,           // how many facts of knowledge item `knowledge` the robot holds
    // Team counts (specs/semantics.md, "Counts of a large team"): how many live robots of `team`
    Holding,         // hold a number of facts of item `knowledge` that is one of `values`
    AtPoints,        // have their program counter of plan `index` at one of `values`
  };
  Kind kind = Kind::Alive;
  Index robot = model::kNone;
  Index team = model::kNone;
  Index index = model::kNone;
  std::string knowledge;
  std::vector<std::int32_t> values;  // Holding, AtPoints: the counted values, ascending

  VariableRole() = default;
  VariableRole(Kind k, Index robotIndex, Index teamIndex, Index what = model::kNone, std::string knowledgeName = {})
      : kind(k), robot(robotIndex), team(teamIndex), index(what), knowledge(std::move(knowledgeName)) {}
};
const char* roleName(VariableRole::Kind kind);

// Something a robot does while it walks from a control point, before its step commits: it calls a
// service or waits (time passes; nothing another robot can see), or it tests a condition.
struct Action {
  enum class Kind : std::uint8_t {
    Call,   // a primitive service call (stmt)
    Wait,   // wait(D) (stmt)
    Sense,  // a condition over sensed values or knowledge: the environment decides (the IR has both outcomes)
    Test,   // a condition over the robot's topic views: part of the IR rule's guard
    LoopStart,  // the walk enters the body of the periodic loop whose back edge is instruction `jump`
  };
  Kind kind = Kind::Call;
  const model::Stmt* stmt = nullptr;  // Call, Wait
  const model::Cond* cond = nullptr;  // Sense, Test
  bool expect = true;                 // Sense, Test: the outcome this path needs
  bool repeat = false;                // the condition of `repeat (cond)` (else an `if`)
  std::size_t jump = 0;               // LoopStart

  Action() = default;
  Action(Kind k, const model::Stmt* s, const model::Cond* c = nullptr, bool expected = true, bool isRepeat = false)
      : kind(k), stmt(s), cond(c), expect(expected), repeat(isRepeat) {}
};

// A condition the step needs when it commits (it is part of the IR rule's guard and holds in the
// state the step starts from). Those reading other robots are group coordination.
struct Guard {
  enum class Kind : std::uint8_t {
    InMode,        // the robot is in mode `index` (a throw reacts per mode)
    ChannelSpace,  // the channel of topic `index` is not past its capacity
    ChannelData,   // the channel of topic `index` holds a value
    GroupStarted,  // no other live robot of the team running service `index` has its pc of plan `plan` in
                   // `pcs` (on its way to, or forming, the block around instruction `at`)
    BlockClear,    // no other live robot of the team has its pc of plan `plan` in `pcs` (inside group block
                   // `index`; the robot waits at the block's end, instruction `at`)
    Elected,       // the election of leader block `index` makes this robot the leader
    NotElected,    // ... does not
    Goal,          // the robot holds at least `count` facts of `knowledge`
  };
  Kind kind = Kind::InMode;
  Index index = model::kNone;
  std::size_t plan = 0, at = 0;
  std::string knowledge;
  std::int64_t count = 0;
  std::vector<std::size_t> pcs;  // GroupStarted, BlockClear

  Guard() = default;
  explicit Guard(Kind k, Index what = model::kNone, std::size_t planIndex = 0, std::size_t instruction = 0)
      : kind(k), index(what), plan(planIndex), at(instruction) {}
};

// What the step does when it commits, in order.
struct Effect {
  enum class Kind : std::uint8_t {
    Throw,       // event `index` to every other live robot of the team
    EnterMode,   // mode `index`: every plan restarts at the mode's service; the robot leaves its blocks
    Publish,     // topic `index`, value of `stmt`: to the subscribers' message slots and the robot's own view
    Send,        // one value onto the reliable channel of topic `index`
    Receive,     // one value off it
    Elect,       // the election of leader block `index` among the robots forming it (and the announcement)
    JoinArm,     // the robot takes arm `arm` of group block `index`
    LeaveBlock,  // the robot leaves group block `index` (a leader stops leading)
  };
  Kind kind = Kind::Throw;
  Index index = model::kNone;
  std::size_t arm = 0;
  const model::Stmt* stmt = nullptr;
  std::int32_t value = 0;  // Publish: the value the IR's message slots and views get (symbol + 1)

  Effect() = default;
  Effect(Kind k, Index what, std::size_t armIndex = 0, const model::Stmt* s = nullptr) : kind(k), index(what), arm(armIndex), stmt(s) {}
};

// The meaning of one IR rule.
struct RuleMeaning {
  enum class Kind : std::uint8_t {
    ProgramStep,      // robot, plan: from `from` through `actions` to `to`, if `guards`, doing `effects`
    ModeDefault,      // robot: every plan of mode `mode` is done; enters mode `target`
    Discover,         // robot, working in group service `service` (plan, from): finds a new fact of `knowledge`
    Learn,            // robot learns `knowledge` from some live teammate and then holds `count` facts
    EventDelivery,    // event `index` reaches robot
    EventLoss,        // event `index` to robot is lost
    MessageDelivery,  // the value of topic `index` on its way to robot reaches its view
    MessageLoss,      // ... is lost
    Crash,            // robot crash-stops
    HeartbeatPeriod,  // one heartbeat period of leader block `index`; heartbeats to the candidates in `lostTo` are lost
    Takeover,         // robot suspects the leader of block `index` and takes over (plan, to: the leader's part)
  };
  Kind kind = Kind::ProgramStep;
  Index robot = model::kNone;
  Index peer = model::kNone;
  Index index = model::kNone;
  Index mode = model::kNone, target = model::kNone;
  std::size_t plan = 0, from = 0, to = 0;
  bool changesMode = false;  // ProgramStep: an effect enters a mode (then `to` is the mode's entry, not a pc update)
  std::string service, knowledge;
  std::int64_t count = 0;
  std::vector<Index> lostTo;  // HeartbeatPeriod: robots
  std::vector<Action> actions;
  std::vector<Guard> guards;
  std::vector<Effect> effects;
};
const char* meaningName(RuleMeaning::Kind kind);

// The fault assumptions the translation used (the verify block, overridden by the options).
struct LoweredAssumptions {
  std::vector<std::int64_t> crashBudget;  // per team
  bool losePublish = false, loseEvents = false, loseKnowledge = false, loseHeartbeats = false;
  bool fairLoss = true;
  std::int64_t lossBurst = 1;
};

struct Lowering {
  LoweredAssumptions assumptions;
  std::vector<std::vector<PlanProgram>> programs;  // per team, per plan
  std::vector<VariableRole> variables;             // per IR variable
  std::vector<RuleMeaning> rules;                  // per IR rule
  // Program walks that change nothing the model sees (an idle loop: `loop (1 SEC) display(x)`):
  // no IR rule, but the running robot takes them (a stutter step).
  std::vector<RuleMeaning> stutters;
  // What each count of a large team is (specs/semantics.md, "Counts of a large team"):
  // `count == (alive_1 && x_1 counted) + ... + (alive_n && x_n counted)`, one per count variable.
  // True in every reachable state by construction; the SMT engine proves them (they are inductive)
  // and then uses them, since its IC3 cannot find a sum itself.
  std::vector<ir::Expr> countDefinitions;
};

}  // namespace semo::lowering
