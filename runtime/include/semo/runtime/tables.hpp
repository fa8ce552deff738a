#pragma once
// The mission as the runtime runs it: the verified IR projected onto each robot (specs/runtime.md,
// "The projection"). Plain data, built once (by codegen::project, or by generated code) and never
// changed while the team runs. Every robot's behaviour is in its step tables: one row per IR rule
// of its program, with the calls, sensed tests, guards and effects of that rule in the mission's
// terms and the rule's index, so that every step the robot takes names the IR rule it is.
//
// Indices: robots, teams, topics, ... index the vectors of MissionTables; a robot's program
// counters are instruction indices of its team's plan program (the IR's `pc` values).
#include <cstdint>
#include <string>
#include <vector>

#include "semo/runtime/dataflow_tables.hpp"
#include "semo/runtime/kinematics.hpp"

namespace semo::runtime {

using Id = std::uint32_t;
inline constexpr Id kNone = 0xffffffffu;

// ------------------------------------------------------------------ values and conditions

struct SensedValueTable {
  enum class Domain : std::uint8_t { Bool, Threshold, Enum, Range };
  std::string name;  // "Team.var"
  Domain domain = Domain::Bool;
  std::vector<double> thresholds;    // Threshold
  std::vector<std::string> symbols;  // Enum
  friend bool operator==(const SensedValueTable&, const SensedValueTable&) = default;
};

// An operand of a condition or a call argument.
struct Operand {
  enum class Kind : std::uint8_t {
    Number,  // `number`
    Symbol,  // `text` (a symbol, a string literal, or "true"/"false")
    Sensed,  // sensed value `index`, read from the robot's sensors now
    View,    // the robot's latest value of topic `index`
    Facts,   // how many facts of knowledge item `index` the robot holds
  };
  Kind kind = Kind::Number;
  double number = 0;
  std::string text;
  Id index = kNone;
  friend bool operator==(const Operand&, const Operand&) = default;
};

// A condition of an `if` or a `repeat`, as a tree in MissionTables::conditions.
struct CondNode {
  enum class Kind : std::uint8_t { Compare, Test, Not, And, Or };
  enum class Rel : std::uint8_t { Lt, Le, Gt, Ge, Eq, Ne };
  Kind kind = Kind::Test;
  Rel rel = Rel::Eq;
  Operand lhs, rhs;                // Compare: both; Test: lhs
  Id left = kNone, right = kNone;  // Not: left; And/Or: both
  friend bool operator==(const CondNode&, const CondNode&) = default;
};

// A primitive service call as written: move("base camp").
struct CallTable {
  std::string service;
  std::vector<Operand> args;
  std::string origin;  // "file:line:col"
  friend bool operator==(const CallTable&, const CallTable&) = default;
};

// ------------------------------------------------------------------ step tables

// Done while the robot walks from its control point, before the step commits (nothing another
// robot can see; time may pass).
struct ActionRow {
  enum class Kind : std::uint8_t {
    Call,       // start call `index` (MissionTables::calls) and wait until it finishes
    Wait,       // wait `seconds`
    Sense,      // condition `index` over sensed values must come out `expect` (the environment decides)
    Test,       // condition `index` over topic views must come out `expect` (part of the IR guard)
    LoopStart,  // the walk enters the body of the periodic loop whose back edge is instruction `index`
  };
  Kind kind = Kind::Call;
  Id index = kNone;
  double seconds = 0;
  bool expect = true;
  friend bool operator==(const ActionRow&, const ActionRow&) = default;
};

// Must hold when the step commits (atomically with its effects).
struct GuardRow {
  enum class Kind : std::uint8_t {
    InMode,        // the robot is in mode `index` of its team
    ChannelSpace,  // the reliable channel of topic `index` is not past its capacity
    ChannelData,   // ... holds a value
    GroupStarted,  // no other live robot of the team has its pc of plan `plan` in pc set `index`
    BlockClear,    // the same test (the robot waits at a block's end for those still inside)
    Elected,       // the election of leader block `index` makes this robot its leader
    NotElected,    // ... does not
    Goal,          // the robot holds at least `count` facts of knowledge item `index`
  };
  Kind kind = Kind::InMode;
  Id index = kNone;
  Id plan = kNone;
  std::int64_t count = 0;
  friend bool operator==(const GuardRow&, const GuardRow&) = default;
};

// What the step does when it commits, in order.
struct EffectRow {
  enum class Kind : std::uint8_t {
    Throw,       // event `index` of the team to every other live robot of it
    EnterMode,   // mode `index`: every plan restarts at its entry; the robot leaves its group blocks
    Publish,     // topic `index` gets `value` (to subscribers' message slots; its own view at once)
    Send,        // `value` onto the reliable channel of topic `index`
    Receive,     // one value off the reliable channel of topic `index`
    Elect,       // the election of leader block `index` among the robots forming it
    JoinArm,     // the robot takes arm `arm` of group block `index`
    LeaveBlock,  // the robot leaves group block `index` (a leader stops leading)
  };
  Kind kind = Kind::Throw;
  Id index = kNone;
  Id arm = kNone;
  Id team = kNone;  // Publish: the team it goes to
  Operand value;    // Publish: `number` is the value the model's slots get, `text` what is sent
  friend bool operator==(const EffectRow&, const EffectRow&) = default;
};

struct Row {
  Id from = 0, to = 0;       // program counters; `to` is ignored when `changesMode`
  bool changesMode = false;  // an EnterMode effect sets every program counter
  std::vector<ActionRow> actions;
  std::vector<GuardRow> guards;
  std::vector<EffectRow> effects;
  Id irRule = kNone;  // MissionTables::rules
  friend bool operator==(const Row&, const Row&) = default;
};

// One instruction of a plan program, as the runtime needs it.
struct PlanPoint {
  bool controlPoint = false;
  double loopPeriod = 0;  // the back edge of a periodic loop (`loop (D)`, `repeat (D)`): its period, seconds
  Id loopHead = kNone;    // on a back edge: the instruction the loop body starts at
  Id service = kNone;     // the service (MissionTables::services) this instruction belongs to
  Id work = kNone;        // a group service call (MissionTables::calls): the robot works in it while it rests here
  std::string label;      // "Search#7"
  friend bool operator==(const PlanPoint&, const PlanPoint&) = default;
};

struct PlanTable {
  std::string name;
  std::vector<PlanPoint> points;  // per program counter (0: done)
  std::vector<Row> rows;          // sorted by `from`; rows of one `from` share their actions up to where tests part them
  std::vector<Id> firstRow;       // per program counter: its first row (rows.size() if none); firstRow[pc + 1] ends them
  friend bool operator==(const PlanTable&, const PlanTable&) = default;
};

// ------------------------------------------------------------------ teams, messages, groups

struct ModeTable {
  std::string name;
  std::vector<Id> entry;  // per plan of the team: the program counter the mode starts it at (0: runs nothing)
  std::vector<std::pair<Id, Id>> catches;  // (event, target mode)
  Id defaultTarget = kNone;                // `default: mode = M` once every plan is done
  std::vector<Id> keepsLeaders;  // LeaderBlockTables whose leader goes on leading on entering it (on-mode-change="keep")
  friend bool operator==(const ModeTable&, const ModeTable&) = default;
};

struct EventTable {
  std::string name;
  bool reliable = false;        // the strategy's delivery="reliable": never lost
  std::int64_t retransmissions = 0;
  bool lossy = false;           // the model lets it be lost (assume loss events)
  friend bool operator==(const EventTable&, const EventTable&) = default;
};

struct TeamTable {
  std::string name;
  std::vector<Id> robots;
  std::vector<std::string> plans;
  std::vector<ModeTable> modes;
  Id initialMode = 0;
  std::vector<EventTable> events;
  std::int64_t crashBudget = 0;  // the model's assumption
  friend bool operator==(const TeamTable&, const TeamTable&) = default;
};

struct TopicTable {
  std::string name;  // "Team.var"
  Id owner = kNone;
  std::vector<std::string> symbols;  // the values it carries (views hold 0 for none, else symbol + 1)
  bool reliable = false;             // written by send, read by receive: a reliable channel
  std::int64_t capacity = 1;         // reliable: the channel's capacity
  bool lossy = false;                // publish: the model lets it be lost
  std::vector<Id> subscribers;       // robots that keep a view (and a message slot) of it
  friend bool operator==(const TopicTable&, const TopicTable&) = default;
};

struct ServiceTable {
  std::string name;  // a composite service of the mission
  std::string plan;
  friend bool operator==(const ServiceTable&, const ServiceTable&) = default;
};

// A knowledge item of a group service, shared by the robots of `team` working in it.
struct KnowledgeTable {
  std::string service, name;  // "searchPaper", "papers"
  Id team = kNone;
  std::vector<std::string> facts;
  bool newest = true;            // merge="newest" (else "union")
  bool shared = true;            // false: via="none", nothing is sent
  bool reliable = false;         // via="reliable": acknowledged, never lost
  double period = 1;             // seconds between broadcasts
  std::int64_t retransmissions = 0;
  bool lossy = false;            // the model lets gossip be lost
  friend bool operator==(const KnowledgeTable&, const KnowledgeTable&) = default;
};

struct ArmTable {
  std::string label;  // "group (TurtlebotBurger)", "leader (ColorSensor)", "others"
  bool leader = false, others = false;
  Id entry = 0, first = 0, end = 0;  // its program counters: entry, and the range [first, end)
  std::vector<Id> candidates;
  friend bool operator==(const ArmTable&, const ArmTable&) = default;
};

struct GroupBlockTable {
  std::string name;  // "SlaveTeam.Action.Search#0"
  Id team = kNone, plan = kNone;
  Id first = 0, formPoint = 0, exit = 0;  // instructions [first, formPoint]; exit == first
  std::vector<ArmTable> arms;
  Id leader = kNone;  // LeaderBlockTable index, for a leader block
  friend bool operator==(const GroupBlockTable&, const GroupBlockTable&) = default;
};

struct LeaderBlockTable {
  std::string name;  // "SlaveTeam.Report.ReportPapers"
  Id block = kNone;  // GroupBlockTable
  std::vector<Id> candidates;   // in the IR's order
  std::vector<Id> preference;   // most preferred first (bully: highest index; lowest-id: lowest)
  double heartbeat = 1;         // seconds
  std::int32_t timeoutPeriods = 3;
  bool detectsFailures = true;  // heartbeats and takeovers (else re-election only when the block forms)
  bool lossyHeartbeats = false;
  std::int32_t lossBurst = 1;
  Id leaderArm = kNone, othersArm = kNone;
  std::vector<Id> heartbeatRule;  // IR rule per set of candidates whose heartbeat is lost (bit i: candidates[i])
  friend bool operator==(const LeaderBlockTable&, const LeaderBlockTable&) = default;
};

// ------------------------------------------------------------------ robots

struct RobotTable {
  std::string name, type;
  Id team = kNone, indexInTeam = 0;
  DriveGeometry geometry;
  std::vector<PlanTable> plans;  // per plan of the team (empty rows when it runs nothing)
  std::vector<Id> leaderBlocks;  // LeaderBlockTable indices it is a candidate of
  std::vector<Id> knowledge;     // KnowledgeTable indices of its team
  // The IR rules of the steps outside its program (kNone where the model has none):
  Id crashRule = kNone;
  std::vector<Id> eventDeliveryRule, eventLossRule;      // per event of the team
  std::vector<Id> messageDeliveryRule, messageLossRule;  // per topic
  std::vector<Id> defaultRule;                           // per mode of the team
  std::vector<Id> takeoverRule;                          // per entry of leaderBlocks
  struct Discover {
    Id knowledge = kNone, plan = kNone, pc = kNone, rule = kNone;
    Id started = kNone;  // pc set of the synchronised start (GuardRow::GroupStarted), kNone: none
    friend bool operator==(const Discover&, const Discover&) = default;
  };
  std::vector<Discover> discoverRules;
  // per entry of `knowledge`: [count] -> the rule "learns from a teammate, now holds count"
  std::vector<std::vector<Id>> learnRule;
  DataflowTable dataflow;  // its task graph, proven capacities and static schedules (empty: not projected)
  friend bool operator==(const RobotTable&, const RobotTable&) = default;
};

// ------------------------------------------------------------------ the abstraction function

// One IR variable, as read off the running team (specs/runtime.md): the same roles as the
// semantics' lowering. Every per-robot variable of a crashed robot reads as its initial value.
// The counts of a large team (Holding, AtPoints) are how many live robots of `team` hold a number
// of facts of item `index` / have their pc of plan `index` that is one of `values`.
struct AbstractVar {
  enum class Kind : std::uint8_t { Alive, Crashed, Mode, Pc, Event, View, Message, Channel, Leads, Silence, LostHeartbeats, Knows, Holding, AtPoints };
  Kind kind = Kind::Alive;
  Id robot = kNone, team = kNone, index = kNone;  // index: plan, event, topic, leader block (LeaderBlockTable), knowledge item
  std::int32_t init = 0;
  std::vector<std::int32_t> values;  // Holding, AtPoints: the values counted, ascending
  std::string name;  // the IR variable's name
  friend bool operator==(const AbstractVar&, const AbstractVar&) = default;
};

struct RuleInfo {
  std::string name, label, origin;
  Id robot = kNone;
  friend bool operator==(const RuleInfo&, const RuleInfo&) = default;
};

struct Assumptions {
  bool losePublish = false, loseEvents = false, loseKnowledge = false, loseHeartbeats = false;
  std::int32_t lossBurst = 1;
  std::vector<std::string> words;  // as every verdict states them
  friend bool operator==(const Assumptions&, const Assumptions&) = default;
};

struct MissionTables {
  std::vector<TeamTable> teams;
  std::vector<RobotTable> robots;
  std::vector<ServiceTable> services;
  std::vector<TopicTable> topics;
  std::vector<SensedValueTable> sensed;
  std::vector<CondNode> conditions;
  std::vector<CallTable> calls;
  std::vector<std::vector<Id>> pcSets;  // sorted
  std::vector<KnowledgeTable> knowledge;
  std::vector<GroupBlockTable> groupBlocks;
  std::vector<LeaderBlockTable> leaderBlocks;
  std::vector<AbstractVar> abstraction;  // per IR variable, in the IR's order
  std::vector<RuleInfo> rules;           // per IR rule, in the IR's order
  Assumptions assumptions;
  std::string modelFingerprint;
  friend bool operator==(const MissionTables&, const MissionTables&) = default;
};

// The tables' layout, as a number: compiled into generated code (`semo-verify simulate --generated`
// loads tables compiled elsewhere only when their layout is its own). It changes with the version
// below, bumped whenever a table's members change, and with the structs' sizes.
inline constexpr unsigned long long kTablesVersion = 3;
inline constexpr unsigned long long kTablesLayout =
    kTablesVersion * 1000003ull ^ (sizeof(MissionTables) << 8) ^ (sizeof(RobotTable) << 20) ^ (sizeof(Row) << 32) ^
    (sizeof(PlanTable) << 40) ^ (sizeof(DataflowTable) << 48) ^ (sizeof(ScenarioTable) << 56) ^ (sizeof(Operand) << 4);

}  // namespace semo::runtime
