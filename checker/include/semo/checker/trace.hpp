#pragma once
// Counterexample traces: numbered steps, each with the robot, what it did, the mission line, and
// the variables it changed. Text for people, JSON for tools (specs/trace.md).
#include <cstdint>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct Change {
  ir::VarId var;
  std::int32_t before, after;
};

struct Step {
  std::size_t rule;    // index into Model::rules
  std::size_t branch;  // which outcome of a probabilistic rule
  std::vector<Change> changes;
};

struct Trace {
  std::string property;               // the property it violates
  std::string kind;                   // "invariant", "deadlock" or "range"
  std::vector<std::int32_t> initial;  // the initial state's values
  std::vector<Step> steps;
  std::size_t loopStart = SIZE_MAX;   // for lassos (liveness): the step where the loop begins
};

// A value as traces show it: true/false for a boolean, the value's name when the variable has one
// (modes, program points), else the number.
std::string valueText(const ir::Variable& v, std::int32_t value);

// Which facts a trace's knowledge counts hold. The model counts a robot's facts of a knowledge item
// (specs/semantics.md, "Knowledge") and leaves out which ones; a trace names them where the mission
// does (the strategy's `<knowledge values="...">`) by one assignment of facts that fits every count
// on the way: a fact found is one nobody holds yet when there is one (else one the finder lacks),
// a fact learnt comes from the robot the step learns from. The counts alone decide the run; the
// names are an illustration of it, and the trace says so.
struct KnowledgeWitness {
  // For step i and its change j: the facts held after the change, when the variable counts facts.
  std::vector<std::vector<std::vector<std::string>>> held;
  // false when no change counts facts, or when the choices above found no assignment (a learner
  // would need more facts than the teacher has that it lacks): then no fact is named.
  bool named = false;
};

KnowledgeWitness knowledgeWitness(const ir::Model& model, const Trace& trace);

std::string traceToText(const ir::Model& model, const Trace& trace);
std::string traceToJson(const ir::Model& model, const Trace& trace);

}  // namespace semo::checker
