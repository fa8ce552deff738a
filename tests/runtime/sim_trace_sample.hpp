#pragma once
// A simulated trace with every kind of content (three robots, a crash, messages sent and lost, roles,
// facts, violations, awkward text), built by hand for the trace writers' tests.
#include <string>

#include "semo/runtime/kinematics.hpp"
#include "semo/runtime/sim_trace.hpp"

namespace semo::runtime::sample {

inline TraceEvent event(double t, std::uint32_t robot, TraceEvent::Kind kind, std::string detail = "", std::uint32_t peer = kNoRobot) {
  TraceEvent e;
  e.t = t;
  e.robot = robot;
  e.kind = kind;
  e.detail = std::move(detail);
  e.peer = peer;
  return e;
}

// Three robots searching a field for coloured papers: one crashes, messages are sent and lost.
inline SimTrace sampleTrace() {
  SimTrace tr;
  tr.mission = "specs/examples/search & report.semo";
  tr.strategy = "strategy.xml";
  tr.worldFile = "field.json";
  tr.modelFingerprint = "3f2a9c";
  tr.seed = 7;
  tr.duration = 60;
  tr.faults = "crash ev3_1 at 25 s; loss 0.2 bernoulli";
  tr.teams = {"MasterTeam", "SlaveTeam"};
  DriveGeometry ev3;
  ev3.wheeled = true;
  ev3.wheelRadius = 0.028;
  ev3.wheelSeparation = 0.12;
  tr.robots = {{"turtle_0", "TurtlebotBurger", "MasterTeam", {}}, {"ev3_1", "Ev3Robot", "SlaveTeam", ev3}, {"ev3_2", "Ev3Robot", "SlaveTeam", ev3}};

  World& w = tr.world;
  w.path = "field.json";
  w.arena = std::pair{Vec2{0, 0}, Vec2{10, 6}};
  w.places = {{"base camp", {1, 1}, {}}, {"Paris palace of congress", {8, 4.5}, {}}};
  Shape ditch;
  ditch.kind = Shape::Kind::Polygon;
  ditch.points = {{4.5, 0}, {5, 0}, {5, 2.5}, {4.5, 2.5}};
  Shape rock;
  rock.center = {6.5, 4};
  rock.radius = 0.4;
  w.obstacles = {{"ditch", ditch, {}}, {"rock <big>", rock, {}}};
  w.facts = {{"papers", "red", {3, 4}, 0.3, {}}, {"papers", "blue", {8, 1.5}, 0.5, {}}};
  w.starts = {{"turtle_0", {1, 1}, 0, {}}, {"ev3_1", {1, 2}, 0.5, {}}, {"ev3_2", {1, 3}, 0, {}}};

  // Poses from the bodies themselves, sampled every half second.
  std::vector<Body> bodies;
  for (const StartPose& s : w.starts) bodies.emplace_back(Pose{s.at.x, s.at.y, s.heading}, DriveGeometry{});
  bodies[0].command(0.1, 0.05);
  bodies[1].command(0.3, 0);
  bodies[2].command(0.2, -0.08);
  for (double t = 0; t <= 60; t += 0.5) {
    PoseSample sample;
    sample.t = t;
    for (std::size_t r = 0; r < bodies.size(); ++r) {
      if (r == 1 && t > 25) bodies[r].command(0, 0);  // crashed: it stays where it is
      if (r == 2 && t == 30) bodies[r].command(0.2, 0.15);
      bodies[r].advanceTo(t);
      sample.poses.push_back(bodies[r].pose());
    }
    tr.poses.push_back(sample);
  }

  using K = TraceEvent::Kind;
  tr.events.push_back(event(0, 0, K::Mode, "START_MODE"));
  tr.events.push_back(event(0, 1, K::Mode, "SEARCH_MODE"));
  tr.events.push_back(event(0, 2, K::Mode, "SEARCH_MODE"));
  TraceEvent step = event(0.5, 1, K::Step);
  step.rule = "SlaveTeam.search.1,SlaveTeam.search.2";
  step.origin = "mission.semo:12:5 move";
  step.changes = {{"pc_ev3_1", 0, 1}, {"at_ev3_1", 0, 2}};
  tr.events.push_back(step);
  tr.events.push_back(event(2, 1, K::Role, "leader of ReportPapers"));
  tr.events.push_back(event(2, 2, K::Role, "others"));
  tr.events.push_back(event(5, 1, K::Send, "found", kNoRobot));
  tr.events.push_back(event(5.2, 2, K::Deliver, "found", 1));
  tr.events.push_back(event(5.2, 0, K::Drop, "found", 1));
  tr.events.push_back(event(12, 2, K::Fact, "papers: red"));
  tr.events.push_back(event(20, 1, K::Send, "report", 0));
  tr.events.push_back(event(20.3, 0, K::Deliver, "report", 1));
  tr.events.push_back(event(22, 0, K::Mode, "COLLECT_MODE"));
  tr.events.push_back(event(25, 1, K::Crash));
  tr.events.push_back(event(31, 2, K::Role, "leader of ReportPapers"));
  tr.events.push_back(event(40, 2, K::Send, "report", 0));
  tr.events.push_back(event(40.1, 0, K::Drop, "report", 2));
  tr.events.push_back(event(41, 2, K::Role, ""));
  tr.events.push_back(event(45, 2, K::Mode, "RETURN_MODE"));
  TraceEvent note = event(50, kNoRobot, K::Note);
  note.label = "quote \" backslash \\ tab \t and a stray byte \xff";
  tr.events.push_back(note);
  TraceEvent violation = event(55, 2, K::Violation);
  violation.label = "P1: never (ev3_2 in RETURN_MODE and turtle_0 in START_MODE)";
  tr.events.push_back(violation);
  tr.events.push_back(event(57, kNoRobot, K::Violation, "conformance"));

  TraceSummary& s = tr.summary;
  s.goalStated = true;
  s.completed = true;
  s.completedAt = 58.25;
  s.modeChanges = {{22, "turtle_0: COLLECT_MODE"}, {45, "ev3_2: RETURN_MODE"}};
  s.leaderChanges = {{"SlaveTeam.Report.ReportPapers", 2, kNoRobot, 1, -1}, {"SlaveTeam.Report.ReportPapers", 31, 1, 2, 6}};
  s.convergedAt = {{"papers", 33.5}, {"obstacles", -1}};
  s.messagesSent = 3;
  s.messagesLost = 2;
  s.stepsChecked = 120;
  s.mismatches = 1;
  s.outsideAssumptions = "ev3_1 crashed after the budget";
  s.violations = {"P1"};
  // Dataflow: turtle_0 ran two of its three scenarios and filled one channel to its capacity; ev3_1
  // overflowed once; ev3_2 has an unproven scenario it never ran.
  s.dataflow.resize(3);
  s.dataflow[0] = {{"SEARCH", "RETURN", "HIDE"}, {1200, 34, 0}, {"a->b", "b->control"}, {4, 1}, {4, 0}, 0, 0, {}};
  s.dataflow[1] = {{"SEARCH"}, {7}, {"a->b"}, {2}, {2}, 0, 1, {}};
  s.dataflow[2] = {{"COLLECT"}, {0}, {}, {}, {}, 0, 0, {"COLLECT: an iteration deadlocks"}};
  return tr;
}

}  // namespace semo::runtime::sample
