#pragma once
// A robot's dataflow as the runtime runs it (specs/runtime.md, "Dataflow"): its task graph (the
// paper's extended SDF model, specs/taskgraph.md) with the capacities the SDF analysis proved, and
// per scenario the static schedule of one iteration and its period. Plain data, projected once
// (codegen::projectDataflow) and never changed while the robot runs; the runtime needs nothing
// else to run the dataflow, and no analysis at run time.
//
// Indices: a task is an index into DataflowTable::tasks, a channel one into DataflowTable::channels
// (the task graph's own order). Self-loops, which the analysis adds to keep each task's firings in
// sequence, are not channels here: the runtime fires one task at a time anyway.
#include <cstdint>
#include <string>
#include <vector>

namespace semo::runtime {

struct DataflowTask {
  enum class Kind : std::uint8_t { Service, Sensing, Control, Communication, Knowledge, LeaderElection };
  std::string name;                     // "large_motors", "control", "publish_SlaveTeam_Message"
  Kind kind = Kind::Service;
  std::vector<std::string> implements;  // the services or sensed values it implements, or what it carries ("topic SlaveTeam.Message")
  std::int64_t execMicros = 0;          // worst case per firing (the strategy's; 1 ms for generated tasks)
  friend bool operator==(const DataflowTask&, const DataflowTask&) = default;
};

struct DataflowChannel {
  std::string name;  // "planner.cmd->large_motors.cmd"
  std::uint32_t from = 0, to = 0;
  bool control = false;       // between a task's interface port and the control task
  std::int64_t capacity = 0;  // the largest max-throughput bound over the scenarios that use it (0: in none with bounds)
  friend bool operator==(const DataflowChannel&, const DataflowChannel&) = default;
};

// One scenario: a mode of the robot's team with, for each plan that calls services in it, the one
// service that plan runs (specs/taskgraph.md, "Scenarios").
struct ScenarioTable {
  std::string name;  // as the SDF analysis names it: "SEARCH_MODE", "RETREAT_MODE[walk]"
  std::string mode;
  std::uint32_t modeIndex = 0xffffffffu;  // into TeamTable::modes of the robot's team (kNone: none)
  std::vector<std::string> services;      // the services running, one per plan that calls any
  std::vector<std::string> planServices;  // per plan of the team: the service it runs here ("" when it calls none)

  // One iteration of the static schedule, in order: `task` fires `repetitions` times in a row.
  struct Firing {
    std::uint32_t task = 0;
    std::int64_t repetitions = 1;
    friend bool operator==(const Firing&, const Firing&) = default;
  };
  std::vector<Firing> schedule;
  // The channels the scenario uses, with its rates; `capacity` repeats the robot's proven capacity of
  // `channel` so that a scenario's schedule is built from this table alone.
  struct Channel {
    std::uint32_t channel = 0;  // into DataflowTable::channels
    std::uint32_t from = 0, to = 0;
    std::int64_t production = 1, consumption = 1, initialTokens = 0, capacity = 0;
    friend bool operator==(const Channel&, const Channel&) = default;
  };
  std::vector<Channel> channels;
  std::int64_t periodNum = 0, periodDen = 1;  // microseconds per iteration, exact (self-timed, within the capacities)
  double period = 0;                          // the same in seconds

  // What running needs held: consistent, deadlock free, a period, and the schedule proven safe
  // within the capacities (no overflow nor underflow, for any number of iterations). The runtime
  // runs only proven scenarios: another has no bounds to claim. (Whether the capacities are also
  // minimal is the analysis' business, `semo-verify sdf`; running does not depend on it.)
  bool proven = false;
  std::string notProven;  // why not, in words (empty when proven)
  friend bool operator==(const ScenarioTable&, const ScenarioTable&) = default;
};

// A port of a communication task to other robots (specs/taskgraph.md, "Remote ports"): the robot's
// wiring. A multicast port belongs to a group (a topic's subscribers, a team's events, a knowledge
// item's workers, a leader block's candidates), a point-to-point port to a reliable channel; an input
// port has a receive buffer. A transport carries what goes through them: `send`/`multicast` to the
// peers named here (the networked robot routes by the same tables, specs/runtime.md section 11).
struct RemotePortTable {
  std::uint32_t task = 0;     // into DataflowTable::tasks
  std::string port;
  bool output = true;         // it sends (else it receives)
  bool multicast = true;      // else point to point
  std::string group;          // "topic:SlaveTeam.Message", "events:SlaveTeam", ...
  std::int64_t buffer = 1;    // the receiving port's buffer (tokens)
  std::vector<std::string> peers;  // the robots on the other side
  friend bool operator==(const RemotePortTable&, const RemotePortTable&) = default;
};

struct DataflowTable {
  std::vector<DataflowTask> tasks;  // the control task first
  std::vector<DataflowChannel> channels;
  std::vector<ScenarioTable> scenarios;
  std::vector<RemotePortTable> remotePorts;
  friend bool operator==(const DataflowTable&, const DataflowTable&) = default;
};

}  // namespace semo::runtime
