#pragma once
// Which facts a trace's knowledge counts hold. The model counts a robot's facts of a knowledge item
// (specs/semantics.md, "Knowledge") and leaves out which ones; a trace names them where the mission
// does (the strategy's `<knowledge values="...">`) by one assignment of facts that fits every count
// on the way: a fact found is one nobody holds yet when there is one (else one the finder lacks),
// a fact learnt comes from the robot the step learns from. The counts alone decide the run; the
// names are an illustration of it, and the trace says so.
#include <string>
#include <vector>

#include "semo/checker/trace.hpp"

namespace semo::checker::detail {

struct KnowledgeWitness {
  // For step i and its change j: the facts held after the change, when the variable counts facts.
  std::vector<std::vector<std::vector<std::string>>> held;
  // false when no change counts facts, or when the choices above found no assignment (a learner
  // would need more facts than the teacher has that it lacks): then no fact is named.
  bool named = false;
};

KnowledgeWitness knowledgeWitness(const ir::Model& model, const Trace& trace);

}  // namespace semo::checker::detail
