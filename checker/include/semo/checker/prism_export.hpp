#pragma once
// The IR in the PRISM language, so that PRISM or Storm can re-check what the quantitative engine
// computes (specs/quantitative.md): one module holding every variable, one unsynchronised command
// per rule with its outcomes and their probabilities, a label per property and invariant, a reward
// structure counting steps, and a properties file asking what `analyze` answers.
#include <string>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct PrismModel {
  std::string model;       // the .pm file
  std::string properties;  // the .props file
  bool deterministic = false;  // written as a dtmc (else an mdp)
};

// `deterministic`: the model offers at most one rule in every reachable state (the caller knows,
// from markov.hpp); a dtmc then, an mdp otherwise. Names are made valid for PRISM (`a.b[1]` ->
// `a_b_1`, a PRISM keyword gets a `v_` in front, clashes a number), with the IR name in a comment.
PrismModel toPrism(const ir::Model& model, bool deterministic);

}  // namespace semo::checker
