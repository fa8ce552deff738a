#pragma once
// Which rules a run can take infinitely often: a loop's steps, once the steps that can happen only
// finitely often are known (specs/ir.md, "Rules that cannot recur").
//
// Why: a fair loop of a settling world takes no crash, no discovery of a fact, no decision of a
// sensed condition the other way, and, in turn, no step that only such steps make possible again:
// an event nobody throws any more is delivered at most once more. A slice that has dropped the
// event's flag cannot see that, and its fair loops deliver it for ever (a spurious lasso, a
// refinement round, a larger slice). The model can: this analysis looks at small parts of it
// (one variable, or one robot's control variables), explores each whole, and finds the steps that
// always change that part along an edge on no cycle of what the allowed rules can do to it. Such
// a step happens finitely often on every run whose loop takes only allowed rules: the part's
// values on the run's end walk only on cycles. Removing it, the cycles of other parts may break in
// turn, to a fixpoint.
#include <cstdint>
#include <functional>
#include <vector>

#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

class RecurringRules {
 public:
  // Explores the parts of `model` (its rules marked in `neverFires` left out): one slice per
  // variable and one per robot's control variables, each small. A part whose slice reaches more
  // than `maxStatesPerPart` states is skipped (it narrows nothing).
  explicit RecurringRules(const ir::Model& model, const std::vector<char>& neverFires = {},
                          std::uint64_t maxStatesPerPart = 1u << 20);

  // Of the rules `allowed` marks (one entry per model rule), those a run can take infinitely often
  // when, from some point on, it takes only rules `allowed` marks.
  [[nodiscard]] std::vector<char> narrow(std::vector<char> allowed) const;

  [[nodiscard]] std::size_t parts() const { return parts_.size(); }

 private:
  struct Edge {
    std::uint32_t from, to, rule;
  };
  struct Part {
    std::uint32_t states = 0;
    std::vector<Edge> edges;
    std::vector<std::uint32_t> rules;  // the model rules the part's slice keeps
  };
  std::vector<Part> parts_;
  std::size_t modelRules_ = 0;
};

// The same for a model cut from it (a slice or a cone, whose rule j is the model's rule
// fromRules[j]): every run of the model seen through the cut one ends in a loop of the cut one
// that takes only steps of rules the model can repeat (rules the cut model left out are stutters).
class LoopNarrowing {
 public:
  LoopNarrowing(const RecurringRules& recurring, const ir::Model& model, std::vector<std::uint32_t> fromRules)
      : recurring_(recurring), model_(model), fromRules_(std::move(fromRules)) {}

  // Per rule of the cut model: whether a loop may take it, when a loop decides each sensed
  // condition only in the ways `senses` lets it (the world searched).
  [[nodiscard]] std::vector<char> loopRules(const std::function<bool(const ir::SensedOutcome&)>& senses) const;

 private:
  const RecurringRules& recurring_;
  const ir::Model& model_;
  std::vector<std::uint32_t> fromRules_;
};

}  // namespace semo::checker::detail
