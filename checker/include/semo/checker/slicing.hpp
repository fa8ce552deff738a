#pragma once
// Property-directed slicing: the model seen only through the variables a liveness property needs.
//
// A slice keeps a set V of variables (always those the property reads) and over-approximates the
// rest away (specs/ir.md, "Slicing"):
// - a rule that assigns no variable of V is left out: its steps change nothing the slice sees;
// - a guard that reads variables outside V is weakened to what V alone can tell (a condition on a
//   removed variable may hold or not), and the rule's fairness group loses its fairness, since the
//   slice cannot tell whether it stays enabled; so does a group with a rule left out, whose steps
//   the slice does not see taken;
// - an assignment to a variable of V whose new value reads removed variables becomes a choice
//   among the values it may take (the branches of a conditional, or the variable's whole range).
// Every fair run of the model, seen through V, is then a fair run of the slice (up to stuttering),
// so a property without `next` that holds on the slice holds on the model. A violation on the
// slice may not be real; sliced_liveness.cpp rebuilds it on the model, or refines V.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

struct Slice {
  ir::Model model;                    // the kept variables, the rules that assign them, one property
  std::vector<ir::VarId> variables;   // slice variable i is model variable variables[i]
  std::vector<std::uint32_t> rules;   // slice rule j comes from model rule rules[j]
  std::vector<char> exactGuard;       // per slice rule: its guard reads only kept variables
  std::vector<char> exactUpdates;     // per slice rule: every kept variable's new value reads only kept ones
  std::size_t leftOut = 0;            // model rules that assign no kept variable
  std::size_t neverFire = 0;          // model rules left out because no reachable state enables them
  std::size_t fairnessDropped = 0;    // fair model rules kept without their fairness
  bool tooCoarse = false;             // an update had too many possible values to enumerate
  std::vector<ir::VarId> coarseReads; // then, the removed variables it read (to keep next time)
};

// Marks in `mark` (one entry per model variable) every variable `e` reads.
void markVariablesRead(const ir::Expr& e, std::vector<char>& mark);
void markVariablesRead(const ir::Ltl& f, std::vector<char>& mark);
bool usesNext(const ir::Ltl& f);

// The slice of `model` for its property `property` (an index into Model::properties) keeping the
// variables marked in `keep` (one entry per model variable; the property's own are added). Rules
// marked in `neverFires` (rulesThatNeverFire) are left out, as their groups' members.
Slice sliceModel(const ir::Model& model, std::size_t property, std::vector<char> keep, const std::vector<char>& neverFires = {});

// The slice keeping the variables marked in `keep`, without a property (for analyses that explore
// it whole). Rules marked in `neverFires` are left out.
Slice sliceVariables(const ir::Model& model, const std::vector<char>& keep, const std::vector<char>& neverFires = {});

// `e` seen through a slice's variables: a condition on them (numbered as in the slice) that every
// state satisfying `e` satisfies, whatever the removed variables hold.
ir::Expr seenThrough(const ir::Expr& e, const Slice& slice, std::size_t modelVariables);

// What each robot's control variables (its mode, program counters and `alive`) can reach, and
// what follows for the rules: the slice keeping one robot's control variables is explored whole;
// its states include every reachable state of the model seen through them. Then
// - a rule whose guard, seen through them, holds in none of its states never fires (a `default`
//   transition out of a mode whose plans loop for ever);
// - a conjunct of a guard that holds in every such state where the rest of the guard may hold
//   is implied there (`pc.Report == 0` in RC_MODE, where the Report plan does not run) and is
//   dropped from `model`'s guards.
// Leaving the dead rules out of slices and cones, and slicing `model`, changes no run and no
// fairness (a rule never enabled is never owed a step; a guard changes only outside the reachable
// states), but keeps out of the cone the variables only those rules and conjuncts read.
// A robot's control variable: its mode, `alive`, or a program counter.
bool isControlVariable(const ir::Variable& v);

struct ControlFacts {
  std::vector<char> neverFires;   // per model rule
  ir::Model model;                // the model with the implied conjuncts dropped
  std::size_t droppedConjuncts = 0;
  std::size_t robotsSkipped = 0;  // robots whose control variables have too many combinations
};
ControlFacts controlFacts(const ir::Model& model, std::uint64_t maxStatesPerRobot = 1u << 22);

// The variables the property depends on: those it reads and, transitively, those read by the
// guard and the new values of every rule that assigns one of them. A slice keeping them all is
// exact: it drops only rules whose steps it cannot see, and weakens no guard or update.
std::vector<char> coneOfInfluence(const ir::Model& model, std::size_t property, const std::vector<char>& neverFires = {});

// Removes from a slice the crash and environment steps that no fairness asks for (a robot that
// crashes, a fact the world offers); returns how many. Every fair run of what is left is a fair
// run of the slice (the same fairness, fewer steps): a lasso found on it is one of the slice's,
// an under-approximation for hunting violations, never for proofs.
std::size_t withoutUnfairEnvironment(Slice& slice);

}  // namespace semo::checker
