#pragma once
// One robot of the team, in its own program, talking to the others over a Transport (specs/runtime.md,
// "Networked robots"). It runs the same step tables with the same interpreter as the simulator
// (plans, rows, guards, effects, behaviours, failure detection, knowledge merging): only its own
// robot; every other robot is a replica kept from that robot's Status and Pose packets, and what the
// simulator does to another robot (an event's slot, a message, an election) goes out as a packet.
//
// Time is the caller's: advanceTo(t) takes every step due by t (microseconds since the start) and
// every packet that arrived meanwhile. robotMain drives it from the steady clock over UDP or DDS;
// tests drive several nodes over one InProcessTransport in simulated time, deterministically.
#include <cstdint>
#include <memory>

#include "semo/runtime/packet_check.hpp"
#include "semo/runtime/sim_trace.hpp"
#include "semo/runtime/simulator.hpp"
#include "semo/runtime/tables.hpp"
#include "semo/runtime/tasklib.hpp"
#include "semo/runtime/transport.hpp"
#include "semo/runtime/world.hpp"

namespace semo::runtime {

namespace detail {
class Team;
struct NodeLink;
}  // namespace detail

struct NodeOptions {
  SimulationOptions simulation;  // duration, seed, injected loss, crashes (of this robot), control period
  double statusPeriod = 0.1;     // seconds between two Status broadcasts (one follows every step too)
  double peerTimeout = 3.0;      // seconds of silence after which a peer is taken as crashed
};

class RobotNode {
 public:
  // `mission` holds every robot's tables; `transport` and `world` must outlive the node.
  RobotNode(const MissionTables& mission, Id self, const World& world, const TaskLibrary& library, Transport& transport,
            const NodeOptions& options);
  ~RobotNode();
  RobotNode(const RobotNode&) = delete;
  RobotNode& operator=(const RobotNode&) = delete;

  // Starts the robot's plans and timers (its first Status goes out).
  void start();
  // Takes every step due by `micros` and every packet that arrived; false once the run is over
  // (the duration, the goal reached, or the robot stopped).
  bool advanceTo(std::int64_t micros);
  // When the next timed step is due (microseconds), to sleep until then.
  [[nodiscard]] std::int64_t nextEventTime() const;
  // Ends the run: the last poses, the summary. The trace has this robot's own steps and every
  // robot's pose (the others' as their Pose packets gave them).
  SimTrace finish();

  [[nodiscard]] Id self() const { return self_; }
  [[nodiscard]] Id mode(Id robot) const;  // this robot's mode, or a peer's as last heard
  [[nodiscard]] Pose pose(Id robot) const;
  [[nodiscard]] bool alive(Id robot) const;
  [[nodiscard]] bool leads(Id robot, Id leaderBlock) const;
  // The packets it refused, by reason: well-formed, but not what the mission's tables allow.
  [[nodiscard]] const PacketRefusals& refusals() const;

 private:
  Id self_;
  NodeOptions options_;
  SimTrace trace_;
  std::unique_ptr<detail::NodeLink> link_;
  std::unique_ptr<detail::Team> team_;
};

}  // namespace semo::runtime
