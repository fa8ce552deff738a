#pragma once
// Safety on the IR with Z3 (checker/src/smt_encoding.hpp has the encoding): bounded model checking
// finds every violation reachable within K steps, with a shortest counterexample in the explicit
// engine's trace format; k-induction then tries to prove what was not violated for every depth, and
// IC3 (Z3's Spacer, checker/src/smt_ic3.hpp) what k-induction could not: it finds a strengthening
// invariant, checked independently before the property counts as proven, or a deeper
// counterexample, rebuilt by BMC at its depth. Anything else is reported unknown, bounded.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "semo/checker/explicit_search.hpp"

namespace semo::checker {

struct SmtOptions {
  std::uint32_t maxDepth = 5;   // K: BMC explores every path of up to K steps; induction tries k <= K + 1
  bool induction = true;        // k-induction after BMC
  std::uint32_t maxInduction = 3;  // induction tries k <= min(K + 1, this)
  bool ic3 = true;              // IC3 on what k-induction leaves open
  unsigned timeoutMs = 0;       // per solver call (an IC3 run is one call); 0: none
  // State predicates the model's maker claims hold in every reachable state: the definitions of a
  // large team's counts (Lowering::countDefinitions). Each is used only once proven: it holds
  // initially and the proven ones together are kept by every step. Then k-induction and IC3 assume
  // them in every state, which they could not find themselves (a sum over the team's robots).
  std::vector<ir::Expr> lemmas;
  // Told what the engine is doing as each phase starts (a BMC depth, an induction k, an IC3 run),
  // for progress lines; may be empty.
  std::function<void(const std::string&)> onPhase;
  // Called once, on the calling thread, as soon as the engine knows that no update leaves a
  // declared range (they hold initially, and every step keeps them, or an induction or IC3 proved
  // them): no range error exists at any depth, so the model is well formed and what needs only
  // that (the LTL properties' search, verify.cpp) may start beside the proofs. Not called when a
  // range error is found or the ranges stay unproven; may be empty.
  std::function<void()> onRangesHold;
};

// How a property was decided, beside its verdict.
enum class SmtProof : std::uint8_t {
  None,       // not proven
  Exhausted,  // BMC found no path longer than bmcDepth: every reachable state was checked
  Induction,  // k-induction at inductionDepth
  Ic3,        // IC3 found an inductive strengthening (invariantConjuncts), checked independently
};

struct SmtResult {
  SearchResult search;                            // properties as the explicit engine reports them
  std::vector<SmtProof> proof;                    // per property
  std::vector<std::uint32_t> inductionDepth;      // per property: k of its induction, or 0
  std::vector<std::uint32_t> invariantConjuncts;  // per property proven by IC3
  std::vector<char> deepCounterexample;           // per property: violated beyond bmcDepth (found by IC3)
  std::uint32_t bmcDepth = 0;                     // every path of up to this many steps was covered
  std::string note;                               // why an unbounded proof stopped, if one did
  std::size_t lemmasProven = 0;                   // of SmtOptions::lemmas (all or none are used)
};

SmtResult checkSafetySmt(const ir::Model& model, const SmtOptions& options);

}  // namespace semo::checker
