#pragma once
// The elaborated mission: every name resolved, robots expanded, group conditions turned into
// candidate sets, the strategy and robot catalog attached. This is what the IR translation, the
// task-graph generator and the code generator read; none of them looks at the AST again.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "semo/frontend/robot_catalog.hpp"
#include "semo/frontend/strategy.hpp"

namespace semo::model {

using Index = std::uint32_t;
inline constexpr Index kNone = 0xffffffffu;

struct Robot {
  std::string name;
  Index team = kNone;
  std::string type;     // robot type name (in the catalog)
  Index indexInTeam = 0;
  SourceRange declaredAt;
};

enum class ValueKind { Sensed, Topic, Knowledge };

struct Expr {
  enum class Kind { Int, Number, String, Bool, Symbol, Value };
  Kind kind = Kind::Int;
  std::int64_t intValue = 0;
  double numberValue = 0;
  std::string text;            // String, Symbol
  Index owner = kNone;         // Value: team index
  std::string var;             // Value
  ValueKind valueKind = ValueKind::Sensed;
  Index topic = kNone;         // Value of kind Topic: index into MissionModel::topics
  SourceRange at;
};

enum class RelOp { Lt, Le, Gt, Ge, Eq, Ne };

struct Cond {
  enum class Kind { Compare, Test, Not, And, Or };
  Kind kind = Kind::Test;
  RelOp op = RelOp::Eq;
  Expr lhs, rhs;
  std::unique_ptr<Cond> left, right;
  SourceRange at;
};

struct Stmt {
  enum class Kind {
    CallPrimitive,     // a strategy primitive service
    CallGroupService,  // a strategy group service
    CallComposite,     // a composite service of the same team (runs inline)
    Throw,
    Loop,
    If,
    Publish,
    Subscribe,
    Send,
    Receive,
    Wait,
    Groups,  // a [[ ]] block: see MissionModel::groupBlocks[groupBlock]
  };
  Kind kind = Kind::CallPrimitive;
  SourceRange at;
  std::string service;          // calls: the name called
  Index composite = kNone;      // CallComposite
  Index strategyService = kNone;  // CallPrimitive, CallGroupService: index into the strategy's services
  std::vector<Expr> args;       // calls
  Index event = kNone;          // Throw: index into the team's events
  std::int64_t durationMillis = 0;  // Loop, Wait
  std::unique_ptr<Cond> cond;   // If
  std::vector<Stmt> thenBody, elseBody;
  Index peerTeam = kNone;       // Publish/Send: destination; Subscribe/Receive: source
  Index topic = kNone;          // communication statements
  Expr value;                   // Publish/Send
  Index groupBlock = kNone;     // Groups
};

struct GroupArm {
  enum class Kind { Group, Leader, Others };
  Kind kind = Kind::Group;
  bool byCapability = false;        // capable of (all) vs instance of (any)
  std::vector<std::string> names;   // robot types or capabilities
  std::vector<Index> candidates;    // robots that may take this arm
  std::vector<Stmt> body;
  SourceRange at;
};

struct LeaderConfig {
  strategy::LeaderSelection::Algorithm algorithm = strategy::LeaderSelection::Algorithm::LowestId;
  std::int64_t heartbeatMillis = 1000;
  std::int64_t timeoutMillis = 3000;
  bool fromStrategy = false;
  bool detectsFailures = true;  // false: a new leader only when the group forms (reelection="formation")
  bool keptAcrossModes = false;  // on-mode-change="keep": a leader whose new mode runs the service goes on leading
};

struct GroupBlock {
  Index team = kNone;
  Index service = kNone;  // the composite service holding the block
  bool isLeaderBlock = false;
  std::vector<GroupArm> arms;
  LeaderConfig leader;     // isLeaderBlock only
  SourceRange at;
};

struct Repeat {
  bool isPeriod = false;
  std::int64_t periodMillis = 0;
  std::unique_ptr<Cond> cond;
};

struct CompositeService {
  std::string name, plan;
  Index team = kNone;
  std::vector<Stmt> body;
  std::optional<Repeat> repeat;
  bool used = false;  // set in a mode or called from a used service
  SourceRange at;
};

struct PlanSetting {
  Index plan = kNone;  // index into the team's plans
  Index service = kNone;
  SourceRange at;
};

struct Transition {
  bool isDefault = false;
  Index event = kNone;  // catch: index into the team's events
  Index target = kNone;
  SourceRange at;
};

struct Mode {
  std::string name;
  Index team = kNone;
  std::vector<PlanSetting> settings;
  std::vector<Transition> transitions;
  bool reachable = false;
  SourceRange at;
};

struct Event {
  std::string name;
  std::vector<SourceRange> thrownAt;
  std::vector<SourceRange> caughtAt;
  strategy::EventDelivery delivery;
};

struct Team {
  std::string name;
  std::vector<Index> robots;
  std::vector<std::string> plans;
  std::vector<Index> services;
  std::vector<Index> modes;
  Index initialMode = kNone;
  std::vector<Event> events;
  SourceRange declaredAt;
};

struct Topic {
  Index owner = kNone;  // the team in Owner.var
  std::string var;
  bool reliable = false;  // written by send (reliable channel) rather than publish
  std::vector<std::string> symbols;  // the domain: strategy values, or constants written
  std::int64_t buffer = 1;
  bool written = false, read = false;
  SourceRange firstUse;
};

struct Assumptions {
  std::vector<std::int64_t> crashBudget;  // per team
  bool losePublish = false, loseEvents = false, loseKnowledge = false, loseHeartbeats = false;
  bool fairLoss = true;
  std::int64_t lossBurst = 1;  // at most this many consecutive losses on one link (heartbeats)
  // The chance that one copy of a message is lost, for the quantitative questions (`analyze`); the
  // qualitative model does not read it.
  std::optional<double> lossProbability;
  std::vector<std::string> checks;  // built-in properties to check (all of them if none named)
  bool checksListed = false;         // the verify block named them (a named one with nothing to check is reported vacuous)
};

struct Ltl {
  enum class Kind { Atom, Not, Always, Eventually, Next, And, Or, Until, Implies };
  enum class Subject { Team, Robot };
  enum class Attribute { Mode, Alive, Leader, Value };
  Kind kind = Kind::Atom;
  Subject subject = Subject::Team;
  Index subjectIndex = kNone;
  Attribute attribute = Attribute::Value;
  std::string var;                  // Value
  ValueKind valueKind = ValueKind::Sensed;
  std::optional<RelOp> op;
  Expr rhs;                          // constant compared with
  Index mode = kNone;                // Mode atoms: the mode compared with
  std::unique_ptr<Ltl> left, right;
  SourceRange at;
};

struct Property {
  std::string name;
  std::unique_ptr<Ltl> formula;
  SourceRange at;
};

struct MissionModel {
  std::vector<Team> teams;
  std::vector<Robot> robots;
  std::vector<CompositeService> services;
  std::vector<Mode> modes;
  std::vector<GroupBlock> groupBlocks;
  std::vector<Topic> topics;
  Assumptions assumptions;
  std::vector<Property> properties;
  strategy::Strategy strategy;
  RobotCatalog catalog;

  [[nodiscard]] Index findTeam(const std::string& name) const;
  [[nodiscard]] Index findRobot(const std::string& name) const;
  [[nodiscard]] Index findService(Index team, const std::string& name) const;
  [[nodiscard]] Index findMode(Index team, const std::string& name) const;
  [[nodiscard]] Index findTopic(Index owner, const std::string& var) const;
  // The strategy's definition of the service a call statement names (resolved by elaboration).
  [[nodiscard]] const strategy::Service& serviceOf(const Stmt& call) const { return strategy.services.at(call.strategyService); }
  // Its implementation for `robot`'s type, or null.
  [[nodiscard]] const strategy::Implementation* implementationOf(const Stmt& call, Index robot) const {
    return serviceOf(call).implementationFor(robots.at(robot).type);
  }
  // How many robots of its own an arm needs for its block to form: one, or the largest `min-robots`
  // of the group services its body calls (through composite services too). What group formation
  // means, for the translation's invariants and for the crash-set analysis alike.
  [[nodiscard]] std::int64_t armDemand(const GroupArm& arm) const;
  // Whether a leader of the leader block goes on leading when its robot enters the mode: the
  // strategy keeps the leadership across modes (on-mode-change="keep") and the mode sets the
  // block's service again. The translation and the runtime's tables both follow it.
  [[nodiscard]] bool keepsLeadership(Index block, Index mode) const;
};

}  // namespace semo::model
