#pragma once
// The strategy description (specs/strategy.md): how services and values of a mission are refined
// into tasks of each robot type's task library, and how groups, leaders and events behave.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/frontend/diagnostics.hpp"

namespace semo::strategy {

struct Port {
  std::string name;
  bool input = true;
  std::int64_t rate = 1;
  SourceRange at;
};

struct Task {
  std::string name;
  std::int64_t execMicros = 0;  // worst-case execution time per firing
  std::vector<Port> ports;
  SourceRange at;
  [[nodiscard]] const Port* port(const std::string& portName) const;
};

struct Channel {
  std::string fromTask, fromPort, toTask, toPort;
  std::int64_t initialTokens = 0;
  SourceRange at;
};

// The dataflow subgraph that implements a service or value on one robot type.
struct Implementation {
  std::string robotType;
  std::vector<Task> tasks;
  std::vector<Channel> channels;
  SourceRange at;
};

const Implementation* findImplementation(const std::vector<Implementation>& implementations, const std::string& robotType);

struct Knowledge {
  enum class Merge { Newest, Union };
  std::string name;
  std::vector<std::string> values;
  Merge merge = Merge::Newest;
  SourceRange at;
};

struct Dissemination {
  std::string via = "broadcast";
  std::int64_t periodMillis = 1000;
  std::int64_t retransmissions = 0;
  SourceRange at;
};

struct Goal {
  std::string knowledge;
  std::int64_t count = 1;
  SourceRange at;
};

struct Service {
  enum class Kind { Primitive, Group };
  std::string name;
  Kind kind = Kind::Primitive;
  bool paramsDeclared = false;
  std::vector<std::string> params;
  std::vector<Implementation> implementations;
  // group services only
  std::int64_t minRobots = 1;
  std::vector<Knowledge> knowledge;
  std::optional<Dissemination> dissemination;
  std::optional<Goal> goal;
  SourceRange at;
  [[nodiscard]] const Implementation* implementationFor(const std::string& robotType) const;
};

struct Domain {
  enum class Kind { Bool, Threshold, Enum, Range };
  Kind kind = Kind::Bool;
  std::vector<double> thresholds;   // Threshold, ascending
  std::vector<std::string> values;  // Enum
  std::int64_t min = 0, max = 0;    // Range
  SourceRange at;
};

struct Value {
  std::string team, var;  // name="Team.var"
  Domain domain;
  // source="team": every robot of the team reads one source (an operator's console, a beacon), so
  // that on a settling world they all read the same; default "robot": each senses it for itself.
  bool teamSource = false;
  std::vector<Implementation> implementations;
  SourceRange at;
  [[nodiscard]] const Implementation* implementationFor(const std::string& robotType) const;
};

struct Topic {
  std::string team, var;
  std::vector<std::string> values;  // empty: inferred from the mission
  std::int64_t buffer = 1;
  SourceRange at;
};

struct LeaderSelection {
  enum class Algorithm { Bully, LowestId };
  std::string team, plan, service;  // service="Team.Plan.Service"
  Algorithm algorithm = Algorithm::LowestId;
  // When a failed leader is replaced: after the failure timeout, by the members that wait for its
  // heartbeats (`timeout`), or only when the group forms again (`formation`, the paper's scheme).
  enum class Reelection { Timeout, Formation };
  Reelection reelection = Reelection::Timeout;
  // What a leader does with its leadership when its mode changes to one that runs the same
  // service again (its services restart either way): gives it up, so the others may take over
  // (`release`), or goes on leading once it is back in the block (`keep`).
  enum class OnModeChange { Release, Keep };
  OnModeChange onModeChange = OnModeChange::Release;
  std::int64_t heartbeatMillis = 1000;
  std::int64_t timeoutMillis = 3000;
  SourceRange at;
};

struct EventDelivery {
  bool reliable = false;
  std::int64_t retransmissions = 0;
  SourceRange at;
};

struct EventOverride {
  std::string name;
  EventDelivery delivery;
};

struct CapabilityAddition {
  std::string name;
  std::string link;  // empty: not tied to a link
  SourceRange at;
};

struct RobotEntry {
  std::string urdf;                 // as written in the strategy
  std::optional<std::string> type;  // the `type` attribute
  std::vector<CapabilityAddition> capabilities;
  SourceRange at;
};

struct Strategy {
  FileId file = kNoFile;
  std::string folder;  // the strategy file's folder, for relative URDF paths
  std::vector<RobotEntry> robots;
  std::vector<Service> services;
  std::vector<Value> values;
  std::vector<Topic> topics;
  std::vector<LeaderSelection> leaderSelections;
  EventDelivery events;
  std::vector<EventOverride> eventOverrides;

  [[nodiscard]] const Service* service(const std::string& name) const;
  [[nodiscard]] const Value* value(const std::string& team, const std::string& var) const;
  [[nodiscard]] const Topic* topic(const std::string& team, const std::string& var) const;
  [[nodiscard]] const LeaderSelection* leaderSelection(const std::string& team, const std::string& plan,
                                                       const std::string& service) const;
  [[nodiscard]] EventDelivery eventDelivery(const std::string& event) const;
};

// Reads and checks a strategy file already registered in `sources`. Errors go to `diags`; the result
// holds everything that could be read.
Strategy readStrategy(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo::strategy
