#pragma once
// What a simulated run leaves behind (specs/runtime.md, "The trace"): the robots, the world, every
// event in time order (each step of a robot with its IR rule and mission origin, messages sent,
// delivered and lost, crashes, mode and role changes, facts found), the robots' poses sampled over
// time, and a summary. Written as JSON ("semo-simtrace", version 1) and drawn as SVG: trajectories
// in the world, and under them a timeline per robot.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/runtime/kinematics.hpp"
#include "semo/runtime/world.hpp"

namespace semo::runtime {

inline constexpr std::uint32_t kNoRobot = 0xffffffffu;

struct TraceRobot {
  std::string name, type, team;
  DriveGeometry geometry;
};

// One change of an IR variable by a step (the abstraction of the running team, before and after).
struct TraceChange {
  std::string var;
  std::int32_t from = 0, to = 0;
};

struct TraceEvent {
  enum class Kind : std::uint8_t {
    Step,       // a step of the model: `rule` (IR rule names, comma separated when one step is several rules)
    Send,       // robot sent `detail` to `peer` (kNoRobot: to every peer)
    Deliver,    // `detail` from `peer` reached robot
    Drop,       // `detail` from `peer` to robot was lost
    Crash,      // robot crash-stopped
    Mode,       // robot entered mode `detail` (at 0 s, labelled "starts in MODE": the mode it starts in)
    Role,       // robot's role in a group block is now `detail` ("leader of ReportPapers",
                // "group (TurtlebotBurger)", "others"; empty: it left the block)
    Fact,       // robot found fact `detail` ("papers: red")
    Note,       // anything else worth a line (`label`)
    Violation,  // a property or a conformance check failed here (`label` says which)
  };
  double t = 0;
  std::uint32_t robot = kNoRobot;
  Kind kind = Kind::Note;
  std::string rule;
  std::string label;
  std::string origin;
  std::string detail;
  std::string block;  // Role: the group block the role is in ("SlaveTeam.Report.ReportPapers#2")
  std::uint32_t peer = kNoRobot;
  std::vector<TraceChange> changes;  // Step: the IR variables it changed
};
const char* eventKindName(TraceEvent::Kind kind);

struct PoseSample {
  double t = 0;
  std::vector<Pose> poses;  // every robot, in robot order (a crashed robot keeps its last pose)
};

struct LeaderChange {
  std::string block;  // "SlaveTeam.Report.ReportPapers"
  double t = 0;
  std::uint32_t from = kNoRobot, to = kNoRobot;
  double sinceCrash = -1;  // seconds since the previous leader crashed, when it did
};

// One robot's dataflow over the run (specs/runtime.md, "Dataflow"): what its static schedules did
// on channels of the proven capacities.
struct DataflowRunSummary {
  std::vector<std::string> scenarios;           // per scenario of its task graph: its name
  std::vector<std::uint64_t> iterations;        // per scenario: iterations completed
  std::vector<std::string> channels;            // per channel: its name
  std::vector<std::int64_t> capacity, maxFill;  // per channel: the proven capacity it ran with, the most tokens it held
  std::uint64_t stalls = 0, overflows = 0;      // iterations that could not complete (impossible by the proof)
  std::vector<std::string> notRun;              // scenarios never run, their schedule not proven: "NAME: why"
};

struct TraceSummary {
  bool goalStated = false;      // the world states the mission's goal
  bool completed = false;       // it was reached (without a goal: every live robot finished)
  double completedAt = -1;
  std::vector<std::pair<double, std::string>> modeChanges;  // (time, "ev3_0: SEARCH_MODE")
  std::vector<LeaderChange> leaderChanges;
  std::vector<std::pair<std::string, double>> convergedAt;  // (knowledge item, since when every live robot taking part has held the same facts, to the end), -1: not at the end
  std::uint64_t messagesSent = 0, messagesLost = 0;
  std::uint64_t stepsChecked = 0;  // conformance: steps compared with the model
  std::uint64_t mismatches = 0;
  std::string outsideAssumptions;  // non-empty: from this point the run left the model's assumptions (why)
  std::vector<std::string> violations;
  std::vector<DataflowRunSummary> dataflow;  // per robot (empty: the tables hold no dataflow)
};

struct SimTrace {
  std::string mission, strategy, worldFile;
  std::string modelFingerprint;  // of the IR the run was projected from (checker/trace fingerprint)
  std::uint64_t seed = 0;
  double duration = 0;            // seconds simulated
  std::string faults;             // the fault injection, in words ("crash ev3_1 at 5 s; loss 0.2 bernoulli on publish, events")
  std::vector<TraceRobot> robots;
  std::vector<std::string> teams;
  World world;
  std::vector<TraceEvent> events;  // in time order
  std::vector<PoseSample> poses;   // in time order
  TraceSummary summary;
};

// The trace as JSON: deterministic (the same trace gives the same bytes), numbers with fixed
// precision (times to the microsecond, poses to the micrometre).
std::string simTraceToJson(const SimTrace& trace);

// The picture: the world (arena, obstacles, places, fact sites) with each robot's trajectory and
// final pose, and under it one timeline per robot: modes as coloured bands, its role in each group
// block on a lane of that block, crashes, and messages sent and lost as ticks. No two labels of the
// world overlap. Self-contained SVG 1.1 (no scripts, no
// external references), deterministic.
std::string renderSvg(const SimTrace& trace);

}  // namespace semo::runtime
