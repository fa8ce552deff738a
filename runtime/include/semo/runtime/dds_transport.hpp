#pragma once
// Eclipse Cyclone DDS as a Transport (specs/runtime.md, "Transports"), the DDS implementation ROS 2
// uses, through its C API (Debian's cyclonedds-dev), so that a team of generated programs can share
// a network with ROS 2 nodes. Built only when the package is there (semo_runtime then says so:
// ddsBuilt()); otherwise makeDdsTransport refuses with the reason.
//
// Two topics per mission (their names carry the model's fingerprint, so missions never mix):
//   best effort, keep last: what the protocol sends again anyway (events, publishes, heartbeats,
//     gossip, Status, Pose), the DDS counterpart of a lossy multicast port;
//   reliable, keep all: the reliable channels' sends and receives and leader announcements, with
//     resource limits from the proven capacities of the mission's channels.
// A sample carries its receiver; every reader takes only what is addressed to its robot.
#include <memory>
#include <string>

#include "semo/runtime/tables.hpp"
#include "semo/runtime/transport.hpp"

namespace semo::runtime {

[[nodiscard]] bool ddsBuilt();

struct DdsOptions {
  int domain = 0;
  // A network interface address ("127.0.0.1"): the domain is configured to use only it, with
  // multicast on (a loopback interface often lacks the MULTICAST flag). Empty: Cyclone DDS's own
  // choice, or its configuration in CYCLONEDDS_URI.
  std::string interfaceAddress;
};

// Null with `error` set when DDS is not built in, or the participant, topics, readers or writers
// cannot be made.
std::unique_ptr<Transport> makeDdsTransport(const MissionTables& mission, Id self, const DdsOptions& options, std::string& error);

}  // namespace semo::runtime
