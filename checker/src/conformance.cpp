#include "semo/checker/conformance.hpp"

#include <fmt/format.h>

namespace semo::checker {

ConformanceMonitor::ConformanceMonitor(const ir::Model& model, const runtime::MissionTables& tables, bool checkInvariants)
    : stepper_(model), tables_(tables), current_(stepper_.initial()), checkInvariants_(checkInvariants) {}

bool ConformanceMonitor::mismatch(const runtime::StepReport& step, const std::string& what, const Stepper::State& expected) {
  const std::string robot = step.robot < tables_.robots.size() ? tables_.robots[step.robot].name : std::string("the team");
  std::string rules;
  for (runtime::Id r : step.rules) rules += (rules.empty() ? "" : ", ") + tables_.rules[r].name;
  why_ = fmt::format("conformance: at {:.6f} s, {} ({}; {}): {}\n  the model:    {}\n  the team:     {}\n  differences (model -> team): {}", step.t,
                     robot, step.what, rules.empty() ? "no rule" : "rules " + rules, what, stepper_.describe(expected),
                     stepper_.describe(*step.after), stepper_.describeDifference(expected, *step.after));
  return false;
}

bool ConformanceMonitor::onStep(const runtime::StepReport& step) {
  if (*step.before != current_) return mismatch(step, "before this step the team was not where the model was", current_);
  Stepper::State s = *step.before;
  for (runtime::Id rule : step.rules) {
    if (!stepper_.enabled(s, rule)) return mismatch(step, "rule " + tables_.rules[rule].name + " is not enabled here", s);
    std::string why;
    std::optional<Stepper::State> next = stepper_.successor(s, rule, &why);
    if (!next) return mismatch(step, "rule " + tables_.rules[rule].name + " has no successor here: " + why, s);
    s = std::move(*next);
  }
  if (s != *step.after) {
    return mismatch(step, step.rules.empty() ? "a step outside the model changed what the model sees" : "the rules lead elsewhere", s);
  }
  for (std::size_t i = 0; checkInvariants_ && i < stepper_.model().invariants.size(); ++i) {
    if (!stepper_.invariantHolds(s, i)) {
      why_ = fmt::format("property {} is violated at {:.6f} s in the running team: {}", stepper_.model().invariants[i].name, step.t,
                         stepper_.describe(s));
      return false;
    }
  }
  current_ = std::move(s);
  return true;
}

}  // namespace semo::checker
