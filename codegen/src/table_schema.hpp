#pragma once
// The runtime's tables (runtime/tables.hpp, runtime/dataflow_tables.hpp) described once, field by
// field in declaration order, for the three things that walk them: the C++ writer of `emit`, the
// reader of `certify`, and the comparison that says where two tables first differ. A field missing
// here would be missing from all three alike; the round-trip test (every projected table written,
// read back and compared with the struct's own operator==) catches that.
//
// describe(v, x) calls v.field("name", x.member) for every member; enumNames<E>() gives each enum's
// values in order, with the qualified name the generated code writes.
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "semo/runtime/tables.hpp"

namespace semo::codegen::schema {

using namespace semo::runtime;

template <class E>
struct EnumInfo;  // qualified: the C++ name of the enum type; names: its values in order

#define SEMO_ENUM(Type, Qualified, ...)                                      \
  template <>                                                               \
  struct EnumInfo<Type> {                                                   \
    static constexpr std::string_view qualified = Qualified;                \
    static constexpr auto names = std::to_array<std::string_view>({__VA_ARGS__}); \
  };

SEMO_ENUM(SensedValueTable::Domain, "SensedValueTable::Domain", "Bool", "Threshold", "Enum", "Range")
SEMO_ENUM(Operand::Kind, "Operand::Kind", "Number", "Symbol", "Sensed", "View", "Facts")
SEMO_ENUM(CondNode::Kind, "CondNode::Kind", "Compare", "Test", "Not", "And", "Or")
SEMO_ENUM(CondNode::Rel, "CondNode::Rel", "Lt", "Le", "Gt", "Ge", "Eq", "Ne")
SEMO_ENUM(ActionRow::Kind, "ActionRow::Kind", "Call", "Wait", "Sense", "Test", "LoopStart")
SEMO_ENUM(GuardRow::Kind, "GuardRow::Kind", "InMode", "ChannelSpace", "ChannelData", "GroupStarted", "BlockClear", "Elected",
          "NotElected", "Goal")
SEMO_ENUM(EffectRow::Kind, "EffectRow::Kind", "Throw", "EnterMode", "Publish", "Send", "Receive", "Elect", "JoinArm", "LeaveBlock")
SEMO_ENUM(AbstractVar::Kind, "AbstractVar::Kind", "Alive", "Crashed", "Mode", "Pc", "Event", "View", "Message", "Channel", "Leads",
          "Silence", "LostHeartbeats", "Knows", "Holding", "AtPoints")
SEMO_ENUM(DataflowTask::Kind, "DataflowTask::Kind", "Service", "Sensing", "Control", "Communication", "Knowledge", "LeaderElection")
#undef SEMO_ENUM

template <class V> void describe(V& v, SensedValueTable& x) {
  v.field("name", x.name), v.field("domain", x.domain), v.field("thresholds", x.thresholds), v.field("symbols", x.symbols);
}
template <class V> void describe(V& v, Operand& x) {
  v.field("kind", x.kind), v.field("number", x.number), v.field("text", x.text), v.field("index", x.index);
}
template <class V> void describe(V& v, CondNode& x) {
  v.field("kind", x.kind), v.field("rel", x.rel), v.field("lhs", x.lhs), v.field("rhs", x.rhs), v.field("left", x.left),
      v.field("right", x.right);
}
template <class V> void describe(V& v, CallTable& x) { v.field("service", x.service), v.field("args", x.args), v.field("origin", x.origin); }
template <class V> void describe(V& v, ActionRow& x) {
  v.field("kind", x.kind), v.field("index", x.index), v.field("seconds", x.seconds), v.field("expect", x.expect);
}
template <class V> void describe(V& v, GuardRow& x) {
  v.field("kind", x.kind), v.field("index", x.index), v.field("plan", x.plan), v.field("count", x.count);
}
template <class V> void describe(V& v, EffectRow& x) {
  v.field("kind", x.kind), v.field("index", x.index), v.field("arm", x.arm), v.field("team", x.team), v.field("value", x.value);
}
template <class V> void describe(V& v, Row& x) {
  v.field("from", x.from), v.field("to", x.to), v.field("changesMode", x.changesMode), v.field("actions", x.actions),
      v.field("guards", x.guards), v.field("effects", x.effects), v.field("irRule", x.irRule);
}
template <class V> void describe(V& v, PlanPoint& x) {
  v.field("controlPoint", x.controlPoint), v.field("loopPeriod", x.loopPeriod), v.field("loopHead", x.loopHead),
      v.field("service", x.service), v.field("work", x.work), v.field("label", x.label);
}
template <class V> void describe(V& v, PlanTable& x) {
  v.field("name", x.name), v.field("points", x.points), v.field("rows", x.rows), v.field("firstRow", x.firstRow);
}
template <class V> void describe(V& v, ModeTable& x) {
  v.field("name", x.name), v.field("entry", x.entry), v.field("catches", x.catches), v.field("defaultTarget", x.defaultTarget),
      v.field("keepsLeaders", x.keepsLeaders);
}
template <class V> void describe(V& v, EventTable& x) {
  v.field("name", x.name), v.field("reliable", x.reliable), v.field("retransmissions", x.retransmissions), v.field("lossy", x.lossy);
}
template <class V> void describe(V& v, TeamTable& x) {
  v.field("name", x.name), v.field("robots", x.robots), v.field("plans", x.plans), v.field("modes", x.modes),
      v.field("initialMode", x.initialMode), v.field("events", x.events), v.field("crashBudget", x.crashBudget);
}
template <class V> void describe(V& v, TopicTable& x) {
  v.field("name", x.name), v.field("owner", x.owner), v.field("symbols", x.symbols), v.field("reliable", x.reliable),
      v.field("capacity", x.capacity), v.field("lossy", x.lossy), v.field("subscribers", x.subscribers);
}
template <class V> void describe(V& v, ServiceTable& x) { v.field("name", x.name), v.field("plan", x.plan); }
template <class V> void describe(V& v, KnowledgeTable& x) {
  v.field("service", x.service), v.field("name", x.name), v.field("team", x.team), v.field("facts", x.facts),
      v.field("newest", x.newest), v.field("shared", x.shared), v.field("reliable", x.reliable), v.field("period", x.period),
      v.field("retransmissions", x.retransmissions), v.field("lossy", x.lossy);
}
template <class V> void describe(V& v, ArmTable& x) {
  v.field("label", x.label), v.field("leader", x.leader), v.field("others", x.others), v.field("entry", x.entry),
      v.field("first", x.first), v.field("end", x.end), v.field("candidates", x.candidates);
}
template <class V> void describe(V& v, GroupBlockTable& x) {
  v.field("name", x.name), v.field("team", x.team), v.field("plan", x.plan), v.field("first", x.first),
      v.field("formPoint", x.formPoint), v.field("exit", x.exit), v.field("arms", x.arms), v.field("leader", x.leader);
}
template <class V> void describe(V& v, LeaderBlockTable& x) {
  v.field("name", x.name), v.field("block", x.block), v.field("candidates", x.candidates), v.field("preference", x.preference),
      v.field("heartbeat", x.heartbeat), v.field("timeoutPeriods", x.timeoutPeriods), v.field("detectsFailures", x.detectsFailures),
      v.field("lossyHeartbeats", x.lossyHeartbeats), v.field("lossBurst", x.lossBurst), v.field("leaderArm", x.leaderArm),
      v.field("othersArm", x.othersArm), v.field("heartbeatRule", x.heartbeatRule);
}
template <class V> void describe(V& v, DriveGeometry& x) {
  v.field("wheeled", x.wheeled), v.field("wheelRadius", x.wheelRadius), v.field("wheelSeparation", x.wheelSeparation),
      v.field("maxSpeed", x.maxSpeed), v.field("maxTurnRate", x.maxTurnRate);
}
template <class V> void describe(V& v, DataflowTask& x) {
  v.field("name", x.name), v.field("kind", x.kind), v.field("implements", x.implements), v.field("execMicros", x.execMicros);
}
template <class V> void describe(V& v, DataflowChannel& x) {
  v.field("name", x.name), v.field("from", x.from), v.field("to", x.to), v.field("control", x.control), v.field("capacity", x.capacity);
}
template <class V> void describe(V& v, ScenarioTable::Firing& x) { v.field("task", x.task), v.field("repetitions", x.repetitions); }
template <class V> void describe(V& v, ScenarioTable::Channel& x) {
  v.field("channel", x.channel), v.field("from", x.from), v.field("to", x.to), v.field("production", x.production),
      v.field("consumption", x.consumption), v.field("initialTokens", x.initialTokens), v.field("capacity", x.capacity);
}
template <class V> void describe(V& v, ScenarioTable& x) {
  v.field("name", x.name), v.field("mode", x.mode), v.field("modeIndex", x.modeIndex), v.field("services", x.services),
      v.field("planServices", x.planServices), v.field("schedule", x.schedule), v.field("channels", x.channels),
      v.field("periodNum", x.periodNum), v.field("periodDen", x.periodDen), v.field("period", x.period), v.field("proven", x.proven),
      v.field("notProven", x.notProven);
}
template <class V> void describe(V& v, RemotePortTable& x) {
  v.field("task", x.task), v.field("port", x.port), v.field("output", x.output), v.field("multicast", x.multicast),
      v.field("group", x.group), v.field("buffer", x.buffer), v.field("peers", x.peers);
}
template <class V> void describe(V& v, DataflowTable& x) {
  v.field("tasks", x.tasks), v.field("channels", x.channels), v.field("scenarios", x.scenarios), v.field("remotePorts", x.remotePorts);
}
template <class V> void describe(V& v, RobotTable::Discover& x) {
  v.field("knowledge", x.knowledge), v.field("plan", x.plan), v.field("pc", x.pc), v.field("rule", x.rule), v.field("started", x.started);
}
template <class V> void describe(V& v, RobotTable& x) {
  v.field("name", x.name), v.field("type", x.type), v.field("team", x.team), v.field("indexInTeam", x.indexInTeam),
      v.field("geometry", x.geometry), v.field("plans", x.plans), v.field("leaderBlocks", x.leaderBlocks),
      v.field("knowledge", x.knowledge), v.field("crashRule", x.crashRule), v.field("eventDeliveryRule", x.eventDeliveryRule),
      v.field("eventLossRule", x.eventLossRule), v.field("messageDeliveryRule", x.messageDeliveryRule),
      v.field("messageLossRule", x.messageLossRule), v.field("defaultRule", x.defaultRule), v.field("takeoverRule", x.takeoverRule),
      v.field("discoverRules", x.discoverRules), v.field("learnRule", x.learnRule), v.field("dataflow", x.dataflow);
}
template <class V> void describe(V& v, AbstractVar& x) {
  v.field("kind", x.kind), v.field("robot", x.robot), v.field("team", x.team), v.field("index", x.index), v.field("init", x.init),
      v.field("values", x.values), v.field("name", x.name);
}
template <class V> void describe(V& v, RuleInfo& x) {
  v.field("name", x.name), v.field("label", x.label), v.field("origin", x.origin), v.field("robot", x.robot);
}
template <class V> void describe(V& v, Assumptions& x) {
  v.field("losePublish", x.losePublish), v.field("loseEvents", x.loseEvents), v.field("loseKnowledge", x.loseKnowledge),
      v.field("loseHeartbeats", x.loseHeartbeats), v.field("lossBurst", x.lossBurst), v.field("words", x.words);
}
// The mission's shared tables; `robots` holds each robot's identity only (its step tables are in its
// own file): see robotIdentity().
template <class V> void describe(V& v, MissionTables& x) {
  v.field("teams", x.teams), v.field("robots", x.robots), v.field("services", x.services), v.field("topics", x.topics),
      v.field("sensed", x.sensed), v.field("conditions", x.conditions), v.field("calls", x.calls), v.field("pcSets", x.pcSets),
      v.field("knowledge", x.knowledge), v.field("groupBlocks", x.groupBlocks), v.field("leaderBlocks", x.leaderBlocks),
      v.field("abstraction", x.abstraction), v.field("rules", x.rules), v.field("assumptions", x.assumptions),
      v.field("modelFingerprint", x.modelFingerprint);
}

// ------------------------------------------------------------------ values as C++ (writer and comparison)

template <class T> struct IsVector : std::false_type {};
template <class T> struct IsVector<std::vector<T>> : std::true_type {};
template <class T> struct IsPair : std::false_type {};
template <class A, class B> struct IsPair<std::pair<A, B>> : std::true_type {};

// A string literal: C escapes, and three octal digits for other control bytes (unlike \x, an octal
// escape never swallows the character after it).
inline std::string quote(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (u < 0x20 || u == 0x7f) {
          out += '\\';
          out += static_cast<char>('0' + ((u >> 6) & 7));
          out += static_cast<char>('0' + ((u >> 3) & 7));
          out += static_cast<char>('0' + (u & 7));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// The shortest text that reads back as exactly `d`.
inline std::string number(double d) {
  if (!std::isfinite(d)) throw std::invalid_argument("a table holds a number that is not finite");
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, d);
  return std::string(buffer, end);
}

// A scalar (or a pair of them) as the generated code writes it.
template <class T> std::string scalarText(const T& x) {
  if constexpr (std::is_same_v<T, bool>) {
    return x ? "true" : "false";
  } else if constexpr (std::is_enum_v<T>) {
    using Info = EnumInfo<T>;
    const auto i = static_cast<std::size_t>(x);
    return std::string(Info::qualified) + "::" + std::string(i < Info::names.size() ? Info::names[i] : "?");
  } else if constexpr (std::is_same_v<T, Id>) {
    return x == kNone ? "kNone" : std::to_string(x);
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(x);
  } else if constexpr (std::is_floating_point_v<T>) {
    return number(x);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return quote(x);
  } else {
    static_assert(IsPair<T>::value, "a scalar or a pair");
    return "{" + scalarText(x.first) + ", " + scalarText(x.second) + "}";
  }
}

// What the mission file keeps of a robot: who it is (name, type, team, place in the team, body);
// the rest of its table is in robots/NAME/tables.cpp.
inline RobotTable robotIdentity(const RobotTable& r) {
  RobotTable out;
  out.name = r.name;
  out.type = r.type;
  out.team = r.team;
  out.indexInTeam = r.indexInTeam;
  out.geometry = r.geometry;
  return out;
}

}  // namespace semo::codegen::schema
