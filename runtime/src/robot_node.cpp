// RobotNode (robot_node.hpp): a Team in node mode (team_node.cpp) with this robot as its own.
#include "semo/runtime/robot_node.hpp"

#include "team.hpp"

namespace semo::runtime {

RobotNode::RobotNode(const MissionTables& mission, Id self, const World& world, const TaskLibrary& library, Transport& transport,
                     const NodeOptions& options)
    : self_(self), options_(options), link_(std::make_unique<detail::NodeLink>()) {
  trace_ = detail::emptyTrace(mission, world, options_.simulation);
  link_->self = self;
  link_->transport = &transport;
  link_->statusPeriod = detail::toMicros(options.statusPeriod);
  link_->peerTimeout = detail::toMicros(options.peerTimeout);
  team_ = std::make_unique<detail::Team>(mission, world, library, options_.simulation, nullptr, trace_, link_.get());
}

RobotNode::~RobotNode() = default;

void RobotNode::start() { team_->start(); }
bool RobotNode::advanceTo(std::int64_t micros) { return team_->advanceTo(micros); }
std::int64_t RobotNode::nextEventTime() const { return team_->nextEventTime(); }

SimTrace RobotNode::finish() {
  team_->finish();
  return trace_;
}

Id RobotNode::mode(Id robot) const { return team_->robot(robot).mode; }
Pose RobotNode::pose(Id robot) const { return team_->pose(robot); }
bool RobotNode::alive(Id robot) const { return team_->robot(robot).alive; }
bool RobotNode::leads(Id robot, Id leaderBlock) const { return team_->robot(robot).leads[leaderBlock] != 0; }
const PacketRefusals& RobotNode::refusals() const { return team_->refusals(); }

}  // namespace semo::runtime
