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

std::string traceToText(const ir::Model& model, const Trace& trace);
std::string traceToJson(const ir::Model& model, const Trace& trace);

}  // namespace semo::checker
