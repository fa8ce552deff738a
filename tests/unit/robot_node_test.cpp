// Networked robots (runtime/robot_node.hpp): one RobotNode per robot over one InProcessTransport,
// driven in simulated time, millisecond by millisecond, so that the runs are deterministic. The
// paper's two experiments must come out as in the simulator: the swarm stops before the ditch, and
// the scouting team replaces its crashed leader and completes.
#include <gtest/gtest.h>

#include "mission_fixture.hpp"

#include "semo/runtime/robot_node.hpp"

#include <array>
#include <bit>
#include <functional>
#include <limits>

namespace semo {
namespace {

struct Team {
  std::unique_ptr<test::LoadedMission> mission;
  std::unique_ptr<runtime::InProcessTransport> transport;
  std::vector<std::unique_ptr<runtime::RobotNode>> nodes;
  std::vector<runtime::SimTrace> traces;
};

// Runs every robot of an example as a node, to `seconds` (or until every node sees the goal).
// `startAt` (per robot, microseconds; default all 0): when each program starts, as processes launched
// one after the other do; a node's own clock starts then.
// `intruder`, when given, is called every millisecond with the time and the transport, before the
// nodes advance: it may put packets of its own on the network.
using Intruder = std::function<void(std::int64_t micros, runtime::InProcessTransport&)>;

Team runNodes(const std::string& dir, const std::string& stem, runtime::NodeOptions options, double seconds, std::uint64_t seed = 1,
              const std::string& strategy = "strategy.xml", std::vector<std::int64_t> startAt = {}, const Intruder& intruder = {}) {
  Team t;
  t.mission = test::loadExample(dir, stem, strategy);
  EXPECT_TRUE(t.mission && t.mission->world);
  const runtime::MissionTables& tables = t.mission->tables;
  runtime::InProcessTransport::Options to;
  to.robots = static_cast<std::uint32_t>(tables.robots.size());
  to.queueCapacity = 4096;
  to.seed = seed;
  t.transport = std::make_unique<runtime::InProcessTransport>(to);
  options.simulation.seed = seed;
  options.simulation.duration = seconds;
  static const runtime::TaskLibrary library = runtime::TaskLibrary::standard();
  for (runtime::Id r = 0; r < tables.robots.size(); ++r) {
    t.nodes.push_back(std::make_unique<runtime::RobotNode>(tables, r, *t.mission->world, library, *t.transport, options));
  }
  startAt.resize(t.nodes.size(), 0);
  std::vector<bool> running(t.nodes.size(), true);
  const auto end = static_cast<std::int64_t>(seconds * 1e6);
  for (std::int64_t micros = 0; micros <= end + startAt.back(); micros += 1000) {
    if (intruder) intruder(micros, *t.transport);
    bool any = false;
    for (std::size_t i = 0; i < t.nodes.size(); ++i) {
      if (micros == startAt[i]) t.nodes[i]->start();
      if (running[i] && micros >= startAt[i]) running[i] = t.nodes[i]->advanceTo(micros - startAt[i]);
      any = any || running[i];
    }
    if (!any) break;
  }
  for (auto& n : t.nodes) t.traces.push_back(n->finish());
  // The team's own packets are all what the mission's tables allow.
  if (!intruder) {
    for (const auto& n : t.nodes) EXPECT_EQ(n->refusals().total(), 0u) << tables.robots[n->self()].name;
  }
  return t;
}

// A node's trace in lines (for a failure's message): its own steps, roles, crashes and deliveries.
std::string lines(const runtime::MissionTables& tables, const runtime::SimTrace& trace) {
  std::string out;
  for (const runtime::TraceEvent& e : trace.events) {
    if (e.kind == runtime::TraceEvent::Kind::Step && e.label.find("continues") != std::string::npos) continue;
    out += std::to_string(e.t) + " " + runtime::eventKindName(e.kind) + " " +
           (e.robot == runtime::kNoRobot ? std::string("-") : tables.robots[e.robot].name) + " " + e.label + "\n";
  }
  return out;
}

runtime::Id robotIndex(const runtime::MissionTables& t, const std::string& name) {
  for (runtime::Id r = 0; r < t.robots.size(); ++r) {
    if (t.robots[r].name == name) return r;
  }
  return runtime::kNone;
}

TEST(RobotNode, TheSwarmStopsBeforeTheDitchOverTheNetwork) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    runtime::NodeOptions options;
    options.simulation.loss = 0.2;
    Team t = runNodes("swarm", "swarm3", options, 60, seed);
    const runtime::MissionTables& tables = t.mission->tables;
    const runtime::Id retreat = 1;  // RETREAT_MODE
    ASSERT_EQ(tables.teams[0].modes[retreat].name, "RETREAT_MODE");
    for (std::size_t i = 0; i < t.nodes.size(); ++i) {
      SCOPED_TRACE(tables.robots[i].name);
      EXPECT_TRUE(t.traces[i].summary.completed) << "every node sees the goal reached";
      EXPECT_EQ(t.nodes[i]->mode(static_cast<runtime::Id>(i)), retreat);
      double eastmost = -1e9;
      for (const runtime::PoseSample& s : t.traces[i].poses) eastmost = std::max(eastmost, s.poses[i].x);
      EXPECT_LT(eastmost, 4.0 - 0.3) << "the ditch starts at x = 4";
      EXPECT_GT(eastmost, 2.5) << "it did march";
    }
    EXPECT_GT(t.transport->counters().delivered, 100u);
  }
}

// Packets well-formed on the wire but not what the mission's tables allow, sent to every robot at
// 3 s by an intruder posing as legged_0: each is refused and counted by reason, and the run is the
// run without them (the same mode changes at the same times). A forged packet within the tables'
// ranges is a matter for authentication, not for these checks.
TEST(RobotNode, PacketsOutsideTheMissionsTablesAreRefusedAndChangeNothing) {
  Team quiet = runNodes("swarm", "swarm3", {}, 40, 2);
  const runtime::MissionTables& tables = quiet.mission->tables;
  using K = runtime::Packet::Kind;
  const std::vector<std::pair<runtime::Packet, runtime::PacketRefusal>> forged = {
      {{.kind = K::KnowledgeFact, .sender = 0, .index = 0, .value = 99, .aux = 0, .word = 7}, runtime::PacketRefusal::Value},  // no fact 99
      {{.kind = K::KnowledgeFact, .sender = 0, .index = 42, .value = 0}, runtime::PacketRefusal::Index},
      {{.kind = K::Status, .sender = 0, .index = 0, .value = 100000, .aux = 0}, runtime::PacketRefusal::Value},  // pc past the plan
      {{.kind = K::Status, .sender = 0, .index = 0, .value = 0, .aux = 7}, runtime::PacketRefusal::Value},       // no mode 7
      {{.kind = K::Pose, .sender = 0, .word = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::quiet_NaN())},
       runtime::PacketRefusal::Pose},
      {{.kind = K::Heartbeat, .sender = 0, .index = 5}, runtime::PacketRefusal::Index},  // swarm3 has no leader block
      {{.kind = K::Event, .sender = 0, .index = 30}, runtime::PacketRefusal::Index},
      {{.kind = K::Publish, .sender = 0, .index = 30, .value = 1}, runtime::PacketRefusal::Index},
      {{.kind = K::KnowledgeDigest, .sender = 0}, runtime::PacketRefusal::Kind},
      // Naming the receiver itself as its sender (filled in per receiver below).
      {{.kind = K::Status, .sender = runtime::kNone, .index = 0}, runtime::PacketRefusal::Sender},
  };
  Team attacked = runNodes("swarm", "swarm3", {}, 40, 2, "strategy.xml", {}, [&](std::int64_t micros, runtime::InProcessTransport& net) {
    if (micros != 3'000'000) return;
    for (const auto& [p, why] : forged) {
      for (std::uint32_t to = 1; to < net.robots(); ++to) {
        runtime::Packet copy = p;
        if (copy.sender == runtime::kNone) copy.sender = to;
        net.send(to, copy);
      }
    }
  });
  for (std::size_t i = 1; i < attacked.nodes.size(); ++i) {
    SCOPED_TRACE(tables.robots[i].name);
    const runtime::PacketRefusals& r = attacked.nodes[i]->refusals();
    std::array<std::uint64_t, runtime::kPacketRefusals> expected{};
    for (const auto& [p, why] : forged) ++expected[static_cast<std::size_t>(why)];
    EXPECT_EQ(r.count, expected);
    EXPECT_EQ(attacked.traces[i].summary.modeChanges, quiet.traces[i].summary.modeChanges);
    EXPECT_EQ(attacked.traces[i].summary.completedAt, quiet.traces[i].summary.completedAt);
  }
}

TEST(RobotNode, WithoutSharingARobotReachesTheDitch) {
  Team t = runNodes("swarm", "swarm3", {}, 60, 1, "strategy_no_sharing.xml");
  int atTheDitch = 0;
  for (runtime::Id r = 0; r < t.nodes.size(); ++r) atTheDitch += t.nodes[r]->pose(r).x > 4.0 - 0.12 ? 1 : 0;
  EXPECT_GE(atTheDitch, 1);
}

// The first leader (bully: the higher index, ev3_1) crashes at 3 s, while ev3_0 waits in the block's
// `others` arm (wait(5 SEC), from 1.9 s): its heartbeats stop, ev3_0 counts four silent periods and
// takes over. (A crash after ev3_0 has left the arm, at 5 s, leaves the block leaderless until it
// forms again, which the model allows too: each robot's heartbeat period runs on its own clock here,
// one period behind the simulator's team-wide one at worst.)
TEST(RobotNode, ScoutingReplacesItsCrashedLeaderOverTheNetwork) {
  runtime::NodeOptions options;
  options.simulation.crashes.push_back({"ev3_1", 3.0});
  Team t = runNodes("scouting", "scouting", options, 60);
  const runtime::MissionTables& tables = t.mission->tables;
  const runtime::Id ev3_0 = robotIndex(tables, "ev3_0"), ev3_1 = robotIndex(tables, "ev3_1");
  ASSERT_NE(ev3_0, runtime::kNone);
  const runtime::SimTrace& trace = t.traces[ev3_0];
  // ev3_0 sees ev3_1 elected, then takes over after the failure timeout (the Burgers' WatchLight
  // block has its own leader).
  std::vector<runtime::LeaderChange> report;
  for (const runtime::LeaderChange& c : trace.summary.leaderChanges) {
    if (c.block.rfind("SlaveTeam.Report.ReportPapers", 0) == 0) report.push_back(c);
  }
  ASSERT_GE(report.size(), 2u) << lines(tables, trace);
  EXPECT_EQ(report.front().to, ev3_1);
  const runtime::LeaderChange& takeover = report.back();
  EXPECT_EQ(takeover.to, ev3_0);
  EXPECT_GE(takeover.t, 3.0);
  EXPECT_LE(takeover.t, 3.0 + 2.0 + 0.5 + 0.01) << "timeout 2 s + one heartbeat period";
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    if (i == ev3_1) continue;
    EXPECT_TRUE(t.traces[i].summary.completed) << tables.robots[i].name;
  }
}

// Programs started one after the other: the candidates reach the Report block's formation point at
// different times on their own clocks, and the Burgers (in its `others` arm) may form it first. Each
// robot elects only after the election window, so every robot sees the same leader: ev3_1 (bully).
TEST(RobotNode, EveryRobotAgreesOnTheLeaderWhateverTheStartingOrder) {
  const std::vector<std::vector<std::int64_t>> orders = {
      {0, 0, 0, 0, 0}, {0, 50'000, 100'000, 150'000, 200'000}, {200'000, 150'000, 100'000, 50'000, 0}, {0, 0, 250'000, 0, 0}};
  for (const std::vector<std::int64_t>& order : orders) {
    Team t = runNodes("scouting", "scouting", {}, 4, 1, "strategy.xml", order);
    const runtime::MissionTables& tables = t.mission->tables;
    ASSERT_EQ(order.size(), tables.robots.size());
    const runtime::Id ev3_1 = robotIndex(tables, "ev3_1");
    for (std::size_t i = 0; i < t.nodes.size(); ++i) {
      SCOPED_TRACE(tables.robots[i].name + ", started " + std::to_string(order[i] / 1000) + " ms late");
      ASSERT_FALSE(t.traces[i].summary.leaderChanges.empty()) << lines(tables, t.traces[i]);
      for (const runtime::LeaderChange& c : t.traces[i].summary.leaderChanges) {
        if (c.block.rfind("SlaveTeam.Report.ReportPapers", 0) == 0) {
          EXPECT_EQ(c.to, ev3_1) << lines(tables, t.traces[i]);
        }
      }
    }
  }
}

}  // namespace
}  // namespace semo
