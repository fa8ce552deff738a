#pragma once
// The running team inside the simulator: every robot's real state (modes, program counters, walks
// under way, views, knowledge with its facts and stamps, leader beliefs, failure-detector counters),
// the in-process network (events, message slots, reliable channels in flight) and the event queue.
// Split by concern: team_steps.cpp (a robot's plan walks and the effects of its rows),
// team_network.cpp (deliveries, losses, heartbeat periods, takeovers, gossip, crashes),
// team_abstraction.cpp (the abstraction function), simulator.cpp (the event loop and the trace).
#include <cstdint>
#include <memory>
#include <queue>
#include <string>
#include <vector>

#include "semo/runtime/knowledge.hpp"
#include "semo/runtime/packet_check.hpp"
#include "semo/runtime/random.hpp"
#include "semo/runtime/replay.hpp"
#include "semo/runtime/simulator.hpp"
#include "semo/runtime/transport.hpp"
#include "team_dataflow.hpp"

namespace semo::runtime::detail {

using Micros = std::int64_t;
inline Micros toMicros(double seconds) { return static_cast<Micros>(seconds * 1e6 + (seconds >= 0 ? 0.5 : -0.5)); }
inline double toSeconds(Micros t) { return static_cast<double>(t) / 1e6; }
std::string formatSeconds(Micros t);  // "5.000000"

// One plan of one robot: where it rests (its IR program counter) and the walk under way from there.
struct PlanRun {
  enum class Phase : std::uint8_t {
    Ready,    // at a control point, about to start a walk
    Period,   // at a periodic loop's back edge, waiting for the next iteration
    Busy,     // a call or a wait of the walk is under way
    Blocked,  // the walk is done but no row's guard holds: waits for the team to change
    Idle,     // nothing to do here (no rows, or a group service point: see `working`)
  };
  Id pc = 0;
  Phase phase = Phase::Ready;
  std::uint32_t action = 0;        // the walk's next action
  std::vector<std::uint8_t> keep;  // per row of pc: still a candidate
  std::vector<Micros> iterationStart;  // per program counter (periodic loop back edges)
  std::uint64_t generation = 0;    // bumps when the walk is abandoned (a wake-up of an old walk is ignored)
  std::unique_ptr<Behaviour> behaviour;  // the call under way, or the group service worked in
  Id behaviourCall = kNone;
  BehaviourContext context;
  bool working = false;            // in a group service with its group started
  Micros busyUntil = 0;
  Micros restingSince = 0;         // when it came to rest at pc
};

struct RobotRun {
  bool alive = true;
  Id mode = 0;
  std::vector<PlanRun> plans;
  std::vector<std::uint8_t> eventPending;  // per event of the team
  std::vector<std::int32_t> view;          // per topic (0 none, else symbol + 1)
  std::vector<std::int32_t> message;       // per topic: the value on its way (0 none)
  std::vector<std::uint8_t> leads;         // per leader block (MissionTables::leaderBlocks)
  std::vector<std::int32_t> silence, lostRun;
  std::vector<KnowledgeStore> knowledge;   // per entry of RobotTable::knowledge
  std::uint64_t lamport = 0;
  Vec2 destination;
  std::vector<std::string> roles;          // per group block, for the trace ("" outside it)
};

struct QueuedEvent {
  enum class Kind : std::uint8_t { Wake, DeliverEvent, DeliverMessage, Heartbeat, Gossip, Crash, Control, Sample, Status };
  Micros t = 0;
  std::uint64_t seq = 0;
  Kind kind = Kind::Wake;
  Id a = 0, b = 0;
  std::uint64_t generation = 0;
  bool operator>(const QueuedEvent& o) const { return t != o.t ? t > o.t : seq > o.seq; }
};

// A trace with the run's header filled in (mission tables, world, seed, faults) and no events yet.
SimTrace emptyTrace(const MissionTables& tables, const World& world, const SimulationOptions& options);

// A networked robot (robot_node.hpp): this process runs robot `self` only; every other robot of the
// Team is a replica, kept from its Status and Pose packets, and what the simulator does to another
// robot directly (an event's slot, a publish's message, an election) goes out as a packet instead
// (team_node.cpp, specs/runtime.md "Networked robots").
// What a lost packet was: Team::lose draws each kind's losses on its own link per receiver.
enum LinkKind : Id { EventLink = 0, MessageLink = 1, HeartbeatLink = 2, GossipLink = 3 };

struct NodeLink {
  Id self = kNone;
  Transport* transport = nullptr;
  Micros statusPeriod = 100'000;  // a Status broadcast at least this often (and after every step)
  Micros peerTimeout = 3'000'000;  // a peer silent this long is taken as crashed
  // A candidate at a leader block's formation point elects only after resting there this long, so
  // that the candidates arriving together know of each other (their Status packets) and elect the
  // same leader.
  Micros electionWindow = 300'000;
};

class Team {
 public:
  Team(const MissionTables& tables, const World& world, const TaskLibrary& library, const SimulationOptions& options,
       StepObserver* observer, SimTrace& trace, const NodeLink* node = nullptr);
  void run();
  // run() in parts, for a networked robot driven by a clock: start, then advance to one time after
  // another (false once the run is over: stopped, or the goal reached with stopAtGoal), then finish.
  void start();
  bool advanceTo(Micros t);
  void finish();
  [[nodiscard]] Micros nextEventTime() const { return queue_.empty() ? INT64_MAX : queue_.top().t; }
  [[nodiscard]] Micros time() const { return now_; }
  [[nodiscard]] const RobotRun& robot(Id r) const { return robots_[r]; }
  [[nodiscard]] const Pose& pose(Id r) const { return poses_[r]; }
  // A networked robot: the packets it refused, by reason (packet_check.hpp).
  [[nodiscard]] const PacketRefusals& refusals() const { return refusals_; }
  // A networked robot's run is over when it crashes too: a crash stops its program.
  [[nodiscard]] bool over() const {
    return stopped_ || (goalSeen_ && options_.stopAtGoal) || (node_ != nullptr && !robots_[node_->self].alive);
  }
  // Replay (replay.hpp): takes exactly `rules`, then runs freely for `settle` seconds.
  void runScript(const std::vector<Id>& rules, const ReplayOptions& options);

 private:
  // ---- team_steps.cpp
  void startPlan(Id robot, Id plan, Id pc);
  void advance(Id robot, Id plan);
  bool commit(Id robot, Id plan);
  bool guardsHold(Id robot, const Row& row) const;
  bool testsHold(Id robot, const Row& row) const;
  void applyEffects(Id robot, Id plan, const Row& row);
  void enterMode(Id robot, Id mode);
  void abandonWalk(Id robot, Id plan);
  bool evaluate(Id robot, Id condition) const;
  bool groupStarted(Id robot, Id plan, Id pcSet) const;
  Id electedLeader(Id leaderBlock) const;  // the candidate the election picks now (kNone: none)
  bool noLeader(Id leaderBlock) const;
  bool settledForElection(Id robot, Id leaderBlock) const;
  void startCall(Id robot, Id plan, Id call);
  void stepBehaviours();
  void retryBlocked();
  void afterStep(Id robot);
  std::vector<std::string> callArgs(Id robot, Id call) const;
  struct Reading {
    bool isNumber = false;
    double number = 0;
    std::string_view symbol;
  };
  Reading read(Id robot, const Operand& o) const;
  Reading sense(Id robot, Id sensed) const;

  // ---- team_network.cpp
  void throwEvent(Id robot, Id event);
  void publish(Id robot, const EffectRow& e);
  void deliverEvent(Id robot, Id event);
  void deliverMessage(Id robot, Id topic);
  void heartbeatPeriod(Id leaderBlock);
  void takeovers(Id robot);
  [[nodiscard]] bool canTakeOver(Id robot, std::size_t slot) const;
  void takeOver(Id robot, std::size_t slot);
  bool learnFrom(Id q, Id sender, Id knowledge);
  void discoverFact(Id robot, const RobotTable::Discover& d, std::uint32_t fact);
  void gossip(Id knowledge);
  void discover(Id robot, Id plan);
  void crash(Id robot, const std::string& why);
  void crashPlanned(Id crashPlan);
  bool lose(Id kind, Id link, bool lossy, std::int64_t retransmissions);
  bool loseHeartbeat(std::size_t candidate, Id robot);
  bool waiting(Id robot, Id leaderBlock) const;
  bool inService(Id robot, Id knowledge) const;
  void leaderChange(Id leaderBlock, Id robot);
  // The robot's role in a group block is now `role` ("" when it leaves): one Role event naming the
  // block, whose lane of the robot's timeline then shows it. `why` labels the event when it is not
  // the role itself ("steps down: hears a preferred leader").
  void setRole(Id robot, Id groupBlock, std::string role, std::string why = {});
  // Its leader block's role, "leader of BLOCK".
  std::string leaderRole(Id groupBlock) const;
  void convergence(Id knowledge);
  Micros latency();

  // ---- team_abstraction.cpp
  void abstractState(std::vector<std::int32_t>& out) const;
  [[nodiscard]] std::int32_t teamCount(const AbstractVar& var) const;
  // A step of the model: `rules` (IR rule indices; empty: a stutter) taken by `robot`.
  void step(Id robot, std::vector<Id> rules, std::string what, std::string origin = {});
  void beginStep();

  // ---- team_replay.cpp: one step of a counterexample, forced; "" when taken, else why it cannot be
  std::string forceStep(Id rule, const RuleSite& site);
  std::string forceRow(Id robot, Id plan, Id row);

  // ---- team_node.cpp: a networked robot
  [[nodiscard]] bool local(Id robot) const { return node_ == nullptr || robot == node_->self; }
  void emit(Id to, Packet p);
  void emitToTeam(Id team, Packet p);  // every other robot of the team
  void emitToAll(Packet p);            // every other robot of the mission
  void pollNetwork();
  void onPacket(const Packet& p);
  void sendStatus();
  void statusTick();
  void nodeHeartbeat(Id leaderBlock);
  void nodeGossip(Id knowledge);
  void nodeElect(Id leaderBlock);

  // ---- simulator.cpp
  void startTimers();
  void processUntil(Micros end);
  void schedule(Micros t, QueuedEvent::Kind kind, Id a = 0, Id b = 0, std::uint64_t generation = 0);
  void note(Id robot, TraceEvent::Kind kind, std::string label, std::string detail = {}, Id peer = kNone);
  void samplePoses();
  bool goalReached() const;
  void summarise();
  [[nodiscard]] double now() const { return toSeconds(now_); }

  const MissionTables& t_;
  const World& world_;
  const TaskLibrary& library_;
  const SimulationOptions& options_;
  StepObserver* observer_;
  SimTrace& trace_;
  std::vector<RobotRun> robots_;
  std::vector<Body> bodies_;
  std::vector<Pose> poses_;
  std::vector<bool> aliveFlags_;
  std::vector<std::string> teamNames_;  // per robot: its team's name (for behaviours that tell friend from foe)
  std::vector<std::int32_t> channel_;  // per topic: values queued on its reliable channel
  std::vector<std::int32_t> crashed_;  // per team
  std::priority_queue<QueuedEvent, std::vector<QueuedEvent>, std::greater<>> queue_;
  std::uint64_t seq_ = 0;
  Micros now_ = 0;
  RandomStream latency_, lossDraws_;
  std::vector<LinkLoss> links_;  // per (kind, receiver) link
  std::vector<std::int32_t> before_, after_;
  bool stopped_ = false;
  bool dirty_ = false;              // a step happened: blocked plans may go on
  std::uint64_t zeroTimeSteps_ = 0;  // steps since time last moved (a loop that never lets time pass is an error)
  bool outside_ = false;         // the run left the model's assumptions: conformance no longer claimed
  std::vector<Id> leaderNow_;    // per leader block: the robot believed leader (for the summary)
  std::vector<double> crashTime_;
  std::vector<std::int32_t> scratchA_, scratchB_;
  std::vector<std::uint8_t> scratchC_;
  std::vector<std::int32_t> varSlot_;  // per IR variable of kind Knows: the robot's knowledge slot
  // Replay: steps happen only as the counterexample says (no automatic mode defaults or takeovers),
  // and losses are what it chose.
  bool scripted_ = false;
  std::vector<Id> lastStep_;  // the rules of the last step taken
  int forcedLoss_ = -1;  // -1: the loss model decides; 0: delivered; 1: lost
  static constexpr std::uint64_t kNoForcedMask = ~std::uint64_t{0};
  std::uint64_t forcedHeartbeatLoss_ = kNoForcedMask;  // bit i: the heartbeat to candidate i is lost

  // Networked robot (team_node.cpp).
  const NodeLink* node_ = nullptr;
  std::vector<Micros> lastHeard_;              // per robot: when its last packet came
  PacketRefusals refusals_;
  std::vector<std::uint8_t> heard_, heardPreferred_;  // per leader block, since the last period: a heartbeat, one of a preferred leader
  std::uint64_t sequence_ = 0;
  std::vector<std::uint32_t> everyone_;  // every robot of the mission, for a multicast to all
  bool goalSeen_ = false;

  // ---- team_dataflow.cpp: each robot's static schedules, once per control period
  void stepDataflow();
  TeamDataflow dataflow_{t_, trace_.summary};  // last: built from the tables once the rest is
};

}  // namespace semo::runtime::detail
