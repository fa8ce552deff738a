#pragma once
// Reads a counterexample back: the output of `semo-verify check --json` (one of its
// counterexamples) or a single counterexample object (specs/trace.md), resolved against a model by
// replaying it with a Stepper from the initial state. Every step must name a rule of the model that
// is enabled in the state reached and that leads to the state the step records; the trace must end
// as its kind says (an invariant violated, a deadlock, an update out of range, a lasso that closes).
// Every problem is a positioned diagnostic ("file:line:col: error: ...") at the JSON value at fault.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "semo/checker/stepper.hpp"
#include "semo/checker/trace.hpp"
#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct TraceReadOptions {
  // Which counterexample of a `check --json` output: the one of the property of this name, or
  // "modelError" for the model error. Empty: the first violated property in the file's order, else
  // the model error. Ignored for a file holding a single counterexample object.
  std::string property;
  // Compare the file's "modelFingerprint" (if it has one) with the model's: a mismatch is an error.
  // Fingerprints cover the origins' file paths (fingerprint.hpp); turn this off to replay a trace
  // on the same mission read through another path.
  bool checkFingerprint = true;
};

struct ReplayedTrace {
  enum class Kind { Invariant, Deadlock, ModelError, Lasso };
  std::string property;  // as the file names it ("" for a model error)
  Kind kind = Kind::Invariant;
  std::vector<std::size_t> rules;     // per step: its IR rule (index into ir::Model::rules)
  std::vector<std::size_t> branches;  // per step: the rule's outcome
  // states[0] is the initial state, states[k + 1] the state after step k (steps + 1 states). For a
  // model error the last one holds the value out of range.
  std::vector<Stepper::State> states;
  // Lassos: the 0-based step where the loop starts; steps.size() when the run stays in its last
  // state. SIZE_MAX otherwise. (The JSON's "loopStart" is 1-based.)
  std::size_t loopStart = SIZE_MAX;
  std::string fingerprint;  // the file's "modelFingerprint" ("" when it has none)

  // The checker's form (trace.hpp), e.g. for traceToText or traceToJson.
  [[nodiscard]] Trace toTrace() const;
};

// "invariant", "deadlock", "range" or "lasso", as in the JSON.
const char* traceKindName(ReplayedTrace::Kind kind);

// Reads `file` and replays the chosen counterexample on `stepper`'s model; nullopt (with errors in
// `diags`) on any problem. Never throws on bad input.
std::optional<ReplayedTrace> readTrace(const SourceManager& sources, FileId file, const Stepper& stepper, DiagnosticEngine& diags,
                                       const TraceReadOptions& options = {});
// The same, compiling the model first.
std::optional<ReplayedTrace> readTrace(const SourceManager& sources, FileId file, const ir::Model& model, DiagnosticEngine& diags,
                                       const TraceReadOptions& options = {});

}  // namespace semo::checker
