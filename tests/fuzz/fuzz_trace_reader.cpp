// Fuzzes the trace reader (checker/trace_reader.hpp) on a fixed hand-written model with every kind
// of trace: invariants, a valid end (deadlocks), an update that can leave its range, a rule with two
// outcomes and an LTL property (lassos). Whatever it accepts is written back with traceToJson and
// must read again to the same steps. Seeds: `semo-verify check --json` of the model below, whole
// and one counterexample at a time (tests/fuzz/corpus/trace/, written by make_trace_seeds.py there),
// and tests/diagnostics/trace/*.json (whose models differ: they exercise the refusals).
#include <cstddef>
#include <cstdint>
#include <string>

#include "semo/checker/stepper.hpp"
#include "semo/checker/trace.hpp"
#include "semo/checker/trace_reader.hpp"
#include "semo/semantics/ir_text.hpp"

namespace {

constexpr const char* kModel = R"(semo-ir 1;
robots a b;
var c : 0..3 = 0 @robot(a);
var d : bool @robot(b);
var mode : 0..2 = 0 @values("idle busy done");
rule inc @robot(a) : c < 3 && mode == 0 -> c' = c + 1;
rule jump @robot(a) : c == 1 && d -> c' = c + 3;
rule coin @robot(b) @kind(environment) : mode == 0 -> 0.5 : d' = true, mode' = 1 + 0.5 : d' = false, mode' = 1;
rule finish @robot(b) : mode == 1 -> mode' = 2;
rule reset @robot(a) : c == 3 && mode == 2 -> c' = 0, mode' = 0;
invariant small : c < 3;
invariant calm : !(d && mode == 2);
valid_end : mode == 2 && c == 0;
property settles : eventually {mode == 2};
)";

const semo::checker::Stepper& stepper() {
  static const semo::checker::Stepper s = [] {
    semo::SourceManager sources;
    semo::DiagnosticEngine diags(sources);
    std::optional<semo::ir::Model> m = semo::ir::parseText(sources, sources.add("fuzz.ir", kModel), diags);
    if (!m) __builtin_trap();
    return semo::checker::Stepper(*m);
  }();
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const semo::checker::Stepper& s = stepper();
  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  semo::FileId file = sources.add("fuzz.json", std::string(reinterpret_cast<const char*>(data), size));
  semo::checker::TraceReadOptions options;
  options.property = size % 3 == 0 ? "" : size % 3 == 1 ? "small" : "modelError";
  std::optional<semo::checker::ReplayedTrace> t = semo::checker::readTrace(sources, file, s, diags, options);
  for (const semo::Diagnostic& d : diags.diagnostics()) (void)diags.format(d);
  if (!t) return 0;
  // What the reader accepted, written as the checker writes it, reads back to the same steps.
  const semo::checker::Trace trace = t->toTrace();
  (void)semo::checker::traceToText(s.model(), trace);
  semo::FileId again = sources.add("again.json", semo::checker::traceToJson(s.model(), trace));
  std::optional<semo::checker::ReplayedTrace> back = semo::checker::readTrace(sources, again, s, diags);
  if (!back || back->rules != t->rules || back->branches != t->branches || back->states != t->states) __builtin_trap();
  return 0;
}
