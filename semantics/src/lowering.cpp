#include "semo/semantics/lowering.hpp"

namespace semo::lowering {

const char* roleName(VariableRole::Kind kind) {
  switch (kind) {
    case VariableRole::Kind::Alive: return "alive";
    case VariableRole::Kind::Crashed: return "crashed";
    case VariableRole::Kind::Mode: return "mode";
    case VariableRole::Kind::Pc: return "pc";
    case VariableRole::Kind::Event: return "event";
    case VariableRole::Kind::View: return "view";
    case VariableRole::Kind::Message: return "message";
    case VariableRole::Kind::Channel: return "channel";
    case VariableRole::Kind::Leads: return "leads";
    case VariableRole::Kind::Silence: return "silence";
    case VariableRole::Kind::LostHeartbeats: return "lost";
    case VariableRole::Kind::Knows: return "knows";
    case VariableRole::Kind::Holding: return "holding";
    case VariableRole::Kind::AtPoints: return "at points";
  }
  return "?";
}

const char* meaningName(RuleMeaning::Kind kind) {
  switch (kind) {
    case RuleMeaning::Kind::ProgramStep: return "program step";
    case RuleMeaning::Kind::ModeDefault: return "mode default";
    case RuleMeaning::Kind::Discover: return "discover";
    case RuleMeaning::Kind::Learn: return "learn";
    case RuleMeaning::Kind::EventDelivery: return "event delivery";
    case RuleMeaning::Kind::EventLoss: return "event loss";
    case RuleMeaning::Kind::MessageDelivery: return "message delivery";
    case RuleMeaning::Kind::MessageLoss: return "message loss";
    case RuleMeaning::Kind::Crash: return "crash";
    case RuleMeaning::Kind::HeartbeatPeriod: return "heartbeat period";
    case RuleMeaning::Kind::Takeover: return "takeover";
  }
  return "?";
}

}  // namespace semo::lowering
