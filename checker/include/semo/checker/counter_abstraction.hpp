#pragma once
// Counting instead of listing robots (specs/ir.md, "Counter abstraction"): a team of robots that
// are one template (the same variables, rules and counts, renamed) is searched as how many robots
// are in each local state (a valuation of one robot's variables), each count being 0, 1, ...,
// K - 1 or "K or more". The cost no longer depends on the team's size: a swarm of 1,000 robots
// has as many abstract states as one of 20.
//
// Every run of the model is a run of the abstraction: a step of a robot in local state l to l'
// takes one from l's count and adds one to l''s ("K or more" less one may still be K or more, or
// K - 1). So an invariant that holds in every abstract state, and an LTL property with no fair
// accepting loop in the abstraction's product, hold on the model. Fairness carries over per local
// state: a robot that stays in l for ever with a group of its steps enabled must take one of them,
// so a loop on which l is occupied and the group enabled throughout must take a step of it from l,
// or a step out of l; and robots cannot leave l again and again unless others enter it again and
// again (the team is finite). An abstract violation may not be one of the model (a count of "K or
// more" cannot say when it reaches K - 1), so it is reported as undecided, never as a violation.
//
// Robots a property names on their own (all_turn_back's legged_0) are kept exactly, outside the
// counts. The counts of the team (T.at.P.k, T.holding.K.c) are recomputed from the abstract state
// through their definitions (Lowering::countDefinitions), which the translation maintains and the
// SMT engine proves inductive.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "semo/checker/explicit_search.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct CountingOptions {
  std::uint64_t maxStates = 2'000'000;  // abstract states (and product states per property)
  std::uint32_t threshold = 2;           // K: counts are exact below it
  std::function<void(const std::string&)> onPhase;  // "counting: all_turn_back", for progress lines
  // The model is a mission's translation, whose teams get counts from this many robots on (0: not
  // known to be). Then a proof covers every team size from there (CountingVerdict::everyTeamFrom).
  std::size_t countedTeamsFrom = 0;
};

struct CountingVerdict {
  std::string name;
  Verdict verdict = Verdict::Unknown;  // Proven or Unknown, never Violated
  std::string why;                     // Unknown: what the abstraction found or could not do
  std::vector<std::string> explicitRobots;  // kept outside the counts for this property
  std::uint64_t productStates = 0;     // LTL properties
  // Proven, on a mission's translation: the same abstraction, so the same proof, for a team of any
  // size N >= everyTeamFrom (specs/ir.md, "Counter abstraction"); 0 otherwise.
  std::size_t everyTeamFrom = 0;
};

struct CountingResult {
  bool applicable = false;
  std::string why;                 // not applicable: why
  std::size_t robots = 0;          // in the team
  std::size_t localStates = 0;     // distinct local states of a counted robot reached
  std::uint32_t threshold = 2;
  std::uint64_t states = 0;        // abstract states of the safety search
  std::uint64_t transitions = 0;
  std::vector<CountingVerdict> invariants;  // ir::Model::invariants, in order
  bool deadlockChecked = false;             // the model has a valid end
  CountingVerdict deadlock;                 // deadlock_freedom
  std::vector<CountingVerdict> properties;  // ir::Model::properties, in order
  double seconds = 0;
  [[nodiscard]] bool allProven() const;
};

// The model with the definitions of its counts; not applicable unless the model is one team of
// interchangeable robots reading each other only through the counts.
CountingResult checkByCounting(const ir::Model& model, const std::vector<ir::Expr>& countDefinitions, const CountingOptions& options = {});

}  // namespace semo::checker
