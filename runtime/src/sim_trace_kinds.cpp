#include "semo/runtime/sim_trace.hpp"

namespace semo::runtime {

const char* eventKindName(TraceEvent::Kind kind) {
  switch (kind) {
    case TraceEvent::Kind::Step: return "step";
    case TraceEvent::Kind::Send: return "send";
    case TraceEvent::Kind::Deliver: return "deliver";
    case TraceEvent::Kind::Drop: return "drop";
    case TraceEvent::Kind::Crash: return "crash";
    case TraceEvent::Kind::Mode: return "mode";
    case TraceEvent::Kind::Role: return "role";
    case TraceEvent::Kind::Fact: return "fact";
    case TraceEvent::Kind::Note: return "note";
    case TraceEvent::Kind::Violation: return "violation";
  }
  return "?";
}

}  // namespace semo::runtime
