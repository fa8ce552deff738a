// The simulator's event loop: the team's initial state, the queue of timed events (plan wake-ups,
// deliveries, heartbeat periods, gossip rounds, crashes, control periods, pose samples), and the
// summary at the end.
#include "semo/runtime/simulator.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "team.hpp"

namespace semo::runtime {
namespace detail {

Team::Team(const MissionTables& tables, const World& world, const TaskLibrary& library, const SimulationOptions& options,
           StepObserver* observer, SimTrace& trace, const NodeLink* node)
    : t_(tables),
      world_(world),
      library_(library),
      options_(options),
      observer_(observer),
      trace_(trace),
      latency_(RandomStream::derive(options.seed, "latency", 0)),
      lossDraws_(RandomStream::derive(options.seed, "loss", 0)),
      node_(node) {
  const std::size_t n = tables.robots.size();
  lastHeard_.assign(n, 0);
  for (std::uint32_t r = 0; r < n; ++r) everyone_.push_back(r);
  heard_.assign(tables.leaderBlocks.size(), 0);
  heardPreferred_.assign(tables.leaderBlocks.size(), 0);
  robots_.resize(n);
  aliveFlags_.assign(n, true);
  crashTime_.assign(n, -1);
  poses_.resize(n);
  leaderNow_.assign(tables.leaderBlocks.size(), kNone);
  channel_.assign(tables.topics.size(), 0);
  crashed_.assign(tables.teams.size(), 0);
  LossModel model = options.lossModel;
  model.p = options.loss;
  for (std::size_t i = 0; i < 4 * n; ++i) links_.emplace_back(model);
  for (Id robot = 0; robot < n; ++robot) {
    const RobotTable& table = tables.robots[robot];
    const TeamTable& team = tables.teams[table.team];
    teamNames_.push_back(team.name);
    RobotRun& r = robots_[robot];
    r.mode = team.initialMode;
    r.plans.resize(table.plans.size());
    for (std::size_t p = 0; p < table.plans.size(); ++p) {
      const PlanTable& plan = table.plans[p];
      std::size_t widest = 0;
      for (std::size_t pc = 0; pc + 1 < plan.firstRow.size(); ++pc) widest = std::max<std::size_t>(widest, plan.firstRow[pc + 1] - plan.firstRow[pc]);
      r.plans[p].keep.assign(widest, 0);
      r.plans[p].iterationStart.assign(plan.points.size(), -1);
    }
    r.eventPending.assign(team.events.size(), 0);
    r.view.assign(tables.topics.size(), 0);
    r.message.assign(tables.topics.size(), 0);
    r.leads.assign(tables.leaderBlocks.size(), 0);
    r.roles.assign(tables.groupBlocks.size(), std::string());
    r.silence.assign(tables.leaderBlocks.size(), 0);
    r.lostRun.assign(tables.leaderBlocks.size(), 0);
    for (Id k : table.knowledge) {
      const KnowledgeTable& item = tables.knowledge[k];
      r.knowledge.emplace_back(item.facts, item.newest ? KnowledgeStore::Merge::Newest : KnowledgeStore::Merge::Union);
    }
    const StartPose* start = world.start(table.name);
    Pose pose;
    if (start != nullptr) pose = {start->at.x, start->at.y, start->heading};
    else pose = {static_cast<double>(table.indexInTeam), -static_cast<double>(table.team), 0.0};  // a replay without a world: one row per team
    bodies_.emplace_back(pose, table.geometry, 0.0);
    poses_[robot] = pose;
    r.destination = {1e9, 1e9};  // nowhere yet: "at_destination" holds only once a move has ended there
  }
  varSlot_.assign(tables.abstraction.size(), -1);
  for (std::size_t v = 0; v < tables.abstraction.size(); ++v) {
    const AbstractVar& var = tables.abstraction[v];
    if (var.kind != AbstractVar::Kind::Knows) continue;
    const std::vector<Id>& items = tables.robots[var.robot].knowledge;
    varSlot_[v] = static_cast<std::int32_t>(std::find(items.begin(), items.end(), var.index) - items.begin());
  }
  for (const KnowledgeTable& item : tables.knowledge) trace_.summary.convergedAt.emplace_back(item.name, -1.0);
}

void Team::schedule(Micros t, QueuedEvent::Kind kind, Id a, Id b, std::uint64_t generation) {
  queue_.push({t, seq_++, kind, a, b, generation});
}

void Team::run() {
  start();
  processUntil(toMicros(options_.duration));
  finish();
}

void Team::start() {
  for (Id robot = 0; robot < robots_.size(); ++robot) {
    const TeamTable& team = t_.teams[t_.robots[robot].team];
    // The initial mode is a mode too: the timeline shows it from the start.
    // (Labelled "starts in": the mode changes are the events after it.)
    if (local(robot)) note(robot, TraceEvent::Kind::Mode, "starts in " + team.modes[robots_[robot].mode].name, team.modes[robots_[robot].mode].name);
    for (Id p = 0; p < robots_[robot].plans.size(); ++p) {
      // A networked robot's peers are replicas: where they are comes from their Status packets.
      if (local(robot)) startPlan(robot, p, team.modes[robots_[robot].mode].entry[p]);
      else robots_[robot].plans[p].pc = team.modes[robots_[robot].mode].entry[p];
    }
  }
  startTimers();
  for (Id c = 0; c < options_.crashes.size(); ++c) schedule(toMicros(options_.crashes[c].at), QueuedEvent::Kind::Crash, c);
  abstractState(before_);
  if (node_ != nullptr) sendStatus();
}

bool Team::advanceTo(Micros t) {
  processUntil(t);
  if (node_ != nullptr && !over()) {
    // Time passes even without an event; what reached the robot meanwhile is taken now.
    now_ = std::max(now_, t);
    pollNetwork();
    processUntil(t);
  }
  return !over();
}

void Team::finish() {
  for (std::size_t r = 0; r < bodies_.size(); ++r) {
    if (local(static_cast<Id>(r))) bodies_[r].advanceTo(now());
  }
  samplePoses();
  trace_.duration = now();
}

// The periodic events from now on: heartbeat periods, gossip rounds, control periods, pose samples.
void Team::startTimers() {
  for (Id lb = 0; lb < t_.leaderBlocks.size(); ++lb) {
    const std::vector<Id>& c = t_.leaderBlocks[lb].candidates;
    const bool mine = node_ == nullptr || std::find(c.begin(), c.end(), node_->self) != c.end();
    if (t_.leaderBlocks[lb].detectsFailures && mine) schedule(now_ + toMicros(t_.leaderBlocks[lb].heartbeat), QueuedEvent::Kind::Heartbeat, lb);
  }
  for (Id k = 0; k < t_.knowledge.size(); ++k) {
    const bool mine = node_ == nullptr || t_.knowledge[k].team == t_.robots[node_->self].team;
    if (t_.knowledge[k].shared && mine) schedule(now_ + toMicros(t_.knowledge[k].period), QueuedEvent::Kind::Gossip, k);
  }
  schedule(now_, QueuedEvent::Kind::Control);
  schedule(now_, QueuedEvent::Kind::Sample);
  if (node_ != nullptr) schedule(now_ + node_->statusPeriod, QueuedEvent::Kind::Status);
}

void Team::processUntil(Micros end) {
  while (!queue_.empty() && !over()) {
    QueuedEvent e = queue_.top();
    if (e.t > end) break;
    queue_.pop();
    e.t = std::max(e.t, now_);  // after a replay's script, wake-ups it left behind happen now
    if (e.t != now_) zeroTimeSteps_ = 0;
    now_ = e.t;
    switch (e.kind) {
      case QueuedEvent::Kind::Wake:
        if (robots_[e.a].alive && robots_[e.a].plans[e.b].generation == e.generation) advance(e.a, e.b);
        break;
      case QueuedEvent::Kind::DeliverEvent: deliverEvent(e.a, e.b); break;
      case QueuedEvent::Kind::DeliverMessage: deliverMessage(e.a, e.b); break;
      case QueuedEvent::Kind::Heartbeat:
        if (node_ != nullptr) nodeHeartbeat(e.a);
        else heartbeatPeriod(e.a);
        break;
      case QueuedEvent::Kind::Gossip:
        if (node_ != nullptr) nodeGossip(e.a);
        else gossip(e.a);
        break;
      case QueuedEvent::Kind::Crash: crashPlanned(e.a); break;
      case QueuedEvent::Kind::Control:
        stepBehaviours();
        schedule(now_ + toMicros(options_.controlPeriod), QueuedEvent::Kind::Control);
        break;
      case QueuedEvent::Kind::Sample:
        samplePoses();
        schedule(now_ + toMicros(options_.poseSampling), QueuedEvent::Kind::Sample);
        break;
      case QueuedEvent::Kind::Status: statusTick(); break;
    }
    while (dirty_ && !stopped_) {
      dirty_ = false;
      retryBlocked();
    }
    if (!goalSeen_ && goalReached()) {
      goalSeen_ = true;
      trace_.summary.completed = true;
      trace_.summary.completedAt = now();
      note(kNone, TraceEvent::Kind::Note, "the mission's goal is reached");
    }
  }
}

void Team::crashPlanned(Id c) {
  const std::string& who = options_.crashes[c].robot;
  Id target = kNone, ledBlock = kNone;
  if (who == "leader" || who.rfind("leader:", 0) == 0) {
    const std::string block = who.size() > 7 ? who.substr(7) : std::string();
    for (Id lb = 0; lb < t_.leaderBlocks.size() && target == kNone; ++lb) {
      if (!block.empty() && t_.leaderBlocks[lb].name.find(block) == std::string::npos) continue;
      for (Id cand : t_.leaderBlocks[lb].candidates) {
        if (robots_[cand].alive && robots_[cand].leads[lb] != 0) target = cand, ledBlock = lb;
      }
    }
    if (target == kNone) {
      note(kNone, TraceEvent::Kind::Note, "crash of " + who + " planned, but no robot leads then");
      return;
    }
    // The faults say whom it hit: "crash leader at 5 s (ev3_1, leader of SlaveTeam.Report.ReportPapers#2)".
    const std::string planned = "crash " + who + " at " + fmt::format("{:g}", options_.crashes[c].at) + " s";
    const std::size_t at = trace_.faults.find(planned);
    if (at != std::string::npos && trace_.faults.compare(at + planned.size(), 2, " (") != 0) {
      trace_.faults.insert(at + planned.size(), " (" + t_.robots[target].name + ", leader of " + t_.leaderBlocks[ledBlock].name + ")");
    }
  } else {
    for (Id r = 0; r < t_.robots.size(); ++r) {
      if (t_.robots[r].name == who) target = r;
    }
    if (target == kNone) return;  // checked before the run
  }
  if (!local(target)) return;  // a networked robot crashes only itself (its peers see it fall silent)
  crash(target, "injected at " + formatSeconds(now_) + " s");
}

void Team::samplePoses() {
  PoseSample s;
  s.t = now();
  for (std::size_t r = 0; r < bodies_.size(); ++r) {
    if (!local(static_cast<Id>(r))) continue;  // a peer's pose is the one its last Pose packet gave
    if (robots_[r].alive) bodies_[r].advanceTo(now());
    poses_[r] = bodies_[r].pose();
  }
  s.poses = poses_;
  trace_.poses.push_back(std::move(s));
}

bool Team::goalReached() const {
  auto allDone = [&](Id robot, const std::vector<std::string>* plans) {
    const RobotTable& table = t_.robots[robot];
    for (Id p = 0; p < table.plans.size(); ++p) {
      if (plans != nullptr && std::find(plans->begin(), plans->end(), table.plans[p].name) == plans->end()) continue;
      if (robots_[robot].plans[p].pc != 0) return false;
    }
    return true;
  };
  if (world_.goal.empty()) {
    for (Id r = 0; r < robots_.size(); ++r) {
      if (robots_[r].alive && !allDone(r, nullptr)) return false;
    }
    return true;
  }
  for (const TeamGoal& g : world_.goal) {
    for (Id r = 0; r < robots_.size(); ++r) {
      const TeamTable& team = t_.teams[t_.robots[r].team];
      if (team.name != g.team || !robots_[r].alive) continue;
      if (team.modes[robots_[r].mode].name != g.mode || !allDone(r, &g.plansDone)) return false;
    }
  }
  return true;
}

SimTrace emptyTrace(const MissionTables& tables, const World& world, const SimulationOptions& options) {
  SimTrace trace;
  trace.modelFingerprint = tables.modelFingerprint;
  trace.seed = options.seed;
  trace.world = world;
  trace.worldFile = world.path;
  for (const TeamTable& team : tables.teams) trace.teams.push_back(team.name);
  for (const RobotTable& r : tables.robots) trace.robots.push_back({r.name, r.type, tables.teams[r.team].name, r.geometry});
  std::string faults;
  for (const CrashPlan& c : options.crashes) faults += (faults.empty() ? "" : "; ") + ("crash " + c.robot + " at " + fmt::format("{:g}", c.at) + " s");
  if (options.loss > 0) {
    faults += (faults.empty() ? "" : "; ") + ("loss " + fmt::format("{:g}", options.loss) + " " + options.lossModel.describe());
  }
  trace.faults = faults.empty() ? "none" : faults;
  trace.summary.goalStated = !world.goal.empty();
  return trace;
}

}  // namespace detail

SimTrace simulate(const MissionTables& tables, const World& world, const TaskLibrary& library, const SimulationOptions& options,
                  StepObserver* observer) {
  SimTrace trace = detail::emptyTrace(tables, world, options);
  detail::Team team(tables, world, library, options, observer, trace);
  team.run();
  return trace;
}

std::vector<std::int32_t> initialAbstractState(const MissionTables& tables) {
  std::vector<std::int32_t> out;
  for (const AbstractVar& v : tables.abstraction) out.push_back(v.init);
  return out;
}

}  // namespace semo::runtime
