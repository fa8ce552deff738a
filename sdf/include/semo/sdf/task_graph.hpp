#pragma once
// A robot's task graph (the paper's extended SDF model): the tasks its part of the mission needs,
// the channels between them, the ports through which it talks to other robots, and its scenarios.
//
// Tasks: those of the strategy implementations of the services and sensed values the robot runs
// (one instance per task name: the same driver serves every service that uses it), one control
// task (the hierarchical FSM: modes on top, each mode's service sequence below), and the
// communication tasks (one per topic published, subscribed, sent or received; events out and in;
// one per shared knowledge item; one leader-election task per leader block the robot may lead).
// Ports of an implementation that its channels leave unconnected are the service's interface to
// the control task.
//
// Scenarios (FSM-controlled SDF): a scenario is one mode with, for each of its plans, the service
// running at that moment (a plan runs its calls one after another, so two calls of one plan are
// never active together). In a scenario the control task fires once per iteration; its port rates
// are chosen so that it exchanges exactly one iteration's worth of tokens with each service
// (rate = the partner task's repetition count times its port rate), and every channel from the
// control task holds that many tokens initially: the commands for the first iteration are issued
// when the scenario starts. Every task has a self-loop with one token (its firings run one after
// another). An iteration returns every channel to its initial tokens, so the FSM switches
// scenarios between iterations without leaving stray tokens.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/frontend/diagnostics.hpp"
#include "semo/sdf/graph.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo::sdf {

enum class TaskKind { Service, Sensing, Control, Communication, Knowledge, LeaderElection };
const char* taskKindName(TaskKind k);

struct TaskPort {
  std::string name;
  bool input = true;
  std::int64_t rate = 1;  // 0 on the control task: set per scenario
};

struct Task {
  std::string name;
  TaskKind kind = TaskKind::Service;
  std::vector<std::string> origins;  // the services or values it implements (or what it carries)
  std::int64_t execMicros = 0;
  std::vector<TaskPort> ports;
  SourceRange at;  // its strategy element, where there is one
};

struct TaskChannel {
  std::string name;
  std::uint32_t fromTask = 0, toTask = 0;
  std::string fromPort, toPort;
  std::int64_t initialTokens = 0;  // on control channels: set per scenario
  bool control = false;            // connects a task's interface port with the control task
};

// A port through which the robot talks to other robots (outside the per-robot SDF analysis:
// multicast is lossy and unsynchronised by design; point-to-point channels are the runtime's).
struct RemotePort {
  enum class Kind { Multicast, PointToPoint };
  std::uint32_t task = 0;
  std::string port;
  bool output = true;
  Kind kind = Kind::Multicast;
  std::string id;                  // the multicast group or link: "topic:Team.var", "events:Team", ...
  std::int64_t buffer = 1;         // the receiving port's buffer (tokens)
  std::vector<std::string> peers;  // robots on the other side
};

struct ScenarioChannel {
  std::uint32_t channel = 0;  // into TaskGraph::channels
  std::int64_t production = 1, consumption = 1, initialTokens = 0;
};

struct Scenario {
  std::string name;  // the mode, and the service picked in plans with several calls
  std::string mode;
  std::vector<std::string> services;   // the services running
  std::vector<std::uint32_t> plans;    // per service: the plan of the team that calls it (generated graphs only)
  std::vector<std::uint32_t> tasks;    // active tasks (the control task first)
  std::vector<ScenarioChannel> channels;
};

struct TaskGraph {
  std::string robot, robotType, team;
  std::vector<Task> tasks;
  std::vector<TaskChannel> channels;
  std::vector<RemotePort> remotePorts;
  std::vector<Scenario> scenarios;
};

// One graph per robot, in the mission's robot order. Conflicts (two services active in one
// scenario that both feed the same input port, or one task declared with different ports by two
// implementations) are errors in `diags`; the result is then nullopt.
std::optional<std::vector<TaskGraph>> generateTaskGraphs(const model::MissionModel& m, DiagnosticEngine& diags);

// The scenario as a plain SDF graph for the analyses: its active tasks as actors (execution times
// in microseconds), its channels with the scenario's rates, and a one-token self-loop per task.
Graph scenarioGraph(const TaskGraph& tg, const Scenario& s);

}  // namespace semo::sdf
