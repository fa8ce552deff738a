#include "semo/checker/replay_monitor.hpp"

#include <fmt/format.h>

namespace semo::checker {

std::vector<runtime::Id> ReplayMonitor::script(const ReplayedTrace& trace, std::size_t loops) {
  std::vector<runtime::Id> rules(trace.rules.begin(), trace.rules.end());
  if (trace.kind == ReplayedTrace::Kind::Lasso && trace.loopStart < trace.rules.size()) {
    for (std::size_t again = 1; again < loops; ++again) rules.insert(rules.end(), trace.rules.begin() + static_cast<std::ptrdiff_t>(trace.loopStart), trace.rules.end());
  }
  return rules;
}

ReplayMonitor::ReplayMonitor(const ir::Model& model, const runtime::MissionTables& tables, const ReplayedTrace& trace, std::size_t loops)
    : conformance_(model, tables, /*checkInvariants=*/false), stepper_(conformance_.stepper()), trace_(trace), script_(script(trace, loops)) {
  if (trace.kind == ReplayedTrace::Kind::Invariant) {
    for (std::size_t i = 0; i < model.invariants.size(); ++i) {
      if (model.invariants[i].name == trace.property) invariant_ = i;
    }
  }
}

std::size_t ReplayMonitor::traceStep(std::size_t k) const {
  const std::size_t n = trace_.rules.size();
  if (k < n || trace_.loopStart >= n) return k;
  return trace_.loopStart + (k - n) % (n - trace_.loopStart);
}

bool ReplayMonitor::fail(std::string why) {
  failed_ = true;
  why_ = std::move(why);
  return false;
}

bool ReplayMonitor::onStep(const runtime::StepReport& step) {
  const bool scripted = taken_ < script_.size();
  const std::size_t m = scripted ? traceStep(taken_) : 0;
  const bool outOfRange = scripted && trace_.kind == ReplayedTrace::Kind::ModelError && taken_ + 1 == script_.size();
  if (scripted) {
    const runtime::Id rule = script_[taken_];
    if (step.rules.size() != 1 || step.rules.front() != rule) {
      return fail(fmt::format("replay: step {}: the running team took another step ({}) where the counterexample takes {}", taken_ + 1,
                              step.what, stepper_.model().rules[rule].name));
    }
    if (outOfRange) {  // the step leaves a variable's range: the stepper has no successor, the team's state shows the value
      const Stepper::Outcome o = stepper_.apply(*step.before, {rule, trace_.branches[m]});
      if (!o.enabled || o.state != *step.after || o.outOfRange.empty()) {
        return fail(fmt::format("replay: step {}: the running team does not leave the range the counterexample leaves", taken_ + 1));
      }
      ++taken_;
      violatedAt_ = taken_;
      violation_ = "variable " + stepper_.model().variables[o.outOfRange.front()].name + " leaves its declared range";
      return true;
    }
  }
  if (!conformance_.onStep(step)) {
    return fail(scripted ? fmt::format("replay: step {}: {}", taken_ + 1, conformance_.why()) : "replay: after the counterexample's steps: " + conformance_.why());
  }
  if (!scripted) {
    if (!step.rules.empty()) ++freeSteps_;
    return true;
  }
  if (*step.after != trace_.states[m + 1]) {
    return fail(fmt::format("replay: step {}: the team is not in the counterexample's state\n  the trace: {}\n  the team:  {}", taken_ + 1,
                            stepper_.describe(trace_.states[m + 1]), stepper_.describe(*step.after)));
  }
  ++taken_;
  if (trace_.kind == ReplayedTrace::Kind::Lasso && trace_.loopStart < trace_.rules.size() && m + 1 == trace_.rules.size()) {
    loopClosedAt_.push_back(taken_);
  }
  if (invariant_ && !violatedAt_ && !stepper_.invariantHolds(*step.after, *invariant_)) {
    violatedAt_ = taken_;
    violation_ = "property " + trace_.property + " is violated";
    why_ = fmt::format("{} at step {} in the running team: {}", violation_, taken_, stepper_.describe(*step.after));
    return false;  // the run ends where the property fails, as the counterexample does
  }
  if (trace_.kind == ReplayedTrace::Kind::Deadlock && taken_ == script_.size() && stepper_.deadlocked(*step.after)) {
    violatedAt_ = taken_;
    violation_ = "no rule is enabled (deadlock)";
  }
  return true;
}

}  // namespace semo::checker
